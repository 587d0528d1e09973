"""The escape hyperbola's velocity for a given excess velocity (rocketsim.flight.maneuvers).

Reference: the universal-variable Kepler propagator (rocketsim.orbits.kepler,
itself checked against Vallado's worked examples): a hyperbola propagated
3e9 s out gives its excess velocity vector; the closed form must return the
hyperbola's own velocity at its start and at a point 3e6 s later.
"""

import numpy as np

from rocketsim.constants import EARTH_MU
from rocketsim.flight.maneuvers import hyperbola_velocity
from rocketsim.orbits.kepler import propagate


def test_the_closed_form_lands_on_the_propagated_hyperbola():
    r0 = np.array([6.578e6, 0.0, 0.0])
    v0 = np.array([0.0, 11.5e3, 1.0e3])
    energy = 0.5 * v0 @ v0 - EARTH_MU / np.linalg.norm(r0)
    _, v_far = propagate(EARTH_MU, r0, v0, 3e9)
    v_inf = v_far / np.linalg.norm(v_far) * np.sqrt(2.0 * energy)
    for dt in (0.0, 2e3, 3e6):
        r, v = (r0, v0) if dt == 0.0 else propagate(EARTH_MU, r0, v0, dt)
        np.testing.assert_allclose(hyperbola_velocity(r, v_inf, EARTH_MU), v, rtol=0, atol=1e-6)
