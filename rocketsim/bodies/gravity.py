"""Gravity of an oblate body: point mass plus the full three-dimensional J2 term.

One formula serves Earth, the Moon and Mars; each is evaluated in a frame whose
``z`` axis is that body's pole (for Earth, the ECI frame). From
docs/physics.md#j2, with ``r = |r|``::

    a = -mu r / r^3 - (3/2) J2 mu R^2 / r^5 [x(1 - 5z^2/r^2), y(1 - 5z^2/r^2), z(3 - 5z^2/r^2)]

which is ``-grad U`` of ``U = -mu/r [1 - J2 (R/r)^2 (3 sin^2(phi_c) - 1)/2]``
(tests/unit/bodies/test_gravity.py checks it against the gradient).
"""

from __future__ import annotations

import math

import numpy as np

from rocketsim.jit import njit
from rocketsim.constants import EARTH_J2, EARTH_MU, EARTH_RADIUS_EQ


@njit(inline="always")
def point_mass_j2(x, y, z, mu, radius, j2):
    """Acceleration (m/s^2) at ``(x, y, z)`` (m, body-pole frame) as a tuple.

    ``mu`` in m^3/s^2, ``radius`` the reference (equatorial) radius in m,
    ``j2`` the unnormalised zonal harmonic (0 for a point mass).
    """
    r2 = x * x + y * y + z * z
    r = math.sqrt(r2)
    inv_r3 = 1.0 / (r2 * r)
    k = 1.5 * j2 * mu * radius * radius * inv_r3 / r2
    s = 5.0 * z * z / r2
    ax = -mu * x * inv_r3 - k * x * (1.0 - s)
    ay = -mu * y * inv_r3 - k * y * (1.0 - s)
    az = -mu * z * inv_r3 - k * z * (3.0 - s)
    return ax, ay, az


@njit
def _point_mass_j2_many(r, mu, radius, j2, out):
    for n in range(r.shape[0]):
        out[n, 0], out[n, 1], out[n, 2] = point_mass_j2(r[n, 0], r[n, 1], r[n, 2], mu, radius, j2)


def gravity(r, mu=EARTH_MU, radius=EARTH_RADIUS_EQ, j2=EARTH_J2) -> np.ndarray:
    """Point mass + J2 acceleration (m/s^2) at ``r`` ((3,) or (N, 3), m).

    Defaults are Earth's (WGS84 mu and a, EGM96 J2); ``r`` in a frame whose
    ``z`` axis is the body's pole (ECI or Earth-fixed for Earth).
    """
    r = np.asarray(r, dtype=float)
    flat = np.ascontiguousarray(r.reshape(-1, 3))
    out = np.empty_like(flat)
    _point_mass_j2_many(flat, mu, radius, j2, out)
    return out.reshape(r.shape)
