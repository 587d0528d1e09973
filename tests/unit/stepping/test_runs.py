"""Compiled runs of steps (rocketsim.sim.window, rocketsim.stepping.runs).

A pure speed change: the reference is the world's one-step loop, which these tests
run side by side with the compiled runs (the window switched off): the same
telemetry, message for message and bit for bit, the same events and final states.
"""

import math
from pathlib import Path

import orjson
import pytest

from rocketsim.flight.program import ProgramError, ProgramRunner
from rocketsim.layout import V
from rocketsim.errors import InputError
from rocketsim.scenario.load import load
from rocketsim.sim import window, window_plans, world as world_module
from rocketsim.sim.build import build_world
from rocketsim.api.telemetry_flight import fly_to_file as fly
from rocketsim.sim.vehicle_checks import VehicleChecks
from rocketsim.stepping import runs
from rocketsim.telemetry.reader import iter_raw_messages
from rocketsim.telemetry.writer import TelemetryWriter

ROOT = Path(__file__).resolve().parents[3]
MISSION = ROOT / "scenarios" / "falcon9-leo.yaml"
# the ascent (the kick's compiled condition, max-Q, MECO), the staging, the boost-back,
# the fairing halves' fall and the start of the booster's compiled wait for its entry:
# every kind of segment of a window, in 230 s of the 600 s mission (the suite's budget)
ARC = 230.0


def _runs_go_on(world) -> bool:
    """Whether another body's compiled run goes on past the world's step: its state is
    still that of its run's start (the window sets it at the run's end)."""
    return any(body.flying and body.t < world.t for body in world.bodies)


def _flight(tmp_path, name, monkeypatch, windows: bool, counts: dict, overrides=None, duration=ARC):
    """The mission's first ``duration`` seconds (with ``overrides``) with the windows
    (counting their runs' steps) or one step at a time; returns the summary and the
    telemetry's messages."""
    if windows:
        vehicle_run, part_run = VehicleChecks.fly_run, runs.fly_part

        def counted(checks, body, k0, h, n, steering, events, condition, samples, between=None):
            y, taken, reason, filled = vehicle_run(checks, body, k0, h, n, steering, events, condition, samples,
                                                   between)
            counts["vehicle steps"] += taken
            counts["conditions"] += reason == runs.CONDITION
            counts["waiting"] += condition.shape[0] > 0
            if body.sensors is not None and not body.sensors.perfect:
                counts["steered on the estimate"] += taken if steering is not None else 0
                counts["conditions on the estimate"] += reason == runs.CONDITION
            return y, taken, reason, filled

        def counted_part(*args):
            y, taken, filled = part_run(*args)
            counts["part steps"] += taken
            return y, taken, filled

        record_rows, record_interleaved = world_module.World.record_rows, world_module.World.record_interleaved
        resume, run_programs = ProgramRunner.resume, world_module.World.run_programs
        fly_window, in_window = world_module.fly_window, [False]

        def resume_counted(runner, fc):
            counts["resumes"] += 1
            resume(runner, fc)

        def window_marked(world, length):
            in_window[0] = True
            try:
                return fly_window(world, length)
            finally:
                in_window[0] = False

        def programs_counted(world, indices):
            before = counts["resumes"]
            made = run_programs(world, indices)
            if in_window[0]:
                if counts["resumes"] > before:
                    counts["programs woken in windows"] += 1
                    counts["... while other bodies' runs go on"] += _runs_go_on(world)
                counts["bodies made in windows"] += len(made)
            return made

        def rows_counted(world, body, rows, shape):
            if sum(b.flying for b in world.bodies) > 1:
                counts["samples in runs beside others"] += len(rows)
            record_rows(world, body, rows, shape)

        def interleaved_counted(world, blocks):
            counts["samples in runs beside others"] += sum(len(rows) for _, rows, *_ in blocks)
            counts["bodies interleaved"] = max(counts["bodies interleaved"], len({body.name for body, *_ in blocks}))
            record_interleaved(world, blocks)

        monkeypatch.setattr(VehicleChecks, "fly_run", counted)
        monkeypatch.setattr(runs, "fly_part", counted_part)
        monkeypatch.setattr(world_module.World, "record_rows", rows_counted)
        monkeypatch.setattr(world_module.World, "record_interleaved", interleaved_counted)
        monkeypatch.setattr(ProgramRunner, "resume", resume_counted)
        monkeypatch.setattr(world_module.World, "run_programs", programs_counted)
        monkeypatch.setattr(world_module, "fly_window", window_marked)
    else:
        monkeypatch.setattr(world_module, "fly_window", lambda world, length: False)
    out = tmp_path / f"{name}.mcap"
    summary = fly(load(MISSION, overrides), out, duration=duration)
    monkeypatch.undo()
    return summary, list(iter_raw_messages(out))


