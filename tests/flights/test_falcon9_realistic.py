"""The Falcon 9-class mission with ``sensors: realistic``: the booster still lands on LZ-1.

Both programs read the navigation estimate (rocketsim/flight/sensors.py: position
2 m and velocity 1 cm/s wandering biases, radar 0.2 % + 5 cm, air data 1 %...);
the physics runs on the truth. Flown at a 0.05 s headless step (the ascent
test's step; the landing holds at it) and to 480 s of mission time, just past
the booster's touchdown (~466 s), to keep the suite fast: the upper stage's
insertion with these sensors is not what this test checks.
"""

import pytest

from rocketsim.scenario.load import load
from rocketsim.api.telemetry_flight import fly_to_file as fly
from tests.conftest import ROOT
from tests.plot_checks import assert_the_plot_reads


@pytest.fixture(scope="module")
def flight(tmp_path_factory):
    out = tmp_path_factory.mktemp("falcon9_realistic") / "run.mcap"
    return {**fly(load(ROOT / "scenarios" / "falcon9-leo-realistic.yaml"), out, step=0.05, duration=480.0),
            "file": out}


def test_booster_lands_within_the_limits_with_realistic_sensors(flight):
    """Booster return (realistic sensors): tilt < 5 deg, vertical speed < 2 m/s,
    within 15 m of the pad centre, from the summary's ``touchdown``."""
    touchdown = flight["bodies"]["booster"]["touchdown"]
    print(f"\nbooster touchdown (realistic sensors): {touchdown}")
    assert touchdown["tilt_deg"] < 5.0
    assert abs(touchdown["vertical_speed_m_s"]) < 2.0
    assert touchdown["distance_to_target_m"] < 15.0


def test_its_plot_reads(flight):
    """The replay plot of the whole flight (tests/plot_checks.py)."""
    assert_the_plot_reads(flight["file"], "falcon9-leo-realistic")
