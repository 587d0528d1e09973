"""WGS84 geodetic latitude, longitude and height <-> Earth-fixed Cartesian.

Ellipsoid: ``a = EARTH_RADIUS_EQ``, ``f = EARTH_FLATTENING``,
``e^2 = f (2 - f)`` (NIMA TR8350.2). Latitude is geodetic (the angle of the
ellipsoid normal to the equator), longitude east of Greenwich, both radians;
height is metres along the normal above the ellipsoid (not above sea level).
Earth-fixed (ECEF) coordinates are metres.

The inverse conversion is Bowring's (1976) formula on the reduced
(parametric) latitude, applied twice (exact to float64 rounding from
-100 km to beyond geostationary height); the height then comes from
``h = p cos(lat) + z sin(lat) - a sqrt(1 - e^2 sin^2 lat)``, which is well
conditioned at the poles and on the equator alike. One compiled scalar core,
:func:`ecef_to_geodetic_njit`, serves the kernels; :func:`ecef_to_geodetic`
loops it over arrays.
"""

from __future__ import annotations

import math

import numpy as np

from rocketsim.jit import njit
from rocketsim.constants import (
    EARTH_E2,
    EARTH_FLATTENING,
    EARTH_RADIUS_EQ,
    EARTH_RADIUS_POLAR,
    WGS84_E2_SOMIGLIANA,
    WGS84_GAMMA_EQ,
    WGS84_SOMIGLIANA_K,
)

_A = EARTH_RADIUS_EQ
_B = EARTH_RADIUS_POLAR
_E2 = EARTH_E2
_EP2 = EARTH_E2 / (1.0 - EARTH_E2)          # second eccentricity squared
_ONE_MINUS_F = 1.0 - EARTH_FLATTENING
_PASSES = 2                                 # Bowring passes: exact to rounding (see below)


def geodetic_to_ecef(lat, lon, h):
    """Earth-fixed position (m) of geodetic ``lat``, ``lon`` (rad) and height ``h`` (m).

    Scalars give shape (3,); arrays (broadcast together) give (..., 3).
    """
    lat = np.asarray(lat, dtype=float)
    lon = np.asarray(lon, dtype=float)
    h = np.asarray(h, dtype=float)
    sin_lat = np.sin(lat)
    cos_lat = np.cos(lat)
    n = _A / np.sqrt(1.0 - _E2 * sin_lat * sin_lat)    # prime-vertical radius
    shape = np.broadcast_shapes(lat.shape, lon.shape, h.shape)
    out = np.empty(shape + (3,))
    out[..., 0] = (n + h) * cos_lat * np.cos(lon)
    out[..., 1] = (n + h) * cos_lat * np.sin(lon)
    out[..., 2] = (n * (1.0 - _E2) + h) * sin_lat
    return out


@njit(inline="always")     # small: typed in its callers, no kernel of its own
def ecef_to_geodetic_njit(x, y, z):
    """Geodetic ``(lat, lon, h)`` (rad, rad, m) of the Earth-fixed point ``(x, y, z)`` (m).

    Compiled scalar version for kernels. Two passes of Bowring's formula,
    carried as unnormalised (cos, sin) pairs so a pass costs one square root
    and no trigonometry; measured against the closed-form forward conversion
    the result is exact to float64 rounding (latitude 3e-16 rad, height
    < 1e-8 m) from -100 km to 10 000 km and < 3e-7 m out to 400 000 km,
    poles included (one pass would leave 6 mm at 1 000 km). The centre of the
    Earth itself has no geodetic coordinates.
    """
    return _bowring(x, y, z, _A, _B, _E2, _EP2, _ONE_MINUS_F)


@njit(inline="always")     # small: typed in its callers, no kernel of its own
def geodetic_on(x, y, z, a, b):
    """Geodetic ``(lat, lon, h)`` (rad, rad, m) of the body-fixed point ``(x, y, z)`` (m) on
    the ellipsoid of revolution of equatorial radius ``a`` and polar radius ``b`` (m; a
    sphere when equal): the Moon's or Mars's as :func:`ecef_to_geodetic_njit` is WGS84's,
    by the same two Bowring passes."""
    one_minus_f = b / a
    e2 = 1.0 - one_minus_f * one_minus_f
    return _bowring(x, y, z, a, b, e2, e2 / (1.0 - e2), one_minus_f)


