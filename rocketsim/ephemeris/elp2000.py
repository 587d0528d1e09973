"""The geocentric Moon from the truncated ELP2000-82B main problem.

ELP2000-82B (Chapront-Touze & Chapront 1983, A&A 124, 50; files ELP01-03)
gives the Moon's geocentric longitude and latitude (sums of sines, arcsec)
and distance (sum of cosines, km) on the mean ecliptic and equinox of date,
as series in the Delaunay arguments ``D, l', l, F``. As in Meeus,
*Astronomical Algorithms* (2nd ed., 1998), chapter 47, they are driven by
Meeus's fundamental arguments (below, ``T`` in Julian centuries of TT from
J2000), terms in ``l'`` (M) are multiplied by ``E^|i2|`` with
``E = 1 - 0.002516 T - 0.0000074 T^2`` (the drift of the Earth's orbital
eccentricity), and Meeus's additive terms for Venus (A1), Jupiter (A2) and
the Earth's flattening (A3, L') are added:

    lambda = L' + sum_l + 3958 sin A1 + 1962 sin(L' - F) + 318 sin A2
    beta   = sum_b - 2235 sin L' + 382 sin A3 + 175 sin(A1 - F)
             + 175 sin(A1 + F) + 127 sin(L' - M') - 115 sin(L' + M')
    Delta  = sum_r

(additive terms in 1e-6 degree). Rates are the analytic derivative.
"""

from __future__ import annotations

import math

import numpy as np

from rocketsim._jit import njit
from rocketsim.constants import (
    ARCSEC,
    DAYS_PER_JULIAN_CENTURY,
    DEG,
    J2000_JD,
    SECONDS_PER_DAY,
)
from rocketsim.ephemeris import _tables
from rocketsim.ephemeris.precession import ecliptic_of_date_to_j2000, spherical_to_cartesian

# Meeus (1998) eqs. 47.1-47.5: degrees, coefficients of T^0..T^4.
MEAN_LONGITUDE = (218.3164477, 481267.88123421, -0.0015786, 1.0 / 538841.0, -1.0 / 65194000.0)
ELONGATION = (297.8501921, 445267.1114034, -0.0018819, 1.0 / 545868.0, -1.0 / 113065000.0)
SUN_ANOMALY = (357.5291092, 35999.0502909, -0.0001536, 1.0 / 24490000.0, 0.0)
MOON_ANOMALY = (134.9633964, 477198.8675055, 0.0087414, 1.0 / 69699.0, -1.0 / 14712000.0)
LATITUDE_ARGUMENT = (93.2720950, 483202.0175233, -0.0036539, -1.0 / 3526000.0, 1.0 / 863310000.0)
# Meeus (1998) p. 338: arguments of the additive terms, degrees.
A1 = (119.75, 131.849)
A2 = (53.09, 479264.290)
A3 = (313.45, 481266.484)
# Meeus (1998) eq. 47.6: eccentricity factor, coefficients of T^0..T^2.
ECCENTRICITY = (1.0, -0.002516, -0.0000074)
MICRODEGREE = 1e-6 * DEG

MAX_MULTIPLIER = 8     # largest |i| of D, l', l, F in the ELP main problem

TABLE = (_tables.MOON_COORD, _tables.MOON_MULT, _tables.MOON_A)


@njit
def _poly_deg(c, T):
    """Value (rad) and rate (rad/century) of a degree polynomial in T."""
    value = 0.0
    rate = 0.0
    for k in range(len(c) - 1, -1, -1):
        value = value * T + c[k]
    for k in range(len(c) - 1, 0, -1):
        rate = rate * T + k * c[k]
    return value * DEG, rate * DEG


@njit
def fundamental_arguments(T):
    """Meeus's ``L', D, M, M', F`` (rad) and their rates (rad per century)."""
    values = np.empty(5)
    rates = np.empty(5)
    for i, c in enumerate((MEAN_LONGITUDE, ELONGATION, SUN_ANOMALY, MOON_ANOMALY,
                           LATITUDE_ARGUMENT)):
        values[i], rates[i] = _poly_deg(c, T)
    return values, rates


@njit
def _add_sin(acc, amplitude, angle, angle_rate):
    """Add ``amplitude * sin(angle)`` and its rate to ``acc = [value, rate]``."""
    acc[0] += amplitude * math.sin(angle)
    acc[1] += amplitude * math.cos(angle) * angle_rate


