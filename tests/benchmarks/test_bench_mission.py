"""Benchmark: the shipped Falcon 9-class mission, flown whole, at 20 ms.

Target: at least 100x real time on one core (the whole mission, about nine
minutes of flight, in under about 6 s), telemetry at 10 Hz included.

The benchmark flies ``scenarios/falcon9-leo.yaml`` as shipped (its programs,
the booster's return included) through :func:`rocketsim.api.telemetry_flight.fly_to_file` with
the file's 10 Hz telemetry. In the suite it flies the first ARC seconds (the
ascent, staging and the start of the boost-back, two vehicles awake after
separation: the suite's budget is ~15 s per benchmark); with
``ROCKETSIM_BENCH_FULL=1`` it flies the whole mission, the target's figure.
Printed (run with ``pytest -s``):

* simulated seconds per wall second (the real-time factor);
* the share of the wall time in each part of the step loop: the physics
  (the compiled RK4 advance of every awake body, a tumbling part's with its
  drag included; for a vehicle with
  aerodynamics one compiled call per step, which also runs the autopilot's
  step before it, when nothing of that is left to Python, and computes the
  checks' figures after it: :func:`rocketsim.stepping.checked_step.advance_checked`),
  the rails (sleeping bodies' compiled steps), the programs (their Python code
  and the readings they compute first), the autopilot (what is left of it
  outside that call), the per-step checks (limits, heating, touchdown, on those
  figures), the flight events, telemetry (on the flight's thread: a sample's
  figures, handing messages and batches of samples to the writing thread, and
  the wait for it at the end; its encoding and writing run beside), the
  loop's decisions (batch length, rails or not, the impact test), and the
  rest of the run;
* the physics, checks, events and loop per body-step (per awake 20 ms step of one
  body; the whole mission takes about 53 000, so 100x real time leaves
  about 110 us per body-step for everything);
* the ratio of the whole flight to its physics alone, both measured in this
  run (1.0 would be a loop that costs nothing beyond the integrator).

The shipped programs hand what they can to compiled code: ``orbit_ascent.py``
climbs from the pitch kick to MECO without waking (surface prograde held, the
engines' q throttle law, a compiled wait on the stage's propellant) and flies
its insertion with Powered Explicit Guidance solved every second, the nose
pointed along its law in between; ``booster_return.py`` predicts its boost-back's miss once a second
(waiting on the nose's angle to its aim while it turns), updates its descent
every 0.5 s and its entry and landing burns every 0.1 s, every step only as a
cut-off or the landing burn's ignition nears (``Approach``): 971 program
resumes in the whole mission. The "programs" share counts the calls that run
the programs due at a step (the loop's and the windows'), not the resumes.

The shares come from timing wrappers put around those parts for this run
only (about a microsecond per wrapped call, included in the figures).

Also printed: the machine's load, and the same flight uninstrumented, in-process
(best of 2 in the suite, 1 for the whole mission): the real-time factor.
Compiled runs (:mod:`rocketsim.sim.window`, :mod:`rocketsim.stepping.runs`) count as
physics: the autopilot's step, RK4, the checks' figures and the tests of the
checks and events inside them; their Python around them (the window's queue, the
runs' arguments) as the loop.

Last figures (a 2-core machine at load 0.7-1.3, in-process): the suite's first
160 s, two bodies, 0.10-0.11 s uninstrumented, 1 470-1 550x real time; whole
flight / physics 1.39-1.44. The whole mission: 0.68-0.71 s uninstrumented
(845-887x), instrumented physics 0.48-0.50 s (67 %), programs 0.14 s (20 %;
1 105 calls, 130 us each), the loop 0.06 s (8 %); whole / physics 1.47-1.50:
0.22-0.24 s beyond the physics, most of it the programs' Python. The
landed booster standing on its legs for its last ~140 s (ground sub-steps) is
0.11 s of the 0.37 s of compiled runs (14.5 us a step). Each
body's run goes on past the sample steps (their samples computed in the runs)
and past the other bodies' program wake-ups (the programs run inside the
window), ending at its own program's wake-up, a check or event that may act,
or every 10 samples (1 s), where the world reports its progress.
Nothing asserts a time; the checks are that the mission reaches orbit and
that the parts add up to no more than the whole.
"""

