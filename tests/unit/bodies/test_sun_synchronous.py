"""The sun-synchronous inclination (rocketsim.bodies.sun_synchronous) and the
mission target ``inclination: sso``.

References: the figure of docs/physics.md#j2, "+0.986 deg a day that makes a 700 km
orbit at 98.2 deg sun-synchronous"; the first-order J2 nodal rate of Vallado
(4th ed., eq. 9-41) solved for the inclination by bisection in
tests/flights/test_electron_sso.py (a different route to the same condition, without
Brouwer's second-order term); and the simulator's own J2 rails flown for 30
days, the node measured on the flown orbit's Kozai mean elements.
"""

import math

import numpy as np
import pytest

from rocketsim.bodies.sun_synchronous import nodal_rate, sun_synchronous_inclination
from rocketsim.constants import (EARTH_J2, EARTH_MU, EARTH_RADIUS_EQ, EARTH_RADIUS_POLAR,
                                 TROPICAL_YEAR)
from rocketsim.dynamics import nbody, rails
from rocketsim.layout import R, V, make_params, make_state
from rocketsim.frames.mean_elements import mean_elements_of_state
from rocketsim.scenario.load import load
from rocketsim.sim.start import start_state
from tests.flights.test_electron_sso import sun_synchronous_inclination as by_bisection

DAY = 86400.0


def test_700_km_is_the_physics_model_s_98_2_deg():
    assert math.degrees(sun_synchronous_inclination(700e3)) == pytest.approx(98.2, abs=0.02)


@pytest.mark.parametrize("altitude_km", [300.0, 500.0, 800.0, 1500.0])
def test_the_inclination_agrees_with_the_first_order_rate_solved_by_bisection(altitude_km):
    # Brouwer's second-order term (it slows the node by 0.08 %) raises the inclination
    # by 0.0062-0.0069 deg.
    ours = sun_synchronous_inclination(altitude_km * 1e3)
    first = by_bisection(altitude_km * 1e3)
    assert 0.006 < math.degrees(ours - first) < 0.007
    assert nodal_rate(EARTH_RADIUS_EQ + altitude_km * 1e3, 0.0, ours) == pytest.approx(
        2 * math.pi / TROPICAL_YEAR, rel=1e-12)


SSO_START = """\
name: sso-start
vehicle: {{name: probe, rigid_body: {{mass: 10 kg, inertia: [1, 1, 1]}}}}
mission:
  epoch: 2026-11-26T12:00:00Z
  start: {{orbit: {{altitude: 700 km, raan: 40 deg, {extra}}}}}
  duration: 1 s
"""


def _mean_node_drift(write, extra):
    """Fly the file's starting orbit 30 days on the parking-orbit rails (Kepler + J2,
    no air at 700 km) and fit the Kozai mean node of the flown states, every 6 h:
    the drift (deg/day) of that node from the mean Sun's 360 deg per tropical year.
    Step 20 s (not the flight's 20 ms: 30 days would be 130 million steps); RK4 at
    20 s on a 99-minute orbit gives the drift of a 10 s step within 6e-7 deg/day."""
    mission = load(write("sso.yaml", SSO_START.format(extra=extra))).scenario.mission
    r, v, _ = start_state(mission, None, 0.0)
    p = make_params(10.0, (1.0, 1.0, 1.0), EARTH_MU, EARTH_RADIUS_EQ, EARTH_J2, EARTH_RADIUS_POLAR)
    field, air = nbody.make_field("earth", 2461006.0, bodies=()), nbody.no_air()
    y, h, per = make_state(r, v), 20.0, 1080
    days, nodes = [], []
    for k in range(121):
        days.append(k * per * h / DAY)
        nodes.append(mean_elements_of_state(y[R:R + 3], y[V:V + 3]).raan)
        y, _ = rails.advance_rails(y, k * per, h, per, p, field, air, p[1:4], rails.FREE)
    rate = math.degrees(np.polyfit(days, np.unwrap(nodes), 1)[0])
    return rate - math.degrees(2 * math.pi / TROPICAL_YEAR) * DAY


def test_a_sun_synchronous_start_stays_sun_synchronous(write):
    # Mean elements (the default): measured drift -2e-6 deg/day (a first-order
    # inclination leaves -0.0008, the size of Brouwer's second-order term).
    assert abs(_mean_node_drift(write, "inclination: sso")) < 1e-3


def test_osculating_numbers_as_a_start_drift_unless_the_inclination_allows_for_them(write):
    # The same numbers read as osculating elements: the start's mean semi-major axis
    # is 9 km lower, so 98.1880 deg, the first-order sun-synchronous inclination of the
    # numbers as given (what 'sso' was before mean elements), drifts by +0.0043 deg/day; 'sso' on osculating
    # elements takes the inclination of their mean elements and keeps the Sun (-2e-6).
    assert _mean_node_drift(write, "elements: osculating, inclination: 98.1880 deg") > 4e-3
    assert abs(_mean_node_drift(write, "elements: osculating, inclination: sso")) < 1e-3


def test_no_sun_synchronous_orbit_far_out():
    with pytest.raises(ValueError, match="no sun-synchronous orbit"):
        sun_synchronous_inclination(7000e3)


MISSION = """\
name: sso
vehicle: {{name: probe, rigid_body: {{mass: 10 kg, inertia: [1, 1, 1]}}}}
mission:
  epoch: 2026-11-26T12:00:00Z
  start: {{orbit: {{altitude: 500 km, inclination: 97 deg}}}}
  duration: 1 s
  target: {{orbit: {{altitude: {altitude}, inclination: sso}}}}
"""


def test_a_target_of_sso_reads_as_the_inclination(write, cli):
    path = write("sso.yaml", MISSION.format(altitude="600 km"))
    target = load(path).scenario.mission.target.orbit
    assert target.inclination == pytest.approx(sun_synchronous_inclination(600e3), rel=1e-15)
    bad = write("far.yaml", MISSION.format(altitude="8000 km"))
    result = cli("validate", bad)
    assert result.exit_code == 2 and "no sun-synchronous orbit" in result.output


def test_an_osculating_target_takes_the_inclination_of_its_mean_elements(write):
    # 'altitude: 600 km, elements: osculating': the circular orbit of radius R + 600 km
    # at its node, whose mean semi-major axis is 9.3 km lower; its mean elements are
    # sun-synchronous (the rate equal to the Sun's to 1e-9) and its inclination is
    # below the mean-element target's (a lower orbit turns its node faster).
    from rocketsim.frames.elements import Elements
    from rocketsim.frames.mean_elements import osculating_to_mean
    text = MISSION.format(altitude="600 km, elements: osculating")
    target = load(write("osc.yaml", text)).scenario.mission.target.orbit
    mean = osculating_to_mean(Elements(EARTH_RADIUS_EQ + 600e3, 0.0, target.inclination, 0.0, 0.0, 0.0))
    assert EARTH_RADIUS_EQ + 600e3 - mean.a == pytest.approx(9.3e3, abs=0.1e3)
    assert nodal_rate(mean.a, mean.e, mean.i) == pytest.approx(2 * math.pi / TROPICAL_YEAR, rel=1e-9)
    assert target.inclination < sun_synchronous_inclination(600e3)


def test_sso_is_refused_about_another_body(write, cli):
    text = MISSION.replace("{{altitude: 500 km, inclination: 97 deg}}",
                           "{{body: mars, altitude: 500 km, inclination: sso}}").format(altitude="600 km")
    result = cli("validate", write("mars.yaml", text))
    assert result.exit_code == 2 and "sun-synchronous about Earth only" in result.output
