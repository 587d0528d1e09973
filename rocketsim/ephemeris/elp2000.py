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

from rocketsim.jit import njit
from rocketsim.constants import (
    ARCSEC,
    DAYS_PER_JULIAN_CENTURY,
    DEG,
    J2000_JD,
    SECONDS_PER_DAY,
)
from rocketsim.ephemeris import _tables
from rocketsim.ephemeris.precession import to_j2000, turn
from rocketsim.ephemeris.layouts import ElpLayout, prepare_elp
from rocketsim.ephemeris.sincos import expand, sincos

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



# the project's truncated series, laid out with the generator's plan (see layouts.py)
TABLE = prepare_elp(_tables.MOON_COORD, _tables.MOON_MULT, _tables.MOON_A, _tables.MOON_RECIPE)


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
    """Meeus's ``L', D, M, M', F`` (rad) and their rates (rad per century),
    as two 5-tuples."""
    lp, dlp = _poly_deg(MEAN_LONGITUDE, T)
    d, dd = _poly_deg(ELONGATION, T)
    m, dm = _poly_deg(SUN_ANOMALY, T)
    mp, dmp = _poly_deg(MOON_ANOMALY, T)
    f, df = _poly_deg(LATITUDE_ARGUMENT, T)
    return (lp, d, m, mp, f), (dlp, dd, dm, dmp, df)


@njit
def _sin_term(amplitude, angle, angle_rate):
    """``amplitude * sin(angle)`` and its rate."""
    s, c = sincos(angle)
    return amplitude * s, amplitude * c * angle_rate


@njit
def _sum_terms(first, last, row, A, value_row, rate_row):
    """``sum A_k value_row[row_k]`` and ``sum A_k rate_row[row_k]`` over terms
    ``first:last``, in two interleaved partial sums (combined in a fixed
    order, so the bits are the same every run) to halve the chain of
    dependent additions."""
    v0 = v1 = d0 = d1 = 0.0
    k = first
    while k + 1 < last:
        v0 += A[k] * value_row[row[k]]
        d0 += A[k] * rate_row[row[k]]
        v1 += A[k + 1] * value_row[row[k + 1]]
        d1 += A[k + 1] * rate_row[row[k + 1]]
        k += 2
    if k < last:
        v0 += A[k] * value_row[row[k]]
        d0 += A[k] * rate_row[row[k]]
    return v0 + v1, d0 + d1