def test_compiled_runs_fly_the_same_telemetry_as_one_step_at_a_time(tmp_path, monkeypatch):
    counts = {"vehicle steps": 0, "part steps": 0, "conditions": 0, "waiting": 0, "samples in runs beside others": 0,
              "bodies interleaved": 0,
              "resumes": 0, "programs woken in windows": 0, "... while other bodies' runs go on": 0,
              "bodies made in windows": 0}
    summary, messages = _flight(tmp_path, "runs", monkeypatch, True, counts)
    summary_before, messages_before = _flight(tmp_path, "steps", monkeypatch, False, counts)
    assert summary == summary_before
    assert len(messages) == len(messages_before) > 10_000
    assert messages == messages_before
    # the runs did fly: most vehicle and part steps, and the kick's condition ended one
    assert counts["vehicle steps"] > 10_000 and counts["part steps"] > 500
    # the kick's height and the booster's cut-off at its reserve of propellant
    assert counts["conditions"] >= 2 and counts["waiting"] > 10
    # with the booster and the fairing's halves flying beside, the vehicles' runs went on
    # past sample steps (their samples written among the others' in the loop's order)
    # (several bodies' runs' samples handed to the writer together: all four bodies')
    assert counts["samples in runs beside others"] > 300 and counts["bodies interleaved"] == 4
    # the programs woke inside the windows (180 of 185 resumes), most while other bodies'
    # runs went on past their step, and the separation and the fairing's jettison made
    # their bodies there: the booster and the two halves, flown on from that step
    assert counts["programs woken in windows"] > 100 and counts["... while other bodies' runs go on"] > 100
    assert counts["bodies made in windows"] == 3
    events = {e["name"] for b in summary["bodies"].values() for e in b["events"]}
    assert {"liftoff", "max_q", "MECO", "separation", "boost-back end", "fairing jettison"} <= events


def test_with_realistic_sensors_the_runs_steer_and_wait_on_the_estimate_as_one_step_at_a_time(tmp_path,
                                                                                            monkeypatch):
    """The mission with ``sensors: realistic`` (rocketsim/flight/sensors.py) to past the
    booster's cut-off and separation: its compiled runs steer on the navigation estimate
    and test the programs' conditions on it (the kick's height, the booster's propellant
    through the gauges of its tanks), the estimate drawn from the same streams as the
    flight computer's; the file is the same, message for message and bit for bit, as the
    loop's one step at a time, where the autopilot and the conditions read the estimate
    in Python (the programs' decisions, MECO's step among them, follow the errors)."""
    counts = {name: 0 for name in ("vehicle steps", "part steps", "conditions", "waiting", "steered on the estimate",
                                   "conditions on the estimate", "samples in runs beside others",
                                   "bodies interleaved", "resumes", "programs woken in windows",
                                   "... while other bodies' runs go on", "bodies made in windows")}
    sensors = {"sensors": "realistic"}
    summary, messages = _flight(tmp_path, "runs", monkeypatch, True, counts, sensors, 160.0)
    summary_before, messages_before = _flight(tmp_path, "steps", monkeypatch, False, counts, sensors, 160.0)
    assert summary == summary_before
    assert len(messages) == len(messages_before) > 5_000
    assert messages == messages_before
    assert counts["steered on the estimate"] > 5_000 and counts["conditions on the estimate"] >= 2
    events = {e["name"] for b in summary["bodies"].values() for e in b["events"]}
    assert {"liftoff", "max_q", "MECO", "separation"} <= events