from __future__ import annotations

import os
import time
from collections import Counter
from pathlib import Path

from rocketsim.jit import Entries
from rocketsim.scenario.load import load
from rocketsim.sim import flight_events, schedule, vehicle_checks, world
from rocketsim.stepping import runs
from rocketsim.stepping.checked_step import advance_checked
from rocketsim.api.telemetry_flight import fly_to_file as fly
from rocketsim.telemetry.writer import TelemetryWriter
from tests.benchmarks.timing import best_of, load_text

ROOT = Path(__file__).resolve().parents[2]
MISSION = ROOT / "scenarios" / "falcon9-leo.yaml"
ARC = 160.0        # s flown in the suite (the whole mission with ROCKETSIM_BENCH_FULL=1)


class SectionClock:
    """Exclusive wall time of nested sections (a section's time excludes the
    sections called inside it)."""

    def __init__(self):
        self.seconds = Counter()
        self.calls = Counter()
        self._open: list[str] = []

    def wrap(self, function, label):
        def timed(*args, **kwargs):
            start = time.perf_counter()
            self._open.append(label)
            try:
                return function(*args, **kwargs)
            finally:
                self._open.pop()
                spent = time.perf_counter() - start
                self.seconds[label] += spent
                self.calls[label] += 1
                if self._open:
                    self.seconds[self._open[-1]] -= spent
        return timed


def _instrument(monkeypatch, clock: SectionClock) -> Counter:
    """Put the section clocks around the parts of the step loop; returns the counter
    of body-steps the integrator takes (``steps["body-steps"]``, awake 20 ms steps of
    every body: what the per-step figures divide by)."""
    patch = monkeypatch.setattr
    steps = Counter()
    integrator = world.advance
    timed_advance = clock.wrap(integrator, "physics")

    def timed_integrator(y, k0, h, n, *rest):                  # a rigid body's steps
        steps["body-steps"] += n
        return timed_advance(y, k0, h, n, *rest)

    patch(world, "advance", timed_integrator)
    timed_free = clock.wrap(world.advance_free, "physics")

    def timed_free_body(y, k0, h, n, *rest):                   # a tumbling part's steps (with drag)
        steps["body-steps"] += n
        return timed_free(y, k0, h, n, *rest)

    patch(world, "advance_free", timed_free_body)
    timed_part = clock.wrap(runs.fly_part, "physics")

    def timed_part_run(*args):                                 # a tumbling part's compiled run
        y, taken, filled = timed_part(*args)
        steps["body-steps"] += taken
        return y, taken, filled

    patch(runs, "fly_part", timed_part_run)
    bound_call = Entries.call                                  # a staged vehicle's steps
    timed_bound_call = clock.wrap(bound_call, "physics")

    def call(entries, kernel, key, *args):
        if kernel is timed_integrator or kernel is advance_checked:
            steps["body-steps"] += args[3]
            return timed_bound_call(entries, integrator if kernel is timed_integrator else kernel, key, *args)
        if kernel is runs.fly_run:                             # a compiled run: its steps as it took them
            result = timed_bound_call(entries, kernel, key, *args)
            steps["body-steps"] += result[2]
            return result
        return bound_call(entries, kernel, key, *args)

    patch(Entries, "call", call)
    for name in ("advance_rails", "advance_cruise"):                # asleep bodies' steps
        patch(world, name, clock.wrap(getattr(world, name), "rails"))
    patch(world.World, "run_programs", clock.wrap(world.World.run_programs, "programs"))
    patch(world.World, "_run_autopilots", clock.wrap(world.World._run_autopilots, "autopilot"))
    patch(world.World, "run_autopilot", clock.wrap(world.World.run_autopilot, "autopilot"))
    # every sample (the rate's, and those at impacts, handovers and new bodies), every
    # handing over to the writing thread, whoever asks for it (an event, a log line, a
    # batch of samples full), and the wait for the thread at the file's end: the
    # telemetry's cost on the flight's thread
    patch(world.World, "record", clock.wrap(world.World.record, "telemetry"))
    for name in ("_hand_over", "close"):
        patch(TelemetryWriter, name, clock.wrap(getattr(TelemetryWriter, name), "telemetry"))
    for cls, name, label in ((vehicle_checks.VehicleChecks, "after_step", "checks"),
                             (vehicle_checks.VehicleChecks, "every_step", "checks"),
                             (flight_events.FlightEvents, "after_step", "events")):
        patch(cls, name, clock.wrap(getattr(cls, name), label))
    # the loop's decisions: what to step and how (the rails tests run from the autopilot
    # and the batch length too: counted here, not there)
    patch(world.World, "advance", clock.wrap(world.World.advance, "loop"))
    for name in ("batch_length", "window_length", "holding", "on_rails", "one_step"):
        patch(schedule.Schedule, name, clock.wrap(getattr(schedule.Schedule, name), "loop"))
    # a window of compiled runs: its queue and plans, and the runs' arguments and results
    patch(world, "fly_window", clock.wrap(world.fly_window, "loop"))
    patch(vehicle_checks.VehicleChecks, "fly_run", clock.wrap(vehicle_checks.VehicleChecks.fly_run, "loop"))
    return steps