@njit
def lbd_kernel(series, T, work):
    """Geocentric ``(lambda rad, beta rad, Delta km)`` and rates per century.

    Mean ecliptic and equinox of date; ``T`` in Julian centuries of TT.
    ``series``: an :class:`~rocketsim.ephemeris.layouts.ElpLayout`; ``work``: a scratch array of shape at
    least ``(7, number of distinct multiplier rows)``. Returns two 3-tuples.

    Each distinct argument row ``u`` is evaluated once, with the eccentricity
    factor of its ``l'`` multiplier folded in: ``E^p sin``, ``E^p cos`` and
    their rates; each term is then one multiply-add per sum.
    """
    args, rates = fundamental_arguments(T)
    lp, dlp = args[0], rates[0]
    two_pi = 2.0 * math.pi
    d = args[1] % two_pi
    m_ = args[2] % two_pi
    l_ = args[3] % two_pi
    f_ = args[4] % two_pi
    e = ECCENTRICITY[0] + T * (ECCENTRICITY[1] + T * ECCENTRICITY[2])
    de = ECCENTRICITY[1] + 2.0 * T * ECCENTRICITY[2]
    x = e - 1.0
    # rows of multipliers as 1-D arrays and rates as scalars: the loop then
    # vectorises (no aliasing question between the tables and the work array)
    m0 = series.mult[0]
    m1 = series.mult[1]
    m2 = series.mult[2]
    m3 = series.mult[3]
    r1 = rates[1]
    r2 = rates[2]
    r3 = rates[3]
    r4 = rates[4]
    sin_v = work[0]
    sin_d = work[1]
    cos_v = work[2]
    cos_d = work[3]
    phase = work[4]
    sin_row = work[5]
    cos_row = work[6]
    direct = series.direct
    for k in range(direct.shape[0]):
        u = direct[k]
        phase[u] = m0[u] * d + m1[u] * m_ + m2[u] * l_ + m3[u] * f_
    expand(phase, direct, series.derived, series.pair_a, series.pair_b, sin_row, cos_row)
    for u in range(m0.shape[0]):
        s = sin_row[u]
        c = cos_row[u]
        w = m0[u] * r1 + m1[u] * r2 + m2[u] * r3 + m3[u] * r4
        # E^p and d(E^p)/dT for p = |i2| <= 4 by the (finite, exact) binomial
        # expansion in x = E - 1: no branch, so the loop vectorises
        p = abs(m1[u])
        c2 = p * (p - 1.0) * 0.5
        c3 = c2 * (p - 2.0) * (1.0 / 3.0)
        c4 = c3 * (p - 3.0) * 0.25
        ep = 1.0 + x * (p + x * (c2 + x * (c3 + x * c4)))
        dep = de * (p + x * (2.0 * c2 + x * (3.0 * c3 + x * 4.0 * c4)))
        sin_v[u] = ep * s
        sin_d[u] = dep * s + ep * w * c
        cos_v[u] = ep * c
        cos_d[u] = dep * c - ep * w * s
    row = series.term_row
    A = series.A
    start = series.start
    lon_sum, lon_rate = _sum_terms(start[0], start[1], row, A, sin_v, sin_d)
    lat_sum, lat_rate = _sum_terms(start[1], start[2], row, A, sin_v, sin_d)
    dist, dist_rate = _sum_terms(start[2], start[3], row, A, cos_v, cos_d)
    lon = lp + lon_sum * ARCSEC
    dlon = dlp + lon_rate * ARCSEC
    lat = lat_sum * ARCSEC
    dlat = lat_rate * ARCSEC
    # Meeus's additive terms (1e-6 degree)
    f, df = args[4], rates[4]
    mp, dmp = args[3], rates[3]
    a1, da1 = _poly_deg(A1, T)
    a2, da2 = _poly_deg(A2, T)
    a3, da3 = _poly_deg(A3, T)
    for amplitude, angle, rate in ((3958.0, a1, da1), (1962.0, lp - f, dlp - df),
                                   (318.0, a2, da2)):
        v, dv = _sin_term(amplitude * MICRODEGREE, angle, rate)
        lon += v
        dlon += dv
    for amplitude, angle, rate in ((-2235.0, lp, dlp), (382.0, a3, da3),
                                   (175.0, a1 - f, da1 - df), (175.0, a1 + f, da1 + df),
                                   (127.0, lp - mp, dlp - dmp), (-115.0, lp + mp, dlp + dmp)):
        v, dv = _sin_term(amplitude * MICRODEGREE, angle, rate)
        lat += v
        dlat += dv
    return (lon, lat, dist), (dlon, dlat, dist_rate)


@njit
def state_kernel(series, T, m, dm, work):
    """Geocentric position (m) and velocity (m/s), J2000 equatorial, 3-tuples.

    ``T``: Julian centuries of TT; ``m``, ``dm``: ``precession.turn(T)``.
    """
    value, rate = lbd_kernel(series, T, work)
    per_second = 1.0 / (DAYS_PER_JULIAN_CENTURY * SECONDS_PER_DAY)
    return to_j2000(m, dm, value[0], value[1], value[2] * 1e3, rate[0] * per_second,
                    rate[1] * per_second, rate[2] * 1e3 * per_second,
                    DAYS_PER_JULIAN_CENTURY * SECONDS_PER_DAY)


def scratch(series: ElpLayout) -> np.ndarray:
    """Work array for :func:`lbd_kernel`."""
    return np.empty((7, series.mult.shape[1]))


def geocentric_lbd(jd_tt: float) -> tuple[np.ndarray, np.ndarray]:
    """The Moon's ``(lambda rad, beta rad, Delta km)`` at ``jd_tt`` (TT), and
    their rates per day; mean ecliptic and equinox of date."""
    T = (jd_tt - J2000_JD) / DAYS_PER_JULIAN_CENTURY
    value, rate = lbd_kernel(TABLE, T, scratch(TABLE))
    return np.array(value), np.array(rate) / DAYS_PER_JULIAN_CENTURY


def geocentric_state(jd_tt: float) -> tuple[np.ndarray, np.ndarray]:
    """The Moon's geocentric ``(r, v)``, m and m/s, J2000 mean equatorial."""
    T = (jd_tt - J2000_JD) / DAYS_PER_JULIAN_CENTURY
    m, dm = turn(T)
    r, v = state_kernel(TABLE, T, m, dm, scratch(TABLE))
    return np.array(r), np.array(v)
