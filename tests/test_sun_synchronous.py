"""The sun-synchronous inclination (rocketsim.bodies.sun_synchronous) and the
mission target ``inclination: sso``.

References: the seed description's figure (docs/physics.md#j2), "+0.986 deg a
day that makes a 700 km orbit at 98.2 deg sun-synchronous"; and the J2 nodal
rate of Vallado (4th ed., eq. 9-41) solved for the inclination by bisection in
tests/test_electron_sso.py (a different route to the same condition).
"""

import math

import pytest

from rocketsim.bodies.sun_synchronous import sun_synchronous_inclination
from rocketsim.scenario.load import load
from tests.test_electron_sso import sun_synchronous_inclination as by_bisection


def test_700_km_is_the_physics_model_s_98_2_deg():
    assert math.degrees(sun_synchronous_inclination(700e3)) == pytest.approx(98.2, abs=0.02)


@pytest.mark.parametrize("altitude_km", [300.0, 500.0, 800.0, 1500.0])
def test_the_closed_form_agrees_with_the_rate_equation_solved_by_bisection(altitude_km):
    assert sun_synchronous_inclination(altitude_km * 1e3) == pytest.approx(by_bisection(altitude_km * 1e3),
                                                                           abs=1e-9)


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
