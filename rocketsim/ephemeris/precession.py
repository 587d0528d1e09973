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

import numpy as np

from rocketsim.jit import njit
from rocketsim.constants import ARCSEC, DAYS_PER_JULIAN_CENTURY, J2000_JD
from rocketsim.ephemeris.sincos import sincos

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


# 3x3 matrices in the kernels are 9-tuples, row-major (no allocation per call).

@njit
def _rotation(axis, angle):
    """Frame rotation R_axis(angle) (axis 0, 1, 2) and d/dangle, as 9-tuples."""
    s, c = sincos(angle)
    if axis == 0:
        return (1.0, 0.0, 0.0, 0.0, c, s, 0.0, -s, c), \
            (0.0, 0.0, 0.0, 0.0, -s, c, 0.0, -c, -s)
    if axis == 1:
        return (c, 0.0, -s, 0.0, 1.0, 0.0, s, 0.0, c), \
            (-s, 0.0, -c, 0.0, 0.0, 0.0, c, 0.0, -s)
    return (c, s, 0.0, -s, c, 0.0, 0.0, 0.0, 1.0), \
        (-s, c, 0.0, -c, -s, 0.0, 0.0, 0.0, 0.0)


@njit
def _mul(a, b):
    """Product of two 3x3 matrices given as row-major 9-tuples."""
    return (a[0] * b[0] + a[1] * b[3] + a[2] * b[6],
            a[0] * b[1] + a[1] * b[4] + a[2] * b[7],
            a[0] * b[2] + a[1] * b[5] + a[2] * b[8],
            a[3] * b[0] + a[4] * b[3] + a[5] * b[6],
            a[3] * b[1] + a[4] * b[4] + a[5] * b[7],
            a[3] * b[2] + a[4] * b[5] + a[5] * b[8],
            a[6] * b[0] + a[7] * b[3] + a[8] * b[6],
            a[6] * b[1] + a[7] * b[4] + a[8] * b[7],
            a[6] * b[2] + a[7] * b[5] + a[8] * b[8])


@njit
def _scale(a, k):
    return (a[0] * k, a[1] * k, a[2] * k, a[3] * k, a[4] * k, a[5] * k,
            a[6] * k, a[7] * k, a[8] * k)


@njit
def _add(a, b):
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2], a[3] + b[3], a[4] + b[4],
            a[5] + b[5], a[6] + b[6], a[7] + b[7], a[8] + b[8])


@njit
def apply(m, x, y, z):
    """``m @ (x, y, z)`` for a 9-tuple matrix; returns a 3-tuple."""
    return (m[0] * x + m[1] * y + m[2] * z,
            m[3] * x + m[4] * y + m[5] * z,
            m[6] * x + m[7] * y + m[8] * z)


@njit
def turn(T):
    """Ecliptic of date -> J2000 equatorial matrix and its rate, as 9-tuples.

    ``T``: Julian centuries of TT from J2000. ``M = R3(zeta) R2(-theta) R3(z)
    R1(-eps_A)``; ``dM/dT`` (per Julian century) by the product rule, so a
    velocity is ``M v + dM/dT r / (36525 * 86400 s)``.
    """
    zeta, dzeta = _poly(ZETA, T)
    z, dz = _poly(Z, T)
    theta, dtheta = _poly(THETA, T)
    eps, deps = _poly(EPSILON, T)
    a, da = _rotation(2, zeta)
    b, db = _rotation(1, -theta)
    c, dc = _rotation(2, z)
    e, de = _rotation(0, -eps)
    ce = _mul(c, e)
    bce = _mul(b, ce)
    ab = _mul(a, b)
    m = _mul(a, bce)
    dm = _add(_add(_scale(_mul(da, bce), dzeta), _scale(_mul(a, _mul(db, ce)), -dtheta)),
              _add(_scale(_mul(ab, _mul(dc, e)), dz), _scale(_mul(ab, _mul(c, de)), -deps)))
    return m, dm


def ecliptic_of_date_to_j2000(jd_tt: float) -> tuple[np.ndarray, np.ndarray]:
    """3x3 ``M`` with ``r_J2000_equatorial = M r_ecliptic_of_date`` at ``jd_tt``
    (TT), and ``dM/dt`` per day."""
    m, dm = turn((jd_tt - J2000_JD) / DAYS_PER_JULIAN_CENTURY)
    return np.array(m).reshape(3, 3), np.array(dm).reshape(3, 3) / DAYS_PER_JULIAN_CENTURY


def precession_matrix(jd_tt: float) -> np.ndarray:
    """IAU 1976 precession matrix ``P``: J2000 mean equatorial -> mean equator
    and equinox of date, at the Julian date ``jd_tt`` (TT)."""
    zeta, z, theta, _ = precession_angles((jd_tt - J2000_JD) / DAYS_PER_JULIAN_CENTURY)
    m = _mul(_mul(_rotation(2, -z)[0], _rotation(1, theta)[0]), _rotation(2, -zeta)[0])
    return np.array(m).reshape(3, 3)


@njit
def spherical_to_cartesian(lon, lat, dist, dlon, dlat, ddist):
    """Cartesian position and its rate (3-tuples) from spherical coordinates.

    ``lon``, ``lat`` in radians, ``dist`` in any length unit; the rates in the
    same units per any time unit, which the velocity then carries.
    """
    sl, cl = sincos(lon)
    sb, cb = sincos(lat)
    r = (dist * cb * cl, dist * cb * sl, dist * sb)
    v = (ddist * cb * cl - dist * sb * cl * dlat - dist * cb * sl * dlon,
         ddist * cb * sl - dist * sb * sl * dlat + dist * cb * cl * dlon,
         ddist * sb + dist * cb * dlat)
    return r, v


@njit
def to_j2000(m, dm, lon, lat, dist, dlon, dlat, ddist, per_century):
    """Spherical ecliptic-of-date position and rates -> J2000 equatorial (r, v).

    ``m``, ``dm``: :func:`turn` at the instant; the rates are per unit of time
    ``u`` and ``per_century`` is the number of ``u`` in a Julian century (so
    ``dm`` is rescaled to per ``u``). Returns two 3-tuples.
    """
    r, v = spherical_to_cartesian(lon, lat, dist, dlon, dlat, ddist)
    rj = apply(m, r[0], r[1], r[2])
    vj = apply(m, v[0], v[1], v[2])
    dr = apply(dm, r[0], r[1], r[2])
    k = 1.0 / per_century
    return rj, (vj[0] + dr[0] * k, vj[1] + dr[1] * k, vj[2] + dr[2] * k)
