"""Benchmark: the sample path of a landing campaign's run, from the world to the samples kept.

A run of ``campaigns/falcon9-landing.yaml`` (run 0: realistic sensors, a random day) is flown
in memory as the campaign flies it, and every call its world makes to the sample watch
(:class:`rocketsim.sim.sample_watch.SampleWatch`: single samples, a compiled run's rows,
several bodies' interleaved blocks, the events that end a body's flight figures) is kept.
The calls are then made again on a fresh sample watch writing into a fresh in-memory
recorder (:class:`rocketsim.api.recorder.Recorder`), the flight figures asked at the end:

* as the flight made them (blocks), without and with the coast rule (the scenario's
  ``telemetry.coast_rate``, here 1 Hz: the booster's coasts above the air thinned);
* the baseline, in the same run: the same samples handed over one at a time
  (``SampleWatch.sample`` of each, in the order they are written).

Printed (``pytest -s``), with the machine's load: each replay's CPU per run (the calling
thread's, best of REPEATS), the blocks' ratio to the one-at-a-time baseline, and the
replay's share of the run's own CPU (the flight's, measured once in the same run). Nothing
asserts a time; the checks are that both ways keep the same samples and figures.

Last figures (2-core machine shared with other work, load 3.0, two runs; the campaign follows
the booster alone past its separation): 1 177 calls, 4 703 samples in 1 149 blocks, the run
0.94-1.32 s of CPU; every sample kept: blocks 5.8-9.1 ms a run, one at a time 21-32 ms (ratio
0.28-0.29, 0.6-0.7 % of the run); coasts at 1 Hz: blocks 9.4-12.7 ms, one at a time 29-36 ms
(ratio 0.33-0.35, 1.0 %). The same calls replayed on the code before the sample watch took
whole blocks (its figures block by block, the recorder a sample at a time): 41 ms, at the same
load. Flying every body to the end (the upper stage and the fairing's halves too: 13 536
samples in 4 481 blocks, load 6.6-6.9): blocks 24 ms against 65 ms one at a time, and 127 ms
before.
"""

from __future__ import annotations

import time
from pathlib import Path

import yaml

from rocketsim.api.flying import fly
from rocketsim.api.recorder import Recorder
from rocketsim.campaigns.cases import Plan
from rocketsim.campaigns.spec import read_campaign
from rocketsim.sim import world as world_module
from rocketsim.sim.sample_watch import SampleWatch
from rocketsim.telemetry.sample_plans import interleaved_samples
from tests.benchmarks.timing import best_of, load_text

ROOT = Path(__file__).resolve().parents[2]
CAMPAIGN = ROOT / "campaigns" / "falcon9-landing.yaml"
REPEATS = 5
COAST_RATE = 1.0        # Hz: the coast rule's rate in the replay with it


class Kept(SampleWatch):
    """A sample watch that keeps a copy of every call made to it, in order."""

    calls: list = []
    settings: list = []

    def __init__(self, telemetry, h, every, coast_every=None):
        Kept.settings.append((h, every))
        super().__init__(telemetry, h, every, coast_every)

    def add_body(self, name):
        Kept.calls.append(("add_body", (name,)))
        super().add_body(name)

    def inherit(self, body, parent):
        Kept.calls.append(("inherit", (body, parent)))
        super().inherit(body, parent)

    def sample(self, body, values, fields, leaving=False):
        Kept.calls.append(("sample", (body, values.copy(), fields, leaving)))
        super().sample(body, values, fields, leaving)

    def sample_rows(self, body, rows, fields):
        Kept.calls.append(("sample_rows", (body, rows.copy(), fields)))
        super().sample_rows(body, rows, fields)

    def sample_interleaved(self, blocks):
        Kept.calls.append(("sample_interleaved", ([(body, rows.copy(), *rest) for body, rows, *rest in blocks],)))
        super().sample_interleaved(blocks)

    def event(self, t, body, name, figures):
        Kept.calls.append(("event", (t, body, name, figures)))
        super().event(t, body, name, figures)


def one_at_a_time(calls: list) -> list:
    """``calls`` with every sample handed over on its own, in the order it is written."""
    found = []
    for name, arguments in calls:
        if name == "sample_rows":
            body, rows, fields = arguments
            found += [("sample", (body, values, fields, False)) for values in rows]
        elif name == "sample_interleaved":
            found += [("sample", (body, values, fields, False))
                      for body, values, fields in interleaved_samples(arguments[0])]
        else:
            found.append((name, arguments))
    return found


def replay(calls: list, h: float, every: int, coast_every: int | None) -> tuple[Recorder, SampleWatch]:
    recorder = Recorder(0)
    watch = SampleWatch(recorder, h, every, coast_every)
    for name, arguments in calls:
        getattr(watch, name)(*arguments)
    watch.finish()
    recorder.close()
    for body in recorder.samples:
        watch.figures(body)
    return recorder, watch


def kept(recorder: Recorder) -> dict:
    return {body: [segment.array().tobytes() for segment in samples.segments]
            for body, samples in recorder.samples.items()}


def test_the_sample_path_of_a_landing_run(monkeypatch):
    data = yaml.safe_load(CAMPAIGN.read_text())
    data = {**data, "runs": 1, "scenario": str((CAMPAIGN.parent / data["scenario"]).resolve())}
    scenario = Plan(read_campaign(data)).scenario(0)
    fly(scenario, duration=1.0)         # the kernels loaded (compiled on a cold cache)
    monkeypatch.setattr(world_module, "SampleWatch", Kept)
    Kept.calls.clear()
    start = time.thread_time()
    fly(scenario)
    flight = time.thread_time() - start
    calls, (h, every) = list(Kept.calls), Kept.settings[-1]
    singles = one_at_a_time(calls)
    samples = sum(1 for name, _ in singles if name == "sample")
    blocks = sum(len(a[0]) if name == "sample_interleaved" else 1 for name, a in calls if name.startswith("sample"))
    print(f"\nthe sample path of a landing run ({load_text()}): {len(calls)} calls, {samples} samples "
          f"in {blocks} blocks; the run {flight:.2f} s of CPU")
    coast_every = every * max(1, round(1.0 / (COAST_RATE * h * every)))
    for label, coast in (("every sample", None), (f"coasts at {COAST_RATE:g} Hz", coast_every)):
        blocked, (recorder, watch) = best_of(REPEATS, lambda: replay(calls, h, every, coast), time.thread_time)
        single, (recorder_1, watch_1) = best_of(REPEATS, lambda: replay(singles, h, every, coast), time.thread_time)
        assert kept(recorder) == kept(recorder_1) and recorder.run.counts == recorder_1.run.counts
        for body in recorder.samples:
            assert watch.figures(body) == watch_1.figures(body)
        assert sum(recorder.run.counts.values()) <= samples
        print(f"  {label}: blocks {blocked * 1e3:.1f} ms a run, one at a time {single * 1e3:.1f} ms "
              f"(ratio {blocked / single:.2f}); the blocks {blocked / flight:.1%} of the run's CPU ({load_text()})")