@njit
def _bowring(x, y, z, a, b, e2, ep2, one_minus_f):
    """:func:`ecef_to_geodetic_njit` on the ellipsoid ``a``, ``b`` (m), first and second
    eccentricity squared ``e2``, ``ep2`` and ``1 - f``."""
    p = math.sqrt(x * x + y * y)
    # reduced latitude beta as (cos, sin) up to a common factor; first guess
    # from the ellipsoid through the point's direction
    cb = one_minus_f * p
    sb = z
    num = z
    den = p
    for _ in range(_PASSES):
        norm = math.sqrt(cb * cb + sb * sb)
        cb /= norm
        sb /= norm
        # Bowring: tan(lat) = (z + e'^2 b sin^3 beta) / (p - e^2 a cos^3 beta)
        num = z + ep2 * b * sb * sb * sb
        den = p - e2 * a * cb * cb * cb
        # tan(beta) = (1 - f) tan(lat)
        cb = den
        sb = one_minus_f * num
    norm = math.sqrt(num * num + den * den)
    s = num / norm
    c = den / norm
    h = p * c + z * s - a * math.sqrt(1.0 - e2 * s * s)
    return math.atan2(num, den), math.atan2(y, x), h


@njit
def _ecef_to_geodetic_rows(xyz):
    n = xyz.shape[0]
    out = np.empty((n, 3))
    for k in range(n):
        lat, lon, h = ecef_to_geodetic_njit(xyz[k, 0], xyz[k, 1], xyz[k, 2])
        out[k, 0] = lat
        out[k, 1] = lon
        out[k, 2] = h
    return out


def ecef_to_geodetic(r):
    """Geodetic ``(lat, lon, h)`` (rad, rad, m) of Earth-fixed ``r`` (m).

    ``r`` of shape (3,) gives three floats; (N, 3) (or (..., 3)) gives three
    arrays of shape (N,) (or (...)). See :func:`ecef_to_geodetic_njit`.
    """
    r = np.asarray(r, dtype=float)
    if r.ndim == 1:
        return ecef_to_geodetic_njit(float(r[0]), float(r[1]), float(r[2]))
    rows = _ecef_to_geodetic_rows(np.ascontiguousarray(r.reshape(-1, 3)))
    shape = r.shape[:-1]
    return rows[:, 0].reshape(shape), rows[:, 1].reshape(shape), rows[:, 2].reshape(shape)


@njit
def enu_basis(lat, lon):
    """Local east, north, up unit vectors (rows of a (3, 3)) in Earth-fixed axes.

    ``lat`` geodetic and ``lon`` in radians; ``enu_basis(lat, lon) @ d``
    gives the east/north/up components of an Earth-fixed vector ``d``.
    """
    sl = math.sin(lat)
    cl = math.cos(lat)
    so = math.sin(lon)
    co = math.cos(lon)
    m = np.empty((3, 3))
    m[0, 0] = -so
    m[0, 1] = co
    m[0, 2] = 0.0
    m[1, 0] = -sl * co
    m[1, 1] = -sl * so
    m[1, 2] = cl
    m[2, 0] = cl * co
    m[2, 1] = cl * so
    m[2, 2] = sl
    return m


def normal_gravity(lat):
    """Somigliana normal gravity (m/s^2) on the WGS84 ellipsoid at geodetic ``lat`` (rad).

    ``gamma = gamma_e (1 + k sin^2 lat) / sqrt(1 - e^2 sin^2 lat)``
    (NIMA TR8350.2, eq. 4-1): the magnitude of gravity plus centrifugal
    acceleration on the surface of the rotating ellipsoid. Scalar or array.
    """
    s2 = np.sin(np.asarray(lat, dtype=float)) ** 2
    g = WGS84_GAMMA_EQ * (1.0 + WGS84_SOMIGLIANA_K * s2) / np.sqrt(1.0 - WGS84_E2_SOMIGLIANA * s2)
    return float(g) if g.ndim == 0 else g
