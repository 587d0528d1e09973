"""An independent n-body field for the tests: numpy, the ephemeris in J2000, heliocentric sums.

The vehicle's acceleration relative to a central body ``c`` is written here as
the difference of two heliocentric accelerations, the vehicle's and the
centre's, each a plain sum of point-mass pulls (plus the centre's J2 about its
pole, from ``rocketsim.bodies.gravity.gravity`` in pole axes). It shares no
code with ``rocketsim.dynamics.nbody`` but the ephemeris, and serves as the
right-hand side of the DOP853 reference integrations.
"""

from __future__ import annotations

import numpy as np
from scipy.integrate import solve_ivp

from rocketsim.bodies.gravity import gravity
from rocketsim.constants import EARTH_MU, MARS_MU, MOON_MU, SECONDS_PER_DAY, SUN_MU
from rocketsim.ephemeris.solar_system import states

MUS = {"sun": SUN_MU, "earth": EARTH_MU, "moon": MOON_MU, "mars": MARS_MU}


def field_j2000(r_frame, jd_tt, center, rotation, bodies, central=(0.0, 1.0, 0.0)):
    """Acceleration (frame axes) of a vehicle at ``r_frame`` from ``center``.

    ``rotation``: frame -> J2000; ``central``: (mu, radius, J2) of the centre
    in the frame (``z`` its pole); ``bodies``: names pulling besides the centre.
    """
    helio = states(jd_tt, center="sun")
    x_c = helio[center][0]
    x_v = x_c + rotation @ np.asarray(r_frame, float)
    a_vehicle = np.zeros(3)
    a_center = np.zeros(3)
    for name in bodies:
        if name == center:
            continue
        x_k = helio[name][0]
        a_vehicle += MUS[name] * (x_k - x_v) / np.linalg.norm(x_k - x_v) ** 3
        a_center += MUS[name] * (x_k - x_c) / np.linalg.norm(x_k - x_c) ** 3
    mu, radius, j2 = central
    return gravity(r_frame, mu=mu, radius=radius, j2=j2) + rotation.T @ (a_vehicle - a_center)


def reference_orbit(r0, v0, t0, t1, jd0, center, rotation, bodies, central, rtol=1e-13,
                    atol=1e-6):
    """DOP853 from mission time ``t0`` to ``t1`` (s); returns (r, v) at ``t1``."""
    def rhs(t, y):
        a = field_j2000(y[:3], jd0 + t / SECONDS_PER_DAY, center, rotation, bodies, central)
        return np.concatenate((y[3:], a))
    solution = solve_ivp(rhs, (t0, t1), np.concatenate((r0, v0)), method="DOP853", rtol=rtol,
                         atol=atol)
    assert solution.success, solution.message
    return solution.y[:3, -1], solution.y[3:, -1]
