"""Benchmark: the realistic-sensor landing campaign's throughput, and its guidance's share.

The campaign is the shipped ``campaigns/falcon9-landing.yaml`` as users fly it: the
mission of ``scenarios/falcon9-leo.yaml`` until the booster is down, the upper stage
no further than its separation (``follow: [booster]``), ``sensors: realistic`` (both
flight programs read the navigation estimate), a random day per run. Target: 1 000
runs in at most 10 minutes on two workers of this 2-core machine, 1.2 s a run.

Printed (``pytest -s``), with the machine's load:

* the runs flown in this process (``workers=1``, warm-up excluded): runs per second,
  each run's wall time, and the process's CPU seconds a run (steadier than wall time
  on a shared machine), with the minutes 1 000 such runs would take on two workers
  that each got a core (the ideal: two workers on two cores get at most that);
* the guidance library's share of those runs: the CPU time (``time.thread_time`` of
  the thread calling it) spent in the library calls the shipped programs make --
  the landing-point predictions (``LandingPoint``), the boost-back's targeting
  (``boostback``), the descent's lean and entry-burn end (``descent``), the powered
  descent's command (``powered_descent.command``) and the ascent's PEG cycles
  (:mod:`rocketsim.guidance.peg`, as ``ascent.Insertion`` calls them) -- counting only
  the outermost call where one calls another; the baseline is the runs' own CPU,
  measured in the same runs;
* the baseline, the same runs without ``follow`` (the upper stage flown on to the
  mission's end, as the campaign flew before it followed the booster): CPU a run, and the
  shipped campaign's share of it; the booster's results must be the same in both;
* with ``ROCKETSIM_BENCH_FULL=1``, the campaign's throughput on a two-worker
  LocalCluster (from the first run's start to the last row, warm-up excluded)
  and the minutes 1 000 runs take at that rate.

In the suite SUITE_RUNS runs (a landing run is a long flight: two keep the suite
inside its budget); with ``ROCKETSIM_BENCH_FULL=1`` FULL_SERIAL_RUNS in this process
and FULL_CLUSTER_RUNS on the cluster. Nothing asserts a time: the checks are that
every run flew, its booster came down with a named outcome, the guidance was timed in
each run, and the booster's results are the same with the upper stage flown on.

Last figures (this 2-core machine, nothing else running, ``ROCKETSIM_BENCH_FULL=1``,
load 0.8-1.0): 1.07 s of CPU a run in one process (9.0 min for 1 000 runs on two ideal
workers), the guidance 0.18 s of it (17 %); the same runs with every body flown 1.44 s
(following the booster alone takes 0.75 of it); 2 workers 1.98 runs/s, 1 000 runs in
8.4 min. The whole campaign flown with ``--runs 1000 --workers 2`` on the same code took
9 min 07 s from the command to the last row (kernels compiled in its warm-up, load
about 2: its own two workers), 999 of 1 000 upright within 10 m. Before this round
(every body flown, the flip's plan ten times a second, the sample path and store as
they were): 1.96 s a run, 16.3 min. The runs' other CPU is the simulator's: its
compiled runs, the programs' readings and the sensors.
"""

from __future__ import annotations

import os
import threading
import time
from pathlib import Path

import numpy as np
import yaml

from rocketsim.campaigns.execute import run
from rocketsim.campaigns.landing import OUTCOMES
from rocketsim.guidance import ascent, boostback, descent, landing_point, powered_descent
from tests.benchmarks.timing import load_text

ROOT = Path(__file__).resolve().parents[2]
CAMPAIGN = ROOT / "campaigns" / "falcon9-landing.yaml"
FULL = os.environ.get("ROCKETSIM_BENCH_FULL") == "1"
SUITE_RUNS = 2
FULL_SERIAL_RUNS = 4
FULL_CLUSTER_RUNS = 16
BOOSTER = "booster"
TARGET_MINUTES = 10.0       # for 1 000 runs on two workers

# the library calls the shipped programs make, by the module (or class) they call them in
TIMED = ((landing_point.LandingPoint, "__call__"), (boostback, "velocity_to_gain"), (boostback, "after_burn"),
         (boostback, "burn_plane"), (descent, "solve_lean"), (descent, "entry_end_speed"),
         (powered_descent, "command"), (ascent, "cycle"), (ascent, "settle"), (ascent, "start"))


