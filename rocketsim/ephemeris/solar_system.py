"""The Sun, Earth, Moon and Mars at a TT instant: one call for the whole field.

Positions in metres and velocities in m/s in the J2000 mean equatorial frame
(``x`` to the J2000 equinox, ``z`` to the J2000 mean pole), relative to a
chosen centre. Earth and Mars come from VSOP87D (heliocentric), the Moon from
ELP2000-82B (geocentric), both precessed from the ecliptic and equinox of
date with the IAU 1976 angles (see ``vsop87``, ``elp2000``, ``precession``).
Time is TT, as a Julian date (``jd_tt``); for Earth rotation use UT1 and
``rocketsim.timescales`` instead.

Accuracy (the truncation, measured against the full series over 1950-2100,
the span the truncation rule was set for): Earth 265 km, Mars 252 km, the
Moon 0.15" / 0.15" / 0.31 km about the Earth. Outside that span the dropped
``t^alpha`` terms grow and nothing is certified.

    r, v = state("mars", jd_tt, center="earth")      # one instant: (3,), (3,)
    r, v = state("mars", jd_array)                   # vectorised: (N, 3), (N, 3)
    field = states(jd_tt, center="earth")            # {"sun": (r, v), ...}
"""

from __future__ import annotations

import numpy as np

from rocketsim.jit import njit
from rocketsim.constants import DAYS_PER_JULIAN_CENTURY, J2000_JD
from rocketsim.ephemeris import elp2000, vsop87
from rocketsim.ephemeris.precession import turn

BODIES = ("sun", "earth", "moon", "mars")
_INDEX = {name: i for i, name in enumerate(BODIES)}


@njit
def heliocentric_kernel(jd_tt, earth, mars, moon):
    """Heliocentric states of all four bodies at each of ``jd_tt`` (1-D, TT).

    ``earth``, ``mars``: ``layouts.VsopLayout`` series; ``moon``: an
    ``layouts.ElpLayout`` series. Returns ``(N, 4, 6)``: for each instant and
    body of ``BODIES`` (sun, earth, moon, mars) ``x y z`` (m) and ``vx vy vz``
    (m/s), J2000 equatorial, relative to the Sun (so the Sun's row is zero).
    """
    out = np.zeros((jd_tt.shape[0], 4, 6))
    work = np.empty((7, max(earth.freq.shape[0], mars.freq.shape[0], moon.mult.shape[1])))
    for n in range(jd_tt.shape[0]):
        T = (jd_tt[n] - J2000_JD) / DAYS_PER_JULIAN_CENTURY
        m, dm = turn(T)
        re, ve = vsop87.state_kernel(earth, T, m, dm, work)
        rm, vm = vsop87.state_kernel(mars, T, m, dm, work)
        rl, vl = elp2000.state_kernel(moon, T, m, dm, work)
        for k in range(3):
            out[n, 1, k] = re[k]
            out[n, 1, 3 + k] = ve[k]
            out[n, 2, k] = re[k] + rl[k]
            out[n, 2, 3 + k] = ve[k] + vl[k]
            out[n, 3, k] = rm[k]
            out[n, 3, 3 + k] = vm[k]
    return out


# The project's truncated series, frozen into the compiled code as constants
# (no unboxing of a dozen arrays per call; the kernel cache is keyed on the
# hash of every source file, _tables.py included, so it cannot go stale).
_EARTH = vsop87.TABLES["earth"]
_MARS = vsop87.TABLES["mars"]
_MOON = elp2000.TABLE


@njit
def _truncated_many(jd_tt):
    return heliocentric_kernel(jd_tt, _EARTH, _MARS, _MOON)


@njit
def _truncated_one(jd_tt, center):
    """Positions ``(4, 3)`` and velocities ``(4, 3)`` of the bodies of
    ``BODIES`` relative to body number ``center``, at one instant."""
    one = np.empty(1)
    one[0] = jd_tt
    helio = heliocentric_kernel(one, _EARTH, _MARS, _MOON)[0]
    r = np.empty((4, 3))
    v = np.empty((4, 3))
    for i in range(4):
        for k in range(3):
            r[i, k] = helio[i, k] - helio[center, k]
            v[i, k] = helio[i, 3 + k] - helio[center, 3 + k]
    return r, v


def heliocentric_states(jd_tt, earth=None, mars=None, moon=None) -> np.ndarray:
    """``(N, 4, 6)`` heliocentric states (see :func:`heliocentric_kernel`).

    The series default to the project's truncated ones; the tests and the
    benchmark pass the full series (``layouts.prepare_vsop``, ``layouts.prepare_elp``)
    here to measure the truncation.
    """
    jd = np.ascontiguousarray(np.asarray(jd_tt, dtype=np.float64).reshape(-1))
    if earth is None and mars is None and moon is None:
        return _truncated_many(jd)
    return heliocentric_kernel(jd, earth or _EARTH, mars or _MARS, moon or _MOON)


def _check_body(name: str, what: str) -> int:
    try:
        return _INDEX[name]
    except (KeyError, TypeError):
        raise ValueError(f"unknown {what} {name!r}: expected one of {', '.join(BODIES)}") from None


def state(body: str, jd_tt, center: str = "sun"):
    """Position (m) and velocity (m/s) of ``body`` relative to ``center``.

    ``body``, ``center`` in ``{"sun", "earth", "moon", "mars"}``; ``jd_tt`` a
    Julian date in TT, a float or a 1-D array. J2000 mean equatorial frame.
    Returns ``(r, v)``: shape ``(3,)`` each for a float, ``(N, 3)`` for an array.
    """
    i = _check_body(body, "body")
    j = _check_body(center, "center")
    if np.ndim(jd_tt) == 0:
        r, v = _truncated_one(float(jd_tt), j)
        return r[i], v[i]
    helio = heliocentric_states(jd_tt)
    relative = helio[:, i, :] - helio[:, j, :]
    return relative[:, :3], relative[:, 3:]


def states(jd_tt, center: str = "earth") -> dict:
    """``{body: (r, v)}`` for all four bodies relative to ``center`` (m, m/s).

    One evaluation of every series for the n-body field; shapes as in
    :func:`state` (the centre itself maps to zeros).
    """
    j = _check_body(center, "center")
    if np.ndim(jd_tt) == 0:
        r, v = _truncated_one(float(jd_tt), j)
        return {"sun": (r[0], v[0]), "earth": (r[1], v[1]), "moon": (r[2], v[2]),
                "mars": (r[3], v[3])}
    helio = heliocentric_states(jd_tt)
    relative = helio - helio[:, j:j + 1, :]
    return {name: (relative[:, i, :3], relative[:, i, 3:]) for i, name in enumerate(BODIES)}
