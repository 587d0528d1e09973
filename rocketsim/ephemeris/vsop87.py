"""Heliocentric Earth and Mars from the truncated VSOP87D series.

VSOP87D (Bretagnon & Francou 1988, A&A 202, 309) gives heliocentric
spherical coordinates on the mean ecliptic and equinox of date:

    X = sum_alpha t^alpha sum_k A_k cos(B_k + C_k t),   X in {L, B, R}

``L`` and ``B`` in radians, ``R`` in au, ``t`` in Julian millennia of TT
(TDB, which differs from TT by < 2 ms) from J2000. The rates are the
analytic derivative of the series, term by term:

    dX/dt = sum_alpha sum_k A_k [alpha t^(alpha-1) cos(.) - t^alpha C_k sin(.)]

The truncated tables come from ``generate.py`` (rule stated there); the
kernels take the tables as arguments so the full series (tests, benchmark)
run through the same code.
"""

from __future__ import annotations

import math

import numpy as np

from rocketsim._jit import njit
from rocketsim.constants import AU, DAYS_PER_JULIAN_MILLENNIUM, J2000_JD, SECONDS_PER_DAY
from rocketsim.ephemeris import _tables
from rocketsim.ephemeris.precession import ecliptic_of_date_to_j2000, spherical_to_cartesian

MAX_POWER = 5          # VSOP87 series run to t^5

TABLES = {
    "earth": (_tables.EARTH_COORD, _tables.EARTH_POWER, _tables.EARTH_A,
              _tables.EARTH_B, _tables.EARTH_C),
    "mars": (_tables.MARS_COORD, _tables.MARS_POWER, _tables.MARS_A,
             _tables.MARS_B, _tables.MARS_C),
}


@njit
def lbr_kernel(coord, power, A, B, C, t):
    """``(L, B, R)`` and their derivatives per Julian millennium at ``t``.

    ``t``: Julian millennia of TT from J2000. Returns two length-3 arrays:
    ``(L rad, B rad, R au)`` and ``(dL/dt, dB/dt, dR/dt)`` per millennium.
    """
    tp = np.empty(MAX_POWER + 1)
    dtp = np.empty(MAX_POWER + 1)
    tp[0] = 1.0
    dtp[0] = 0.0
    for k in range(1, MAX_POWER + 1):
        tp[k] = tp[k - 1] * t
        dtp[k] = k * tp[k - 1]
    value = np.zeros(3)
    rate = np.zeros(3)
    for k in range(A.shape[0]):
        arg = B[k] + C[k] * t
        c = math.cos(arg)
        s = math.sin(arg)
        p = power[k]
        i = coord[k]
        value[i] += A[k] * tp[p] * c
        rate[i] += A[k] * (dtp[p] * c - tp[p] * C[k] * s)
    return value, rate


@njit
def state_kernel(coord, power, A, B, C, t, matrix, dmatrix):
    """Heliocentric position (m) and velocity (m/s) in the J2000 equatorial frame.

    ``matrix``/``dmatrix``: the ecliptic-of-date -> J2000 turn and its rate per
    Julian century at the same instant (``precession.ecliptic_of_date_to_j2000``).
    """
    value, rate = lbr_kernel(coord, power, A, B, C, t)
    per_second = 1.0 / (DAYS_PER_JULIAN_MILLENNIUM * SECONDS_PER_DAY)
    r, v = spherical_to_cartesian(value[0], value[1], value[2] * AU,
                                  rate[0] * per_second, rate[1] * per_second,
                                  rate[2] * AU * per_second)
    return matrix @ r, matrix @ v + (dmatrix @ r) * (10.0 * per_second)


def heliocentric_lbr(body: str, jd_tt: float) -> tuple[np.ndarray, np.ndarray]:
    """VSOP87D ``(L, B, R)`` of ``body`` ("earth" or "mars") at ``jd_tt`` (TT).

    Mean ecliptic and equinox of date; ``L``, ``B`` in radians, ``R`` in au.
    Returns the three values and their rates per day.
    """
    t = (jd_tt - J2000_JD) / DAYS_PER_JULIAN_MILLENNIUM
    value, rate = lbr_kernel(*TABLES[body], t)
    return value, rate / DAYS_PER_JULIAN_MILLENNIUM


def heliocentric_state(body: str, jd_tt: float) -> tuple[np.ndarray, np.ndarray]:
    """Heliocentric ``(r, v)`` of ``body`` in m and m/s, J2000 mean equatorial."""
    t = (jd_tt - J2000_JD) / DAYS_PER_JULIAN_MILLENNIUM
    matrix, dmatrix = ecliptic_of_date_to_j2000(t * 10.0)
    return state_kernel(*TABLES[body], t, matrix, dmatrix)
