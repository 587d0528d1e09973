"""The apsis velocity and the impact parameter (rocketsim.guidance.apsis) against the
orbits they are meant to give.

Reference for the apsis velocity: the classical elements of the state
(rocketsim.frames.elements, Vallado's algorithm 9, itself checked in
tests/unit/frames/test_elements.py): from ``r`` and the apsis velocity the orbit's apsides are
``|r|`` and the other one asked for, its plane that of the present velocity, and the
motion goes the same way. For the impact parameter: the hyperbola's geometry, its
asymptote's miss distance is its semi-minor axis ``|a| sqrt(e^2 - 1)`` with
``a = -mu / v_inf^2`` and ``e = 1 + r_p v_inf^2 / mu`` (Bate, Mueller & White,
*Fundamentals of Astrodynamics*, 1971, sec. 8.3); and a state far out with the
hyperbola's energy and angular momentum ``b v_inf`` has its periapsis at ``r_p``.
"""

import numpy as np
import pytest

from rocketsim.constants import MARS_MU, MARS_RADIUS_EQ, MOON_MU, MOON_RADIUS
from rocketsim.frames.elements import state_to_elements
from rocketsim.guidance.apsis import apsis_velocity, impact_parameter


@pytest.mark.parametrize("mu, r, other", [
    (MOON_MU, MOON_RADIUS + 100e3, MOON_RADIUS + 100e3),          # a lunar circularisation
    (MARS_MU, MARS_RADIUS_EQ + 400e3, MARS_RADIUS_EQ + 33000e3),  # a Mars capture at periapsis
    (MARS_MU, MARS_RADIUS_EQ + 300e3, MARS_RADIUS_EQ - 40e3),     # a deorbit: here the apoapsis
])
def test_the_apsis_velocity_gives_the_orbit_of_those_apsides(mu, r, other):
    position = r * np.array([0.6, -0.48, 0.64])
    velocity = np.array([2000.0, 1500.0, -500.0]) + 300.0 * position / r     # climbing, any plane
    target = apsis_velocity(position, velocity, other, mu)
    elements = state_to_elements(position, target, mu)
    assert elements.periapsis == pytest.approx(min(r, other), rel=1e-12)
    if other != r:
        assert elements.apoapsis == pytest.approx(max(r, other), rel=1e-12)
    else:
        assert elements.e < 1e-12
    assert target @ position == pytest.approx(0.0, abs=1e-9 * r)                  # horizontal
    h, h_then = np.cross(position, velocity), np.cross(position, target)
    assert np.linalg.norm(np.cross(h, h_then)) < 1e-12 * np.linalg.norm(h) * np.linalg.norm(h_then)   # one plane
    assert h @ h_then > 0.0                                                         # the same way round


@pytest.mark.parametrize("mu, periapsis, v_inf", [
    (MOON_MU, MOON_RADIUS + 100e3, 800.0),            # a lunar arrival
    (MARS_MU, MARS_RADIUS_EQ + 400e3, 2650.0),        # the 2026 window's Mars arrival
])
def test_the_impact_parameter_is_the_hyperbolas_semi_minor_axis(mu, periapsis, v_inf):
    b = impact_parameter(periapsis, v_inf, mu)
    a, e = -mu / v_inf ** 2, 1.0 + periapsis * v_inf ** 2 / mu
    assert b == pytest.approx(abs(a) * np.sqrt(e * e - 1.0), rel=1e-12)
    # a state 1e9 m out with the hyperbola's energy and angular momentum b v_inf (the
    # asymptote's miss distance times the speed along it): its periapsis is r_p
    position = np.array([-1e9, 0.0, 0.0])
    speed = np.sqrt(v_inf ** 2 + 2.0 * mu / 1e9)
    across = b * v_inf / 1e9
    velocity = np.array([np.sqrt(speed ** 2 - across ** 2), -across, 0.0])
    assert state_to_elements(position, velocity, mu).periapsis == pytest.approx(periapsis, rel=1e-9)