class GuidanceClock:
    """The CPU time (s) and the count of the outermost calls of TIMED, while installed."""

    def __init__(self):
        self.seconds, self.calls = 0.0, 0
        self._inside = threading.local()

    def wrap(self, function):
        def timed(*args, **kwargs):
            if getattr(self._inside, "depth", 0):
                return function(*args, **kwargs)
            self._inside.depth = 1
            start = time.thread_time()
            try:
                return function(*args, **kwargs)
            finally:
                self.seconds += time.thread_time() - start
                self.calls += 1
                self._inside.depth = 0
        return timed


def campaign_of(runs: int, every_body: bool = False) -> dict:
    """The shipped campaign, ``runs`` runs, no telemetry; ``every_body``: without its
    ``follow`` (the upper stage flown on past its separation, as before it had one)."""
    data = yaml.safe_load(CAMPAIGN.read_text())
    if every_body:
        data["overrides"] = {key: value for key, value in data["overrides"].items() if key != "follow"}
    return {**data, "runs": runs, "scenario": str((CAMPAIGN.parent / data["scenario"]).resolve()),
            "telemetry": "none"}


def flown(campaign: dict, directory: Path, clock: GuidanceClock | None = None, **executor):
    """``(results, runs per second, CPU s of this process a run)`` from the first run's start
    to the last row (the warm-up left out; ``clock`` started at the first run)."""
    marks = []

    def progress(done, failed, total):
        if not marks and clock is not None:
            clock.seconds, clock.calls = 0.0, 0
        marks.append((time.perf_counter(), time.process_time()))

    results = run(campaign, directory, progress=progress, **executor)
    (wall0, cpu0), (wall1, cpu1) = marks[0], marks[-1]
    return results, (len(marks) - 1) / (wall1 - wall0), (cpu1 - cpu0) / (len(marks) - 1)


def check(results):
    ok = (results["status"] == "ok").to_numpy()
    assert ok.all(), results.loc[~ok, ["run", "error"]]
    assert set(results[f"{BOOSTER}.landing.outcome"]) <= set(OUTCOMES)


def test_landing_campaign_throughput_and_the_guidance_share(tmp_path, monkeypatch):
    print(f"\nlanding campaign throughput ({load_text()})")
    clock = GuidanceClock()
    for owner, name in TIMED:
        monkeypatch.setattr(owner, name, clock.wrap(getattr(owner, name)))
    runs = FULL_SERIAL_RUNS if FULL else SUITE_RUNS
    results, rate, cpu = flown(campaign_of(runs), tmp_path / "serial", clock, workers=1)
    check(results)
    assert clock.calls > 0
    share = clock.seconds / runs / cpu
    walls = results["wall_time_s"].to_numpy()
    print(f"  in this process ({runs} runs): {rate:.2f} runs/s; a run's wall time {np.median(walls):.2f} s "
          f"(median; {walls.min():.2f}-{walls.max():.2f}), CPU {cpu:.2f} s a run (target 1.2 s)")
    print(f"  1 000 runs on two workers at this CPU a run, each worker a core: {1000 * cpu / 2 / 60:.1f} min "
          f"(target <= {TARGET_MINUTES:.0f} min)")
    print(f"  the guidance library: {clock.seconds / runs:.2f} s of CPU a run in {clock.calls // runs} calls, "
          f"{share:.0%} of the run's CPU ({load_text()})")
    monkeypatch.undo()
    every, _, every_cpu = flown(campaign_of(runs, every_body=True), tmp_path / "every body", workers=1)
    check(every)
    differ = [c for c in results.columns if c.startswith(f"{BOOSTER}.") and not results[c].equals(every[c])]
    assert not differ, differ              # the booster's flight is the same with the upper stage flown on
    print(f"  the same runs flying the upper stage on past its separation (no follow): CPU {every_cpu:.2f} s "
          f"a run; following the booster alone takes {cpu / every_cpu:.2f} of it ({load_text()})")
    if FULL:
        results, rate, _ = flown(campaign_of(FULL_CLUSTER_RUNS), tmp_path / "cluster", workers=2)
        check(results)
        print(f"  2 workers ({FULL_CLUSTER_RUNS} runs): {rate:.2f} runs/s, 1 000 runs in {1000 / rate / 60:.1f} min "
              f"(target <= {TARGET_MINUTES:.0f} min); a run's wall time on a worker "
              f"{results['wall_time_s'].median():.2f} s (median; {load_text()})")

