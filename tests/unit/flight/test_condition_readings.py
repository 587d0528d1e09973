"""What a condition read in Python reads between a compiled run's steps.

A program's ``fc.wait_until(lambda: ...)`` is read after every step of a compiled run
(rocketsim.stepping.runs: the step's state and its navigation estimate handed over in
one buffer, rocketsim.flight.navigation.hand_into), where the flight computer's views
follow that buffer from step to step (rocketsim.flight.readings.StateView.following).
The reference is the world's one-step loop (the windows switched off), where each step
makes its views afresh from the body's state: the same readings to the bit at every
step, with the truth's readings and with realistic sensors' errors, the place's
readings read alone first and then all of them, a scalar sensor's (the radar), the
air, the orbit and the engines' thrust.
"""

import pytest

from rocketsim.api.telemetry_flight import fly_to_file
from rocketsim.scenario.load import load
from rocketsim.sim import world as world_module
from rocketsim.sim.vehicle_checks import VehicleChecks
from tests.sounding_peer import scenario

FLOWN = 30.0        # s: the boost and the climb after burn-out (the engine burns ~29 s)


def _read(fc) -> tuple:
    """The readings a condition reads, the place's first (read alone: its own kernel)."""
    return (fc.time, fc.vertical_speed, fc.altitude, fc.horizontal_speed, tuple(fc.surface_velocity),
            fc.pitch, fc.heading, fc.roll, tuple(fc.prograde), fc.gravity, fc.radar_altitude, fc.mach,
            fc.dynamic_pressure, fc.thrust, fc.apoapsis, tuple(fc.position), tuple(fc.attitude))


def _flown(tmp_path, monkeypatch, sensors: str, windows: bool) -> tuple[list, int]:
    """The readings of a condition at every step from 0.5 s on, and the steps flown in
    compiled runs that read it."""
    read, asked = [], [0]

    def program(fc):
        fc.ignite()
        fc.sleep(0.5)
        fc.wait_until(lambda: read.append(_read(fc)) or fc.time > FLOWN - 1.0)
        read.append(("woken", _read(fc)))

    fly_run = VehicleChecks.fly_run

    def counted(checks, body, k0, h, n, steering, events, condition, samples, between=None):
        result = fly_run(checks, body, k0, h, n, steering, events, condition, samples, between)
        asked[0] += result[1] if between is not None else 0
        return result

    monkeypatch.setattr(VehicleChecks, "fly_run", counted)
    if not windows:
        monkeypatch.setattr(world_module, "fly_window", lambda world, length: False)
    fly_to_file(load({**scenario(FLOWN), "program": program, "sensors": sensors, "seed": 3}),
                tmp_path / "flight.mcap")
    monkeypatch.undo()
    return read, asked[0]


@pytest.mark.parametrize("sensors", ["truth", "realistic"])
def test_a_condition_reads_in_a_run_what_it_reads_one_step_at_a_time(tmp_path, monkeypatch, sensors):
    in_runs, asked = _flown(tmp_path, monkeypatch, sensors, True)
    one_by_one, _ = _flown(tmp_path, monkeypatch, sensors, False)
    assert asked > 1000                         # read between the steps of compiled runs
    assert len(in_runs) > 1400 and in_runs == one_by_one
    assert in_runs[-1][0] == "woken"
    if sensors == "realistic":                  # the estimate's errors in what it read
        truth, _ = _flown(tmp_path, monkeypatch, "truth", True)
        assert [r[2] for r in truth[:100]] != [r[2] for r in in_runs[:100]]
