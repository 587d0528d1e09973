"""Heliocentric Earth and Mars from the truncated VSOP87D series.

VSOP87D (Bretagnon & Francou 1988, A&A 202, 309) gives heliocentric
spherical coordinates on the mean ecliptic and equinox of date:

    X = sum_alpha t^alpha sum_k A_k cos(B_k + C_k t),   X in {L, B, R}

``L`` and ``B`` in radians, ``R`` in au, ``t`` in Julian millennia of TT
(TDB, which differs from TT by < 2 ms) from J2000. The rates are the
analytic derivative of the series, term by term:

    dX/dt = sum_alpha sum_k A_k [alpha t^(alpha-1) cos(.) - t^alpha C_k sin(.)]

How it is evaluated: many terms share a frequency ``C`` (the Earth's 204
terms have 123 frequencies), so the layout (:func:`rocketsim.ephemeris.layouts.prepare_vsop`)
writes each term as
``P cos(C t) - Q sin(C t)`` with ``P = A cos B``, ``Q = A sin B`` and the
kernel needs one sine/cosine pair per distinct frequency; and most
frequencies are the sum of two others (94 of the Earth's 123, 331 of Mars's
356), whose pair then comes from the angle-addition formulas
(``sincos.sum_recipe``).

The heliocentric states (:func:`heliocentric_state`) move ``L, B`` from
VSOP87's dynamical ecliptic to FK5 (Meeus 1998, eq. 32.3) before turning
them to the J2000 equator with the IAU 1976 angles; :func:`heliocentric_lbr`
returns the series' own ``L, B, R``. The truncated
tables come from ``generate.py`` (rule stated there); the kernels take the
prepared tables as arguments, so the full series (tests, benchmark) run
through the same code.
"""

from __future__ import annotations

import math
import numpy as np

from rocketsim.jit import njit
from rocketsim.constants import (
    ARCSEC,
    AU,
    DAYS_PER_JULIAN_CENTURY,
    DAYS_PER_JULIAN_MILLENNIUM,
    DEG,
    J2000_JD,
    SECONDS_PER_DAY,
)
from rocketsim.ephemeris import _tables
from rocketsim.ephemeris.precession import to_j2000, turn
from rocketsim.ephemeris.layouts import GROUPS, MAX_POWER, VsopLayout, prepare_vsop
from rocketsim.ephemeris.sincos import expand, sincos

MILLENNIA_PER_CENTURY = 0.1


# the project's truncated series, laid out with the generator's plans (see layouts.py)
TABLES = {body: prepare_vsop(*(getattr(_tables, f"{body.upper()}_{f}") for f in ("COORD", "POWER", "A", "B", "C")),
                             getattr(_tables, f"{body.upper()}_RECIPE"))
          for body in ("earth", "mars")}


@njit
def _group_sums(first, last, index, P, Q, C, sin_f, cos_f):
    """``sum A cos(B + C t)`` and ``sum A C sin(B + C t)`` over terms
    ``first:last``, in two interleaved partial sums (combined in a fixed
    order: the same bits every run) to halve the chain of dependent adds."""
    a0 = a1 = b0 = b1 = 0.0
    k = first
    while k + 1 < last:
        c = cos_f[index[k]]
        s = sin_f[index[k]]
        a0 += P[k] * c - Q[k] * s
        b0 += C[k] * (Q[k] * c + P[k] * s)
        c = cos_f[index[k + 1]]
        s = sin_f[index[k + 1]]
        a1 += P[k + 1] * c - Q[k + 1] * s
        b1 += C[k + 1] * (Q[k + 1] * c + P[k + 1] * s)
        k += 2
    if k < last:
        c = cos_f[index[k]]
        s = sin_f[index[k]]
        a0 += P[k] * c - Q[k] * s
        b0 += C[k] * (Q[k] * c + P[k] * s)
    return a0 + a1, b0 + b1


@njit
def lbr_kernel(series, t, work):
    """``(L, B, R)`` and their rates per Julian millennium at ``t`` (3-tuples).

    ``series``: a :class:`~rocketsim.ephemeris.layouts.VsopLayout`; ``t``: Julian millennia of TT from J2000;
    ``work``: a scratch array of shape at least ``(3, len(series.freq))``.
    ``L``, ``B`` in radians, ``R`` in au.
    """
    freq = series.freq
    sin_scratch = work[0]
    cos_scratch = work[1]
    phase = work[2]
    direct = series.direct
    for k in range(direct.shape[0]):
        phase[direct[k]] = freq[direct[k]] * t
    expand(phase, direct, series.derived, series.pair_a, series.pair_b, sin_scratch, cos_scratch)
    start = series.start
    index = series.term_freq
    P = series.P
    Q = series.Q
    C = series.C
    value0 = value1 = value2 = 0.0
    rate0 = rate1 = rate2 = 0.0
    t2 = t * t
    powers = (1.0, t, t2, t2 * t, t2 * t2, t2 * t2 * t)          # t^p, p = 0..5
    dpowers = (0.0, 1.0, 2.0 * t, 3.0 * t2, 4.0 * t2 * t, 5.0 * t2 * t2)
    for g in range(GROUPS):
        if start[g] == start[g + 1]:
            continue
        s0, s1 = _group_sums(start[g], start[g + 1], index, P, Q, C,
                             sin_scratch, cos_scratch)
        coord = g // (MAX_POWER + 1)
        p = g % (MAX_POWER + 1)
        tp = powers[p]
        dtp = dpowers[p]
        if coord == 0:
            value0 += tp * s0
            rate0 += dtp * s0 - tp * s1
        elif coord == 1:
            value1 += tp * s0
            rate1 += dtp * s0 - tp * s1
        else:
            value2 += tp * s0
            rate2 += dtp * s0 - tp * s1
    return (value0, value1, value2), (rate0, rate1, rate2)