def _sounding(tmp_path, name, monkeypatch, how: str, duration: float = 110.0, cut: float = math.inf):
    """The sounding rocket of tests/sounding_peer.py flown ``duration`` s: in windows whose
    runs compute the samples (``how`` "runs"), whose runs return at every sample step
    ("python": the world samples each), or one step at a time ("steps"); ``on_progress``
    ends the flight at its first call at ``cut`` s or later. Returns the telemetry's
    messages, the samples the runs computed and the world's last step."""
    from tests.sounding_peer import scenario

    computed = []
    if how == "steps":
        monkeypatch.setattr(world_module, "fly_window", lambda world, length: False)
    if how == "python":
        monkeypatch.setattr(window, "RUN_SAMPLES", 0)
    record_rows = world_module.World.record_rows

    def counted(world, body, rows, shape):
        computed.extend(rows[:, -2].tolist())      # the samples' times
        record_rows(world, body, rows, shape)

    monkeypatch.setattr(world_module.World, "record_rows", counted)
    world = build_world(load(scenario(duration)))
    world.on_progress = lambda t: setattr(world, "n_steps", world.k) if t >= cut else None
    out = tmp_path / f"{name}.mcap"
    with TelemetryWriter(out, 0, "") as telemetry:
        world.run(telemetry)
    monkeypatch.undo()
    return list(iter_raw_messages(out)), computed, world.k


def _one_way(monkeypatch, windows: bool, seen) -> None:
    """Fly the next flight in windows, each resume of a program first shown to ``seen(world)``
    (the world's loop, or a run reading the program at every step), or one step at a time."""
    if not windows:
        monkeypatch.setattr(world_module, "fly_window", lambda world, length: False)
        return
    resume = ProgramRunner.resume

    def resume_seen(runner, fc):
        seen(fc._craft._world)
        resume(runner, fc)

    monkeypatch.setattr(ProgramRunner, "resume", resume_seen)


# booster programs that wake inside a window while the upper stage's runs go on past their
# steps: one that then waits on a condition read in Python (flown one step at a time inside
# the window, read at every step), one that raises there (the flight ends at that step)
BOOSTER_PROGRAMS = {
    "waits on a lambda": """
def main(fc):
    fc.sleep(2.13)
    fc.point_at(fc.radial)
    top = fc.altitude + 2000.0
    fc.wait_until(lambda: fc.altitude > top)
    fc.event("climbed", altitude_m=fc.altitude)
    fc.sleep(0.37)
    fc.wait_until(fc.below("vertical_speed", fc.vertical_speed - 30.0))
    fc.event("slower", vertical_speed_m_s=fc.vertical_speed)
""",
    "raises": """
def main(fc):
    fc.sleep(3.07)
    fc.log("about to fail")
    raise RuntimeError("booster program failed")
""",
}


@pytest.mark.parametrize("kind", sorted(BOOSTER_PROGRAMS))
def test_a_program_woken_inside_a_window_flies_as_one_step_at_a_time(tmp_path, monkeypatch, kind):
    (tmp_path / "booster.py").write_text(BOOSTER_PROGRAMS[kind])
    text = MISSION.read_text().replace("programs/booster_return.py", str(tmp_path / "booster.py"))
    for key in ("vehicle: ", "site: ", "program: ", "mission: "):     # the shipped files, from here
        start = text.index(key) + len(key)
        end = text.index("\n", start)
        text = text[:start] + str((MISSION.parent / text[start:end]).resolve()) + text[end:]
    scenario = tmp_path / "mission.yaml"
    scenario.write_text(text)

    beside = []                 # the steps where a program ran beside another body's run

    def flown(name, windows):
        _one_way(monkeypatch, windows, lambda world: _runs_go_on(world) and beside.append(world.k))
        out = tmp_path / f"{name}.mcap"
        try:
            result = fly(load(scenario), out, duration=150.0)
        except ProgramError as error:
            result = str(error)
        monkeypatch.undo()
        return result, list(iter_raw_messages(out))

    result, messages = flown("runs", True)
    result_before, messages_before = flown("steps", False)
    assert result == result_before
    assert messages == messages_before and len(messages) > 5_000
    assert len(beside) >= 3         # the booster's program ran inside windows beside the upper stage's runs
    if kind == "raises":
        assert "booster program failed" in result
    else:
        names = [e["name"] for e in result["bodies"]["booster"]["events"]]
        assert "climbed" in names and "slower" in names