def test_falcon9_mission_speed(tmp_path, monkeypatch):
    loaded = load(MISSION)
    whole = bool(os.environ.get("ROCKETSIM_BENCH_FULL"))
    duration = None if whole else ARC
    # compile or load every kernel the flight calls: a kernel first called late in the
    # flight (the landing's, the fairing halves') is loaded from the cache there, ~10 ms each
    fly(loaded, tmp_path / "warm.mcap", duration=duration)
    plain, _ = best_of(1 if whole else 2, lambda: fly(loaded, tmp_path / "plain.mcap", duration=duration))
    clock = SectionClock()
    steps = _instrument(monkeypatch, clock)
    start = time.perf_counter()
    summary = fly(loaded, tmp_path / "mission.mcap", duration=duration)
    wall = time.perf_counter() - start
    flown = summary["mission_time_s"]
    bodies = summary["bodies"]

    arc = "the whole mission" if whole else f"its first {ARC:g} s (ROCKETSIM_BENCH_FULL=1: all of it)"
    print(f"\n[mission] {loaded.scenario.name}, {arc}: {flown:g} s of flight, {len(bodies)} bodies "
          f"({', '.join(bodies)}); {load_text()}, a shared machine")
    print(f"[mission] in-process, uninstrumented: {plain:.2f} s, {flown / plain:.0f}x real time "
          f"(targets >= 100x, >= 500x on a quiet machine)")
    print(f"[mission] instrumented: {wall:.2f} s, {flown / wall:.0f}x real time")
    clock.seconds["rest of the loop"] = wall - sum(clock.seconds.values())
    for label, seconds in clock.seconds.most_common():
        calls = clock.calls[label]
        per_call = f", {seconds / calls * 1e6:.1f} us per call ({calls})" if calls else ""
        print(f"[mission]   {label:18s} {seconds:6.2f} s  {100 * seconds / wall:5.1f} %{per_call}")
    print(f"[mission] whole flight / its physics alone: {wall / clock.seconds['physics']:.2f} (instrumented; "
          f"uninstrumented whole / instrumented physics {plain / clock.seconds['physics']:.2f}; target <= 1.3)")
    body_steps = steps["body-steps"]
    per_step = ", ".join(f"{label} {clock.seconds[label] / body_steps * 1e6:.1f} us"
                         for label in ("physics", "checks", "events", "loop", "rest of the loop"))
    print(f"[mission] per body-step ({body_steps} awake 20 ms steps of all bodies): {per_step}")

    events = {e["name"] for b in bodies.values() for e in b["events"]}
    assert {"liftoff", "separation"} <= events, events
    if whole:
        assert "orbit" in events, events
    assert clock.seconds["rest of the loop"] > -1e-3 * wall   # the parts add up to the whole
