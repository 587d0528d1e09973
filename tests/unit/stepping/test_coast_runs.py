"""Compiled runs of whole sample intervals (rocketsim.sim.coast_runs, rocketsim.stepping.runs.coast_run)
against the loop's own path.

The reference is the world's loop flying the same bodies one sample interval at
a time in Python (the runs switched off): the runs must write the same file, byte
for byte, for a coasting spacecraft and for a state that diverges mid-run (the
same samples before the error, the same error).
"""

import pytest

from rocketsim.errors import InputError
from rocketsim.scenario.load import load
from rocketsim.sim import coast_runs, world as world_module
from rocketsim.api.telemetry_flight import fly_to_file as fly
from rocketsim.telemetry.reader import messages


@pytest.fixture
def counted(monkeypatch):
    """The runs flown by the world, counted: ``counted["runs"]``."""
    count = {"runs": 0}

    def fly_coast(world):
        flown = coast_runs.fly_coast(world)
        count["runs"] += flown
        return flown

    monkeypatch.setattr(world_module, "fly_coast", fly_coast)
    return count


def _without_runs(monkeypatch):
    monkeypatch.setattr(world_module, "fly_coast", lambda world: False)


def test_a_coast_flown_in_runs_writes_the_loops_file(scenario, counted, monkeypatch, tmp_path):
    # 100 s of a program-less probe in a 415 km orbit at 20 ms steps and 10 Hz: 1000 sample
    # intervals, so several full runs and a last short one
    loaded = load(scenario(duration="100 s"))
    fly(loaded, tmp_path / "runs.mcap")
    assert counted["runs"] >= 1000 // coast_runs.MAX_INTERVALS
    _without_runs(monkeypatch)
    fly(loaded, tmp_path / "loop.mcap")
    assert (tmp_path / "runs.mcap").read_bytes() == (tmp_path / "loop.mcap").read_bytes()
    states = [m for _, _, m in messages(tmp_path / "runs.mcap", ["/probe/state"])]
    assert len(states) == 1001 and states[-1]["t"] == pytest.approx(100.0)


def test_a_state_diverging_inside_a_run_stops_where_the_loop_stops(scenario, counted, monkeypatch, tmp_path):
    # 3000 rad/s at 0.1 s steps: far outside RK4's stability region for the attitude's
    # kinematics, the state overflows within a few steps (as the loop's error test knows)
    path = scenario(extra="step: 0.1 s\n")
    mission = path.with_name("mission.yaml")
    mission.write_text(mission.read_text() + "initial_rates: [3000, 100, 0]\n")
    errors = []
    for name in ("runs", "loop"):
        if name == "loop":
            _without_runs(monkeypatch)
        with pytest.raises(InputError) as caught:
            fly(load(path), tmp_path / f"{name}.mcap")
        errors.append(caught.value.message)
    assert counted["runs"] >= 1
    assert errors[0] == errors[1] and "no longer finite at T+" in errors[0]
    assert (tmp_path / "runs.mcap").read_bytes() == (tmp_path / "loop.mcap").read_bytes()
