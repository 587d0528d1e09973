"""IAU 1976 precession (Lieske et al. 1977) and the ecliptic-of-date -> J2000 turn.

The series VSOP87D and ELP2000-82B give positions on the mean ecliptic and
equinox *of date*; the simulator works in the J2000 mean equatorial frame
(``x`` to the J2000 equinox, ``z`` to the J2000 mean pole). The turn is

    r_J2000 = P(T)^T  R1(-eps_A(T))  r_ecliptic_of_date

with the IAU 1976 angles, ``T`` in Julian centuries of TT from J2000
(Lieske, Lederle, Fricke & Morando 1977, A&A 58, 1, Table 5):

    zeta_A  = 2306.2181" T + 0.30188" T^2 + 0.017998" T^3
    z_A     = 2306.2181" T + 1.09468" T^2 + 0.018203" T^3
    theta_A = 2004.3109" T - 0.42665" T^2 - 0.041833" T^3
    eps_A   = 84381.448" - 46.8150" T - 0.00059" T^2 + 0.001813" T^3

``P = R3(-z_A) R2(theta_A) R3(-zeta_A)`` carries J2000 mean equatorial
coordinates to the mean equator and equinox of date; ``eps_A`` is the mean
obliquity of date. ``R1, R2, R3`` are the usual frame (passive) rotations.
Angles are in radians, times in Julian centuries unless a name says so.
"""

from __future__ import annotations

import math

import numpy as np

from rocketsim._jit import njit
from rocketsim.constants import ARCSEC, DAYS_PER_JULIAN_CENTURY, J2000_JD

# Lieske et al. 1977 polynomial coefficients, arcseconds (constant, T, T^2, T^3)
ZETA = (0.0, 2306.2181, 0.30188, 0.017998)
Z = (0.0, 2306.2181, 1.09468, 0.018203)
THETA = (0.0, 2004.3109, -0.42665, -0.041833)
EPSILON = (84381.448, -46.8150, -0.00059, 0.001813)   # mean obliquity of date


@njit
def _poly(c, t):
    """Value and derivative of c0 + c1 t + c2 t^2 + c3 t^3, times ARCSEC."""
    value = c[0] + t * (c[1] + t * (c[2] + t * c[3]))
    rate = c[1] + t * (2.0 * c[2] + t * 3.0 * c[3])
    return value * ARCSEC, rate * ARCSEC


@njit
def precession_angles(T):
    """``(zeta_A, z_A, theta_A, eps_A)`` in radians at ``T`` centuries of TT."""
    return (_poly(ZETA, T)[0], _poly(Z, T)[0], _poly(THETA, T)[0],
            _poly(EPSILON, T)[0])


@njit
def _rotation(axis, angle):
    """Frame rotation R_axis(angle) (axis 0, 1, 2) and its derivative d/dangle."""
    c = math.cos(angle)
    s = math.sin(angle)
    m = np.zeros((3, 3))
    d = np.zeros((3, 3))
    i = (axis + 1) % 3
    j = (axis + 2) % 3
    m[axis, axis] = 1.0
    m[i, i] = c
    m[j, j] = c
    m[i, j] = s
    m[j, i] = -s
    d[i, i] = -s
    d[j, j] = -s
    d[i, j] = c
    d[j, i] = -c
    return m, d


@njit
def ecliptic_of_date_to_j2000(T):
    """Matrix ``M`` with ``r_J2000_equatorial = M r_ecliptic_of_date``, and dM/dT.

    ``T``: Julian centuries of TT from J2000. ``M = R3(zeta) R2(-theta)
    R3(z) R1(-eps_A)``; ``dM/dT`` is per Julian century (the product rule on
    the four rotations), so a velocity is ``M v + dM/dT r / (36525 * 86400)``.
    """
    zeta, dzeta = _poly(ZETA, T)
    z, dz = _poly(Z, T)
    theta, dtheta = _poly(THETA, T)
    eps, deps = _poly(EPSILON, T)
    a, da = _rotation(2, zeta)
    b, db = _rotation(1, -theta)
    c, dc = _rotation(2, z)
    e, de = _rotation(0, -eps)
    ce = c @ e
    bce = b @ ce
    m = a @ bce
    dm = (da * dzeta) @ bce - a @ ((db * dtheta) @ ce) \
        + a @ (b @ ((dc * dz) @ e)) - a @ (b @ (c @ (de * deps)))
    return m, dm


def precession_matrix(jd_tt: float) -> np.ndarray:
    """IAU 1976 precession matrix ``P``: J2000 mean equatorial -> mean equator
    and equinox of date, at the Julian date ``jd_tt`` (TT)."""
    zeta, z, theta, _ = precession_angles((jd_tt - J2000_JD) / DAYS_PER_JULIAN_CENTURY)
    c, _ = _rotation(2, -z)
    b, _ = _rotation(1, theta)
    a, _ = _rotation(2, -zeta)
    return c @ b @ a


@njit
def spherical_to_cartesian(lon, lat, dist, dlon, dlat, ddist):
    """Cartesian position and its rate from spherical coordinates and rates.

    ``lon``, ``lat`` in radians, ``dist`` in any length unit; the rates in the
    same units per any time unit, which the velocity then carries.
    """
    cl = math.cos(lon)
    sl = math.sin(lon)
    cb = math.cos(lat)
    sb = math.sin(lat)
    r = np.empty(3)
    v = np.empty(3)
    r[0] = dist * cb * cl
    r[1] = dist * cb * sl
    r[2] = dist * sb
    v[0] = ddist * cb * cl - dist * sb * cl * dlat - dist * cb * sl * dlon
    v[1] = ddist * cb * sl - dist * sb * sl * dlat + dist * cb * cl * dlon
    v[2] = ddist * sb + dist * cb * dlat
    return r, v
