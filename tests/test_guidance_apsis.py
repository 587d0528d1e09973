"""The apsis velocity (rocketsim.guidance.apsis) against the orbit it is meant to give.

Reference: the classical elements of the state (rocketsim.frames.elements, Vallado's
algorithm 9, itself checked in tests/test_elements.py): from ``r`` and the apsis velocity
the orbit's apsides are ``|r|`` and the other one asked for, its plane that of the
present velocity, and the motion goes the same way.
"""

import numpy as np
import pytest

from rocketsim.constants import MARS_MU, MARS_RADIUS_EQ, MOON_MU, MOON_RADIUS
from rocketsim.frames.elements import state_to_elements
from rocketsim.guidance.apsis import apsis_velocity


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
