"""``rocketsim windows --mission-fragment``: a mission file that flies, its parking orbit
in the plane the window needs, and windows on a bound of the search marked as such.

References: the plane of a parking orbit from which a departure asymptote of right
ascension ``a`` and declination ``d`` is reached holds that direction (its normal is
perpendicular to it); the shipped ``scenarios/mars-orbit.yaml`` states the 2026 window's
asymptote (declination 29.46 deg, right ascension 133.28 deg) and the plane worked out
by hand from it for a 31 deg parking orbit, RAAN 63.21 deg. A lunar window's search
assumes the parking orbit in the Moon's orbital plane at arrival (the Moon's geocentric
angular momentum from the ephemeris).
"""

import datetime as dt
import math

import numpy as np
import pytest
import yaml
from click.testing import CliRunner

from rocketsim.api import fly, load, validate_file
from rocketsim.ephemeris.solar_system import state
from rocketsim.errors import InputError
from rocketsim.transfer import windows
from rocketsim_cli.main import main
from tests.conftest import ROOT

DEG = math.pi / 180.0


def windows_cli(*args):
    return CliRunner().invoke(main, ["windows", *map(str, args)])


def normal(orbit: dict) -> np.ndarray:
    """Unit normal of an orbit's plane from its inclination and RAAN (deg)."""
    i, raan = orbit["inclination_deg"] * DEG, orbit["raan_deg"] * DEG
    return np.array([math.sin(i) * math.sin(raan), -math.sin(i) * math.cos(raan), math.cos(i)])


def fly_fragment(fragment, tmp_path, seconds=60.0):
    """The fragment as a scenario's mission with the 6U CubeSat, flown ``seconds``
    (a minute: the mission's start, not its months of cruise)."""
    scenario = tmp_path / "window.yaml"
    scenario.write_text(f"name: window\nvehicle: {ROOT}/vehicles/cubesat-6u.yaml\nmission: {fragment.name}\n"
                        "telemetry: {rate: 1 Hz}\n")
    return fly(load(scenario), duration=seconds)


def test_a_lunar_fragment_is_a_mission_that_flies_in_the_moons_plane(tmp_path):
    fragment = tmp_path / "moon.yaml"
    result = windows_cli("--target", "moon", "--from", "2026-12-06", "--to", "2026-12-09", "--step", "2h",
                         "--format", "json", "--mission-fragment", fragment)
    assert result.exit_code == 0, result.output
    import json
    best = json.loads(result.stdout)[0]
    assert validate_file(fragment) == "mission"
    run = fly_fragment(fragment, tmp_path)
    assert run.outcome == "ok"
    table = run.bodies["cubesat-6u"].table()
    assert table.index[-1] == 60.0
    assert run.metadata["rocketsim"]["epoch_utc"].startswith(best["departure_utc"][:19])
    altitude = table["orbit_periapsis_altitude_m"].iloc[0]
    assert altitude == pytest.approx(200e3, abs=15e3)           # mean elements: the osculating ripple
    arrival = dt.datetime.fromisoformat(best["arrival_utc"].replace("Z", "+00:00"))
    from rocketsim.timescales import Epoch
    r, v = state("moon", Epoch.from_utc(arrival).jd_tt(), center="earth")
    moon = np.cross(r, v) / np.linalg.norm(np.cross(r, v))
    flown = normal({"inclination_deg": table["orbit_inclination_deg"].iloc[0],
                    "raan_deg": table["orbit_raan_deg"].iloc[0]})
    print(f"\n[fragment] lunar parking plane vs the Moon's at arrival: "
          f"{math.degrees(math.acos(min(1.0, float(flown @ moon)))):.4f} deg")
    assert float(flown @ moon) > math.cos(0.05 * DEG)


def test_the_mars_parking_plane_holds_the_asymptote_as_the_shipped_mission_works_it_out():
    window = windows.Window(0.0, 0.0, 310.2, 9.27e6, (0.0, 0.0, 0.0), 2568.0, 133.28 * DEG, 29.46 * DEG,
                            3638.0, 2041.0, 5679.0)
    i, raan = windows.parking_plane(window, "mars", 31.0 * DEG)
    assert math.degrees(raan) == pytest.approx(63.21, abs=0.01)       # scenarios/mars-orbit.yaml
    u = np.array([math.cos(window.dla) * math.cos(window.rla), math.cos(window.dla) * math.sin(window.rla),
                  math.sin(window.dla)])
    assert abs(normal({"inclination_deg": math.degrees(i), "raan_deg": math.degrees(raan)}) @ u) < 1e-12
    i, raan = windows.parking_plane(window, "mars")                 # the least inclination: |d|
    assert math.degrees(i) == pytest.approx(29.46)
    assert math.degrees(raan) == pytest.approx(133.28 - 90.0)
    with pytest.raises(InputError, match="cannot hold the departure asymptote"):
        windows.parking_plane(window, "mars", 20.0 * DEG)


def test_a_parking_inclination_too_small_is_one_line_exit_2(tmp_path):
    result = windows_cli("--target", "mars", "--from", "2026-10-25", "--to", "2026-11-08", "--step", "2d",
                         "--tof", "290:330", "--mission-fragment", tmp_path / "m.yaml",
                         "--parking-inclination", "10 deg")
    assert result.exit_code == 2
    assert "--parking-inclination" in result.output and "Traceback" not in result.output


def test_a_window_on_a_bound_of_the_search_is_marked_edge(tmp_path):
    """Departures to 19 October 2026 only: the 2026 Mars window's optimum (1 November) lies
    beyond, so the best the range holds is its last departure date, marked EDGE; the
    mission fragment says so too."""
    fragment = tmp_path / "edge.yaml"
    result = windows_cli("--target", "mars", "--from", "2026-09-01", "--to", "2026-10-19", "--step", "2d",
                         "--tof", "250:400", "--mission-fragment", fragment)
    assert result.exit_code == 0, result.output
    assert "EDGE: #1 lies on the last departure date searched" in result.output
    assert "AT THE EDGE of the search: on the last departure date searched" in fragment.read_text()
    data = yaml.safe_load(fragment.read_text())
    assert data["epoch"].startswith("2026-10-19")