def test_a_single_body_samples_inside_its_runs_what_the_world_samples(tmp_path, monkeypatch):
    """A flight of one body (the sounding rocket: pad, boost, coast past apogee): its
    compiled runs go on past the sample steps, computing those samples themselves, from
    the pad on (standing on its base until liftoff at 0.86 s); the file is the same,
    message for message and bit for bit, as the world sampling each one (the runs
    returning at every sample step) and as the loop one step at a time."""
    messages, computed, _ = _sounding(tmp_path, "runs", monkeypatch, "runs")
    by_python, none, _ = _sounding(tmp_path, "python", monkeypatch, "python")
    by_steps, _, _ = _sounding(tmp_path, "steps", monkeypatch, "steps")
    assert not none and len(computed) > 900      # of the 1 101 samples: those inside the runs
    assert min(computed) == pytest.approx(0.1)    # the first after T+0, on the pad
    states = [m for m in messages if m[0].endswith("/state")]
    assert len(states) == 1101 and len({time for _, time, _ in states}) == 1101
    assert messages == by_python == by_steps


def test_a_run_still_compiling_elsewhere_is_flown_one_step_at_a_time_meanwhile(tmp_path, monkeypatch):
    """On a cold cache the second process may still be compiling the vehicle's run when the
    flight needs it: the world flies one step at a time meanwhile (here its first 400
    plans, 8 s: the pad, liftoff, the start of the burn) and the runs take over from
    there; the file is the runs' own, message for message and bit for bit."""
    messages, _, _ = _sounding(tmp_path, "runs", monkeypatch, "runs", duration=30.0)
    asked, first_run = [], []

    def compiling_elsewhere(kernel):
        asked.append(kernel)
        return kernel is runs.fly_run and len(asked) <= 400

    vehicle_run = VehicleChecks.fly_run

    def counted(checks, body, k0, *rest):
        first_run.append(k0)
        return vehicle_run(checks, body, k0, *rest)

    monkeypatch.setattr(window_plans, "compiling_elsewhere", compiling_elsewhere)
    monkeypatch.setattr(VehicleChecks, "fly_run", counted)
    meanwhile, _, _ = _sounding(tmp_path, "meanwhile", monkeypatch, "runs", duration=30.0)
    assert first_run and first_run[0] >= 400
    assert meanwhile == messages


def test_a_flight_on_progress_ends_early_ends_there_once_sampled(tmp_path, monkeypatch):
    """``on_progress`` ending the flight at its step (``n_steps = k``) in the middle of
    the runs' samples: the flight ends at that step, sampled once, as a flight of that
    duration flown one step at a time."""
    messages, computed, k = _sounding(tmp_path, "cut", monkeypatch, "runs", cut=40.0)
    assert computed and 2000 <= k < 2200
    same, _, _ = _sounding(tmp_path, "short", monkeypatch, "steps", duration=k * 0.02)
    assert messages == same
    states = [time for topic, time, _ in messages if topic.endswith("/state")]
    assert len(states) == len(set(states)) == k // 5 + 1


def test_a_window_needs_two_steps():
    assert window.fly_window(None, 1) is False


def test_a_state_gone_non_finite_inside_a_run_ends_the_flight_at_the_next_sample(tmp_path):
    """The sounding rocket's velocity made enormous (1e154 times, so its square overflows)
    where the flight first reports progress after T+30 s, between two compiled runs: the
    next run's first step turns the state to inf and nan, and its checks hand the flight
    back to Python, which flies to the next sample step. There the world's finiteness test
    stops the flight with an input error naming the step. The file ends with the last
    finite sample, taken before the change."""
    from tests.sounding_peer import scenario

    world = build_world(load(scenario(60.0)))
    changed = []

    def enormous(t):
        if t >= 30.0 and not changed:
            changed.append(world.k)
            world.bodies[0].y[V:V + 3] *= 1e154

    world.on_progress = enormous
    out = tmp_path / "non-finite.mcap"
    with pytest.raises(InputError, match="no longer finite at T") as raised:
        with TelemetryWriter(out, 0, "") as telemetry:
            world.run(telemetry)
    assert raised.value.field == "step"
    assert changed and changed[0] % world.sample_every == 0     # at a sample step
    assert world.k == changed[0] + world.sample_every            # stopped at the next one
    states = [orjson.loads(data) for topic, _, data in iter_raw_messages(out) if topic.endswith("/state")]
    assert states[-1]["t"] == pytest.approx(changed[0] * world.h)
    assert all(math.isfinite(x) for state in states for x in state["position"] + state["velocity"])