@njit
def lbd_kernel(coord, mult, A, T):
    """Geocentric ``(lambda rad, beta rad, Delta km)`` and rates per century.

    Mean ecliptic and equinox of date; ``T`` in Julian centuries of TT.
    ``exp(i k x)`` of each Delaunay argument is built once by multiplication,
    so each term costs a product of four complex numbers, not a sine.
    """
    args, rates = fundamental_arguments(T)
    lp, dlp = args[0], rates[0]
    e = ECCENTRICITY[0] + T * (ECCENTRICITY[1] + T * ECCENTRICITY[2])
    de = ECCENTRICITY[1] + 2.0 * T * ECCENTRICITY[2]
    n = MAX_MULTIPLIER
    powers = np.empty((4, 2 * n + 1), dtype=np.complex128)
    for j in range(4):
        base = complex(math.cos(args[j + 1]), math.sin(args[j + 1]))
        powers[j, n] = 1.0
        for k in range(1, n + 1):
            powers[j, n + k] = powers[j, n + k - 1] * base
            powers[j, n - k] = powers[j, n + k].conjugate()
    epow = np.empty(5)
    depow = np.empty(5)
    epow[0] = 1.0
    depow[0] = 0.0
    for k in range(1, 5):
        epow[k] = epow[k - 1] * e
        depow[k] = k * epow[k - 1] * de
    value = np.zeros(3)
    rate = np.zeros(3)
    for k in range(A.shape[0]):
        i1 = mult[k, 0]
        i2 = mult[k, 1]
        i3 = mult[k, 2]
        i4 = mult[k, 3]
        z = powers[0, n + i1] * powers[1, n + i2] * powers[2, n + i3] * powers[3, n + i4]
        w = i1 * rates[1] + i2 * rates[2] + i3 * rates[3] + i4 * rates[4]
        m = abs(i2)
        a = A[k] * epow[m]
        da = A[k] * depow[m]
        c = coord[k]
        if c == 2:
            value[2] += a * z.real
            rate[2] += da * z.real - a * w * z.imag
        else:
            value[c] += a * z.imag
            rate[c] += da * z.imag + a * w * z.real
    lon = np.zeros(2)
    lat = np.zeros(2)
    lon[0] = lp + value[0] * ARCSEC
    lon[1] = dlp + rate[0] * ARCSEC
    lat[0] = value[1] * ARCSEC
    lat[1] = rate[1] * ARCSEC
    # Meeus's additive terms (1e-6 degree)
    f, df = args[4], rates[4]
    mp, dmp = args[3], rates[3]
    a1, da1 = _poly_deg(A1, T)
    a2, da2 = _poly_deg(A2, T)
    a3, da3 = _poly_deg(A3, T)
    _add_sin(lon, 3958.0 * MICRODEGREE, a1, da1)
    _add_sin(lon, 1962.0 * MICRODEGREE, lp - f, dlp - df)
    _add_sin(lon, 318.0 * MICRODEGREE, a2, da2)
    _add_sin(lat, -2235.0 * MICRODEGREE, lp, dlp)
    _add_sin(lat, 382.0 * MICRODEGREE, a3, da3)
    _add_sin(lat, 175.0 * MICRODEGREE, a1 - f, da1 - df)
    _add_sin(lat, 175.0 * MICRODEGREE, a1 + f, da1 + df)
    _add_sin(lat, 127.0 * MICRODEGREE, lp - mp, dlp - dmp)
    _add_sin(lat, -115.0 * MICRODEGREE, lp + mp, dlp + dmp)
    out = np.empty(3)
    out_rate = np.empty(3)
    out[0] = lon[0]
    out[1] = lat[0]
    out[2] = value[2]
    out_rate[0] = lon[1]
    out_rate[1] = lat[1]
    out_rate[2] = rate[2]
    return out, out_rate


@njit
def state_kernel(coord, mult, A, T, matrix, dmatrix):
    """Geocentric position (m) and velocity (m/s) in the J2000 equatorial frame."""
    value, rate = lbd_kernel(coord, mult, A, T)
    per_second = 1.0 / (DAYS_PER_JULIAN_CENTURY * SECONDS_PER_DAY)
    r, v = spherical_to_cartesian(value[0], value[1], value[2] * 1e3,
                                  rate[0] * per_second, rate[1] * per_second,
                                  rate[2] * 1e3 * per_second)
    return matrix @ r, matrix @ v + (dmatrix @ r) * per_second


def geocentric_lbd(jd_tt: float) -> tuple[np.ndarray, np.ndarray]:
    """The Moon's ``(lambda rad, beta rad, Delta km)`` at ``jd_tt`` (TT), and
    their rates per day; mean ecliptic and equinox of date."""
    value, rate = lbd_kernel(*TABLE, (jd_tt - J2000_JD) / DAYS_PER_JULIAN_CENTURY)
    return value, rate / DAYS_PER_JULIAN_CENTURY


def geocentric_state(jd_tt: float) -> tuple[np.ndarray, np.ndarray]:
    """The Moon's geocentric ``(r, v)``, m and m/s, J2000 mean equatorial."""
    T = (jd_tt - J2000_JD) / DAYS_PER_JULIAN_CENTURY
    matrix, dmatrix = ecliptic_of_date_to_j2000(T)
    return state_kernel(*TABLE, T, matrix, dmatrix)
