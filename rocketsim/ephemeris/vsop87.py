"""Heliocentric Earth and Mars from the truncated VSOP87D series.

VSOP87D (Bretagnon & Francou 1988, A&A 202, 309) gives heliocentric
spherical coordinates on the mean ecliptic and equinox of date:

    X = sum_alpha t^alpha sum_k A_k cos(B_k + C_k t),   X in {L, B, R}

``L`` and ``B`` in radians, ``R`` in au, ``t`` in Julian millennia of TT
(TDB, which differs from TT by < 2 ms) from J2000. The rates are the
analytic derivative of the series, term by term:

    dX/dt = sum_alpha sum_k A_k [alpha t^(alpha-1) cos(.) - t^alpha C_k sin(.)]

How it is evaluated: many terms share a frequency ``C`` (the Earth's 204
terms have 123 frequencies), so :func:`prepare` writes each term as
``P cos(C t) - Q sin(C t)`` with ``P = A cos B``, ``Q = A sin B`` and the
kernel takes one sine/cosine pair per distinct frequency. The truncated
tables come from ``generate.py`` (rule stated there); the kernels take the
prepared tables as arguments, so the full series (tests, benchmark) run
through the same code.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from rocketsim._jit import njit
from rocketsim.constants import (
    AU,
    DAYS_PER_JULIAN_CENTURY,
    DAYS_PER_JULIAN_MILLENNIUM,
    J2000_JD,
    SECONDS_PER_DAY,
)
from rocketsim.ephemeris import _tables
from rocketsim.ephemeris.precession import to_j2000, turn
from rocketsim.ephemeris.sincos import sincos

MAX_POWER = 5                       # VSOP87 series run to t^5
GROUPS = 3 * (MAX_POWER + 1)        # (coordinate, power) pairs
MILLENNIA_PER_CENTURY = 0.1


class Prepared(NamedTuple):
    """A VSOP87D series laid out for the kernel (see module docstring).

    Terms are sorted by group ``g = 6 * coord + power``; ``start[g]:start[g+1]``
    are the terms of group ``g``; ``term_freq`` indexes ``freq``.
    """

    freq: np.ndarray        # distinct frequencies C, rad per millennium
    start: np.ndarray       # (GROUPS + 1,) group boundaries
    term_freq: np.ndarray   # frequency index of each term
    P: np.ndarray           # A cos B
    Q: np.ndarray           # A sin B
    C: np.ndarray           # frequency of each term


def prepare(coord, power, A, B, C) -> Prepared:
    """Lay out a flat VSOP87D series (``generate.VsopSeries`` fields)."""
    group = np.asarray(coord) * (MAX_POWER + 1) + np.asarray(power)
    order = np.argsort(group, kind="stable")
    freq, term_freq = np.unique(np.asarray(C)[order], return_inverse=True)
    start = np.searchsorted(group[order], np.arange(GROUPS + 1))
    a = np.asarray(A)[order]
    b = np.asarray(B)[order]
    return Prepared(freq, start.astype(np.int64), term_freq.astype(np.int64),
                    a * np.cos(b), a * np.sin(b), np.asarray(C)[order].astype(np.float64))


TABLES = {
    "earth": prepare(_tables.EARTH_COORD, _tables.EARTH_POWER, _tables.EARTH_A,
                     _tables.EARTH_B, _tables.EARTH_C),
    "mars": prepare(_tables.MARS_COORD, _tables.MARS_POWER, _tables.MARS_A,
                    _tables.MARS_B, _tables.MARS_C),
}


@njit
def lbr_kernel(series, t, work):
    """``(L, B, R)`` and their rates per Julian millennium at ``t`` (3-tuples).

    ``series``: a :class:`Prepared`; ``t``: Julian millennia of TT from J2000;
    ``work``: a scratch array of shape at least ``(2, len(series.freq))``.
    ``L``, ``B`` in radians, ``R`` in au.
    """
    freq = series.freq
    sin_scratch = work[0]
    cos_scratch = work[1]
    for f in range(freq.shape[0]):
        s, c = sincos(freq[f] * t)
        sin_scratch[f] = s
        cos_scratch[f] = c
    start = series.start
    index = series.term_freq
    P = series.P
    Q = series.Q
    C = series.C
    value0 = value1 = value2 = 0.0
    rate0 = rate1 = rate2 = 0.0
    for g in range(GROUPS):
        if start[g] == start[g + 1]:
            continue
        s0 = 0.0
        s1 = 0.0
        for k in range(start[g], start[g + 1]):
            c = cos_scratch[index[k]]
            s = sin_scratch[index[k]]
            s0 += P[k] * c - Q[k] * s          # A cos(B + C t)
            s1 += C[k] * (Q[k] * c + P[k] * s)  # A C sin(B + C t)
        coord = g // (MAX_POWER + 1)
        p = g % (MAX_POWER + 1)
        tp = t ** p
        dtp = p * t ** (p - 1) if p > 0 else 0.0
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
def state_kernel(series, T, m, dm, work):
    """Heliocentric position (m) and velocity (m/s), J2000 equatorial, 3-tuples.

    ``T``: Julian centuries of TT; ``m``, ``dm``: ``precession.turn(T)``.
    """
    value, rate = lbr_kernel(series, T * MILLENNIA_PER_CENTURY, work)
    per_second = 1.0 / (DAYS_PER_JULIAN_MILLENNIUM * SECONDS_PER_DAY)
    return to_j2000(m, dm, value[0], value[1], value[2] * AU, rate[0] * per_second,
                    rate[1] * per_second, rate[2] * AU * per_second,
                    DAYS_PER_JULIAN_CENTURY * SECONDS_PER_DAY)


def scratch(series: Prepared) -> np.ndarray:
    """Work array for :func:`lbr_kernel`."""
    return np.empty((2, series.freq.shape[0]))


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