def _ignites_in_its_condition(fc):
    fc.wait_until(lambda: fc.time > 2.0 and fc.ignite() is not None)


def _ignites_on_waking(fc):
    fc.wait_until(lambda: fc.time > 2.0)
    fc.ignite()


def test_a_command_inside_a_condition_read_in_python_acts_on_the_flight(tmp_path, monkeypatch):
    """A condition read in Python between a compiled run's steps that commands (the sounding
    rocket's engine lit inside ``fc.wait_until(lambda: ...)`` at T+2.02 s) acts on the state
    the flight goes on from: the file is, message for message and bit for bit, that of the
    world's loop one step at a time (which reads the condition on the body's own state),
    and the flight is the one of a program lighting the engine as it wakes at that step
    (liftoff after the engine's 0.3 s dead time and its spool-up)."""
    from tests.sounding_peer import scenario

    def flown(name, program, windows=True):
        if not windows:
            monkeypatch.setattr(world_module, "fly_window", lambda world, length: False)
        out = tmp_path / f"{name}.mcap"
        summary = fly(load({**scenario(10.0), "program": program}), out)
        monkeypatch.undo()
        return summary["bodies"], list(iter_raw_messages(out))

    inside, messages = flown("inside", _ignites_in_its_condition)
    inside_steps, messages_steps = flown("inside-steps", _ignites_in_its_condition, windows=False)
    waking, _ = flown("waking", _ignites_on_waking)
    assert messages == messages_steps and inside == inside_steps
    assert inside == waking
    events = {e["name"]: e["time_s"] for e in inside["peer_sounding_rocket"]["events"]}
    assert events["ignition"] == pytest.approx(2.02) and events["liftoff"] > 2.02 + 0.3


def _polls_every_step(fc):
    """A flight computer's loop: the engine lit, then read at every step; the throttle
    taken down once, lines logged now and then, the descent's step noted."""
    fc.ignite()
    steps = 0
    while not (fc.time > 5.0 and fc.vertical_speed < 0.0):
        steps += 1
        if steps == 900:
            fc.throttle(0.6)
        if steps % 700 == 0:
            fc.log(f"climbing at {fc.vertical_speed:.1f} m/s")
        fc.step()
    fc.event("descending", altitude_m=fc.altitude)


def test_a_program_read_at_every_step_flies_inside_the_runs_as_one_step_at_a_time(tmp_path, monkeypatch):
    """The sounding rocket's program as a flight computer's loop (``fc.step()`` at every step,
    a throttle command, log lines, an event): resumed from inside the compiled runs, between
    their steps, the runs ending only where it acts; the file is, message for message and
    bit for bit, the loop's one step at a time, and most of the program's wakes were inside
    the runs."""
    from tests.sounding_peer import scenario

    inside = []                 # the wakes inside a run reading the program (its acting hook set)

    def flown(name, windows):
        _one_way(monkeypatch, windows, lambda world: world.before_act is not None and inside.append(world.k))
        out = tmp_path / f"{name}.mcap"
        summary = fly(load({**scenario(110.0), "program": _polls_every_step}), out)
        monkeypatch.undo()
        return summary["bodies"], list(iter_raw_messages(out))

    runs_summary, messages = flown("runs", True)
    steps_summary, messages_steps = flown("steps", False)
    assert messages == messages_steps and runs_summary == steps_summary
    names = [e["name"] for e in runs_summary["peer_sounding_rocket"]["events"]]
    assert "descending" in names
    assert len(inside) > 4_000      # of some 5 000 wakes