@njit
def fk5_correction(lon, lat, dlon, dlat, T):
    """VSOP87's dynamical ecliptic and equinox -> FK5 (Meeus 1998, eq. 32.3).

    ``L' = L - 1.397 deg T - 0.00031 deg T^2``;
    ``dL = -0.09033" + 0.03916" (cos L' + sin L') tan B``,
    ``dB = +0.03916" (cos L' - sin L')``. ``lon``, ``lat`` in rad with their
    rates per century; returns ``(dL, dB, d(dL)/dT, d(dB)/dT)``. Without it
    the Earth sits ~70 km (0.09") off the FK5/J2000 frame of the IAU 1976
    precession.
    """
    lp = lon - (1.397 * T + 0.00031 * T * T) * DEG
    dlp = dlon - (1.397 + 0.00062 * T) * DEG
    s, c = sincos(lp)
    tan_b = math.tan(lat)
    sec2_b = 1.0 + tan_b * tan_b
    k = 0.03916 * ARCSEC
    d_lon = -0.09033 * ARCSEC + k * (c + s) * tan_b
    d_lat = k * (c - s)
    rate_lon = k * ((c - s) * dlp * tan_b + (c + s) * sec2_b * dlat)
    rate_lat = -k * (s + c) * dlp
    return d_lon, d_lat, rate_lon, rate_lat


@njit
def state_kernel(series, T, m, dm, work):
    """Heliocentric position (m) and velocity (m/s), J2000 equatorial, 3-tuples.

    ``T``: Julian centuries of TT; ``m``, ``dm``: ``precession.turn(T)``.
    The series' ``L, B`` get :func:`fk5_correction` before the turn.
    """
    value, rate = lbr_kernel(series, T * MILLENNIA_PER_CENTURY, work)
    # rates per millennium -> per century for the correction
    d_lon, d_lat, rate_lon, rate_lat = fk5_correction(
        value[0], value[1], rate[0] * MILLENNIA_PER_CENTURY, rate[1] * MILLENNIA_PER_CENTURY, T)
    per_second = 1.0 / (DAYS_PER_JULIAN_MILLENNIUM * SECONDS_PER_DAY)
    per_second_century = 1.0 / (DAYS_PER_JULIAN_CENTURY * SECONDS_PER_DAY)
    return to_j2000(m, dm, value[0] + d_lon, value[1] + d_lat, value[2] * AU,
                    rate[0] * per_second + rate_lon * per_second_century,
                    rate[1] * per_second + rate_lat * per_second_century,
                    rate[2] * AU * per_second, DAYS_PER_JULIAN_CENTURY * SECONDS_PER_DAY)


def scratch(series: VsopLayout) -> np.ndarray:
    """Work array for :func:`lbr_kernel`."""
    return np.empty((3, series.freq.shape[0]))


def heliocentric_lbr(body: str, jd_tt: float) -> tuple[np.ndarray, np.ndarray]:
    """VSOP87D ``(L, B, R)`` of ``body`` ("earth" or "mars") at ``jd_tt`` (TT).

    Mean ecliptic and equinox of date; ``L``, ``B`` in radians, ``R`` in au.
    Returns the three values and their rates per day.
    """
    series = TABLES[body]
    t = (jd_tt - J2000_JD) / DAYS_PER_JULIAN_MILLENNIUM
    value, rate = lbr_kernel(series, t, scratch(series))
    return np.array(value), np.array(rate) / DAYS_PER_JULIAN_MILLENNIUM


def heliocentric_state(body: str, jd_tt: float) -> tuple[np.ndarray, np.ndarray]:
    """Heliocentric ``(r, v)`` of ``body`` in m and m/s, J2000 mean equatorial."""
    series = TABLES[body]
    T = (jd_tt - J2000_JD) / DAYS_PER_JULIAN_CENTURY
    m, dm = turn(T)
    r, v = state_kernel(series, T, m, dm, scratch(series))
    return np.array(r), np.array(v)
