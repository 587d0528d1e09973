"""A campaign's insertion columns: the orbit a run reached against the mission's target.

The states are built from their elements by hand (vis-viva at periapsis, the
plane turned by the inclination), so the errors the columns give are checked
against the orbit the state was made on, not against the conversion the module
uses. A bad ``insertion:`` block, or one in a campaign whose scenario names no
target orbit, is refused at its line with exit status 2 before anything flies.
"""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest
from click.testing import CliRunner

from rocketsim.campaigns.insertion import InsertionTolerance, insertion_columns, report_lines
from rocketsim.constants import EARTH_MU, EARTH_RADIUS_EQ
from rocketsim.frames.elements import Elements
from rocketsim.frames.mean_elements import state_of_mean_elements
from rocketsim_cli.main import main
from tests.campaign_files import write_arc

TARGET_ALTITUDE = 200e3
TARGET_INCLINATION = math.radians(51.6)
TOLERANCE = InsertionTolerance(periapsis="2 km", apoapsis="2 km", inclination="0.02 deg")
PREFIX = "stack.insertion"


def periapsis_state(periapsis_altitude: float, apoapsis_altitude: float, inclination: float):
    """Position and velocity at the periapsis of that orbit, on the ascending node (the
    x axis): the speed from vis-viva, along the plane's horizontal."""
    rp, ra = EARTH_RADIUS_EQ + periapsis_altitude, EARTH_RADIUS_EQ + apoapsis_altitude
    speed = math.sqrt(EARTH_MU * (2.0 / rp - 2.0 / (rp + ra)))
    return (np.array([rp, 0.0, 0.0]),
            speed * np.array([0.0, math.cos(inclination), math.sin(inclination)]))


def fake_run(states, orbit_time: float | None):
    """A run of one body ``stack`` whose samples are ``states`` (``(t, r, v)``) and whose
    ``orbit`` event, if any, is at ``orbit_time``."""
    table = pd.DataFrame({f"{kind}_{c}_{unit}": [float(s[i][j]) for s in states]
                          for i, kind, unit in ((1, "position", "m"), (2, "velocity", "m_s"))
                          for j, c in enumerate("xyz")},
                         index=pd.Index([s[0] for s in states], name="t_s"))
    events = pd.DataFrame([{"t_s": orbit_time, "body": "stack", "name": "orbit"}] if orbit_time is not None
                          else [], columns=["t_s", "body", "name"])
    body = SimpleNamespace(name="stack", events=events, table=lambda: table)
    return SimpleNamespace(bodies={"stack": body})


def target(elements: str):
    return SimpleNamespace(altitude=TARGET_ALTITUDE, inclination=TARGET_INCLINATION, elements=elements)


def test_the_first_sample_after_the_orbit_event_gives_the_insertion_orbit():
    """Osculating target: a state at the periapsis of 200.5 x 210 km at 51.61 deg, sampled
    just after the orbit event (an earlier sample, still burning, is not read)."""
    burning = periapsis_state(150e3, 180e3, TARGET_INCLINATION)
    inserted = periapsis_state(200.5e3, 210e3, TARGET_INCLINATION + math.radians(0.01))
    run = fake_run([(530.0, *burning), (537.02, *inserted)], orbit_time=537.01)
    row = insertion_columns(run, target("osculating"), TOLERANCE)
    assert row[f"{PREFIX}.time_s"] == 537.02
    assert row[f"{PREFIX}.periapsis_error_m"] == pytest.approx(500.0, abs=1e-3)
    assert row[f"{PREFIX}.apoapsis_error_m"] == pytest.approx(10e3, abs=1e-3)
    assert row[f"{PREFIX}.inclination_error_deg"] == pytest.approx(0.01, abs=1e-9)
    assert row[f"{PREFIX}.within_tolerance"] == 0.0          # the apoapsis is 10 km off
    wide = InsertionTolerance(periapsis="1 km", apoapsis="11 km", inclination="0.011 deg")
    assert insertion_columns(run, target("osculating"), wide)[f"{PREFIX}.within_tolerance"] == 1.0


