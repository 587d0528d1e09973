"""The shipped Falcon 9-class ascent reaches its orbit (issue 6, the LEO ascent check).

Flown at a 0.05 s headless step (and 540 s of mission time, just past orbit
insertion) to keep the suite fast: at this step the insertion orbit agrees
with the 20 ms flight to 10 m in periapsis.
"""

import pytest

from rocketsim.scenario.load import load
from rocketsim.sim.flight import fly
from tests.conftest import ROOT


@pytest.fixture(scope="module")
def flight(tmp_path_factory):
    out = tmp_path_factory.mktemp("falcon9") / "run.mcap"
    return fly(load(ROOT / "scenarios" / "falcon9-leo.yaml"), out, step=0.05, duration=540.0)


def events(flight, body="falcon9-block5"):
    return {e["name"]: e for e in flight["bodies"][body]["events"]}


def test_orbit_reached_with_periapsis_and_inclination_on_target(flight):
    """Issue 6: periapsis >= 190 km, inclination within 0.1 deg of 51.6 deg."""
    orbit = events(flight)["orbit"]
    assert orbit["periapsis_altitude_m"] >= 190e3
    assert orbit["inclination_deg"] == pytest.approx(51.6, abs=0.1)


def test_the_ascent_events_come_in_order(flight):
    names = [e["name"] for e in flight["bodies"]["falcon9-block5"]["events"]]
    order = ["ignition", "liftoff", "max_q", "MECO", "separation", "ignition", "fairing jettison",
             "shutdown", "orbit"]
    remaining = iter(names)
    assert all(name in remaining for name in order), names      # a subsequence, in order
    assert "booster" in flight["bodies"] and "fairing" in flight["bodies"]


def test_max_q_is_where_the_physics_model_quotes_it(flight):
    """The physics model's figure for this class of ascent: max-Q 36.4 kPa at
    11.0 km, Mach 1.51, 63 s after liftoff. The program's trajectory is not
    the seed's, so within 10 % in q and Mach and 2 km in altitude."""
    max_q = events(flight)["max_q"]
    assert max_q["q_Pa"] == pytest.approx(36.4e3, rel=0.10)
    assert max_q["mach"] == pytest.approx(1.51, rel=0.10)
    assert max_q["altitude_m"] == pytest.approx(11.0e3, abs=2e3)


def test_standing_on_the_pad_is_not_a_touchdown(flight):
    """The vehicle starts on its legs: no touchdown until it has flown."""
    assert "touchdown" not in events(flight)


# --- the booster's return to Landing Zone 1 (booster_return.py, flown in the same run) ---

def test_booster_touches_down_on_lz1_upright_slow_and_on_target(flight):
    """Issue 6, booster return (truth): touches down upright (tilt < 5 deg), vertical
    speed < 2 m/s, within 15 m of the pad centre (LZ-1, the mission's target pad);
    figures from the summary's ``touchdown`` (the first contact)."""
    touchdown = flight["bodies"]["booster"]["touchdown"]
    print(f"\nbooster touchdown: {touchdown}")
    assert touchdown["tilt_deg"] < 5.0
    assert abs(touchdown["vertical_speed_m_s"]) < 2.0
    assert touchdown["distance_to_target_m"] < 15.0
    assert "breakup" not in events(flight, "booster")


def test_booster_return_phases_come_in_order(flight):
    """Separation, boost-back, grid fins, entry burn, landing burn on the legs, touchdown;
    the booster stays a body of its own with its own program."""
    names = [e["name"] for e in flight["bodies"]["booster"]["events"]]
    order = ["separation", "ignition", "boost-back start", "boost-back end", "grid fins deployed",
             "ignition", "entry burn end", "legs deployed", "ignition", "landing burn start",
             "landing burn end", "touchdown"]
    remaining = iter(names)
    assert all(name in remaining for name in order), names