def test_a_mean_target_is_measured_in_mean_elements():
    """The osculating state of the mean 200 km circle at 51.6 deg, 40 deg past the node:
    its osculating apsides are kilometres from 200 km (J2's short-period terms), its mean
    elements are the circle's."""
    r, v = state_of_mean_elements(Elements(EARTH_RADIUS_EQ + TARGET_ALTITUDE, 0.0, TARGET_INCLINATION, 0.3, 0.0,
                                           math.radians(40.0), EARTH_MU))
    run = fake_run([(540.0, r, v)], orbit_time=540.0)
    osculating = insertion_columns(run, target("osculating"), TOLERANCE)
    assert max(abs(osculating[f"{PREFIX}.periapsis_error_m"]), abs(osculating[f"{PREFIX}.apoapsis_error_m"])) > 2e3
    mean = insertion_columns(run, target("mean"), TOLERANCE)
    for error in ("periapsis_error_m", "apoapsis_error_m"):
        assert abs(mean[f"{PREFIX}.{error}"]) < 20.0
    assert abs(mean[f"{PREFIX}.inclination_error_deg"]) < 1e-4
    assert mean[f"{PREFIX}.within_tolerance"] == 1.0


def test_a_run_that_never_reached_orbit_counts_as_outside():
    run = fake_run([(300.0, *periapsis_state(-50e3, 180e3, TARGET_INCLINATION))], orbit_time=None)
    row = insertion_columns(run, target("mean"), TOLERANCE)
    assert math.isnan(row[f"{PREFIX}.periapsis_error_m"]) and row[f"{PREFIX}.within_tolerance"] == 0.0


def test_the_report_gives_the_share_within_with_its_interval():
    """3 of 4 ok runs within (a fifth run failed and is not counted): 75 %, with the
    exact Clopper-Pearson interval of 3 in 4, [19.4 %, 99.4 %]."""
    results = pd.DataFrame({f"{PREFIX}.within_tolerance": [1.0, 1.0, 0.0, 1.0, 0.0],
                            f"{PREFIX}.periapsis_error_m": [100.0, -200.0, 3000.0, 50.0, math.nan],
                            f"{PREFIX}.apoapsis_error_m": [10.0, 20.0, 30.0, 40.0, math.nan],
                            f"{PREFIX}.inclination_error_deg": [0.0, 0.001, -0.002, 0.0, math.nan]})
    ok = np.array([True, True, True, True, False])
    lines = report_lines({"periapsis_m": 2e3, "apoapsis_m": 2e3, "inclination_deg": 0.02}, results, ok)
    assert "stack: 3 of 4 ok runs, 75 % [19.4 %, 99.4 %]" in lines[1]
    assert "largest |error| 3000" in lines[2]
    assert report_lines(None, results, ok) == []


CAMPAIGN = """\
name: insertion
scenario: arc.yaml
runs: 2
seed: 1
insertion: {periapsis: 2 km, apoapsis: 2 km, inclination: 0.02 deg}
"""


@pytest.mark.parametrize("change, expected", [
    (("inclination: 0.02 deg", "inclination: 0.02"), "insertion.inclination"),
    (("periapsis: 2 km", "periapsis: 2 kg"), "unknown unit 'kg'"),
    # the arc's mission has no target orbit to measure an insertion against
    (("", ""), "names none (mission.target.orbit"),
])
def test_a_bad_insertion_block_is_refused_at_its_line(tmp_path, change, expected):
    campaign = write_arc(tmp_path, CAMPAIGN.replace(*change))
    out = tmp_path / "out"
    result = CliRunner().invoke(main, ["campaign", "run", str(campaign), "-o", str(out), "--workers", "1"])
    assert result.exit_code == 2, result.output
    assert result.output.startswith(f"error: {campaign}:5:"), result.output
    assert expected in result.output and "Traceback" not in result.output
    assert not out.exists()
