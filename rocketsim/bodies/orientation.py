"""Pole and prime meridian of the Moon and Mars (IAU WGCCRE 2015).

Archinal et al., "Report of the IAU Working Group on Cartographic
Coordinates and Rotational Elements: 2015", Celest. Mech. Dyn. Astr. 130:22
(2018), Tables 1 and 2 (the Moon's model, unchanged since the 2009 report,
is the "mean Earth/polar axis" one with thirteen libration terms E1..E13;
Mars's 2015 model is Kuchynka et al. 2014's with its periodic terms). The
same numbers are NAIF's ``pck00011.tpc`` (BODY301_*, BODY499_*).

For a body, at ``d`` days and ``T`` Julian centuries of TT (TDB within 2 ms)
from J2000, the report gives the right ascension ``alpha0`` and declination
``delta0`` of the north pole in the J2000 equatorial frame (ICRF) and the
angle ``W`` of the prime meridian along the equator from its node on the
J2000 equator. The body-fixed frame (``z`` the pole, ``x`` the prime
meridian) turns into J2000 by

    M = R3(-(alpha0 + 90 deg)) R1(-(90 deg - delta0)) R3(-W)

(``R1``, ``R3`` frame rotations): ``r_J2000 = M r_body_fixed``.

Gravity of the Moon and Mars is a point mass plus J2 about these poles
(:func:`gravity_j2000`, with ``rocketsim.bodies.gravity``).
"""

from __future__ import annotations

import numpy as np

from rocketsim.bodies.gravity import gravity
from rocketsim.constants import (
    DAYS_PER_JULIAN_CENTURY,
    DEG,
    J2000_JD,
    MARS_J2,
    MARS_MU,
    MARS_RADIUS_EQ,
    MOON_J2,
    MOON_MU,
    MOON_RADIUS,
    SECONDS_PER_DAY,
)

BODIES = ("moon", "mars")

# --- The Moon (Archinal et al. 2018, Table 2; pck00011 BODY301) --------------
MOON_POLE_RA = (269.9949, 0.0031)            # deg, deg per century
MOON_POLE_DEC = (66.5392, 0.0130)            # deg, deg per century
MOON_PM = (38.3213, 13.17635815, -1.4e-12)   # deg, deg/day, deg/day^2
# E1..E13: (deg, deg per day)
MOON_ARGUMENTS = (
    (125.045, -0.0529921), (250.089, -0.1059842), (260.008, 13.0120009),
    (176.625, 13.3407154), (357.529, 0.9856003), (311.589, 26.4057084),
    (134.963, 13.0649930), (276.617, 0.3287146), (34.226, 1.7484877),
    (15.134, -0.1589763), (119.743, 0.0036096), (239.961, 0.1643573),
    (25.053, 12.9590088),
)
# amplitudes (deg) of sin E_i in alpha0, cos E_i in delta0, sin E_i in W
MOON_RA_SIN = (-3.8787, -0.1204, 0.0700, -0.0172, 0.0, 0.0072, 0.0, 0.0, 0.0,
               -0.0052, 0.0, 0.0, 0.0043)
MOON_DEC_COS = (1.5419, 0.0239, -0.0278, 0.0068, 0.0, -0.0029, 0.0009, 0.0, 0.0,
                0.0008, 0.0, 0.0, -0.0009)
MOON_PM_SIN = (3.5610, 0.1208, -0.0642, 0.0158, 0.0252, -0.0066, -0.0047, -0.0046,
               0.0028, 0.0052, 0.0040, 0.0019, -0.0044)

# --- Mars (Archinal et al. 2018, Table 1; pck00011 BODY499) ------------------
MARS_POLE_RA = (317.269202, -0.10927547)     # deg, deg per century
MARS_POLE_DEC = (54.432516, -0.05827105)
MARS_PM = (176.049863, 350.891982443297)     # deg, deg/day
# periodic terms: (amplitude deg, phase deg, rate deg per century)
MARS_RA_SIN = ((0.000068, 198.991226, 19139.4819985), (0.000238, 226.292679, 38280.8511281),
               (0.000052, 249.663391, 57420.7251593), (0.000009, 266.183510, 76560.6367950),
               (0.419057, 79.398797, 0.5042615))
MARS_DEC_COS = ((0.000051, 122.433576, 19139.9407476), (0.000141, 43.058401, 38280.8753272),
                (0.000031, 57.663379, 57420.7517205), (0.000005, 79.476401, 76560.6495004),
                (1.591274, 166.325722, 0.5042615))
MARS_PM_SIN = ((0.000145, 129.071773, 19140.0328244), (0.000157, 36.352167, 38281.0473591),
               (0.000040, 56.668646, 57420.9295360), (0.000001, 67.364003, 76560.2552215),
               (0.000001, 104.792680, 95700.4387578), (0.584542, 95.391654, 0.5042615))

GRAVITY = {"moon": (MOON_MU, MOON_RADIUS, MOON_J2), "mars": (MARS_MU, MARS_RADIUS_EQ, MARS_J2)}


def _check(body: str) -> str:
    if body not in BODIES:
        raise ValueError(f"no IAU orientation for {body!r}: expected one of {', '.join(BODIES)}")
    return body


def pole_and_meridian(body: str, jd_tt):
    """``(alpha0, delta0, W)`` of ``body`` ("moon" or "mars") in radians.

    ``jd_tt``: Julian date(s), TT. Pole right ascension and declination in
    the J2000 equatorial frame, prime-meridian angle ``W`` (not reduced to
    0..2 pi). Arrays in, arrays out (same shape).
    """
    _check(body)
    d = np.asarray(jd_tt, dtype=np.float64) - J2000_JD
    T = d / DAYS_PER_JULIAN_CENTURY
    if body == "moon":
        alpha = MOON_POLE_RA[0] + MOON_POLE_RA[1] * T
        delta = MOON_POLE_DEC[0] + MOON_POLE_DEC[1] * T
        w = MOON_PM[0] + MOON_PM[1] * d + MOON_PM[2] * d * d
        for (e0, e1), a, b, c in zip(MOON_ARGUMENTS, MOON_RA_SIN, MOON_DEC_COS, MOON_PM_SIN):
            e = (e0 + e1 * d) * DEG
            s = np.sin(e)
            alpha = alpha + a * s
            delta = delta + b * np.cos(e)
            w = w + c * s
    else:
        alpha = MARS_POLE_RA[0] + MARS_POLE_RA[1] * T
        delta = MARS_POLE_DEC[0] + MARS_POLE_DEC[1] * T
        w = MARS_PM[0] + MARS_PM[1] * d
        for amplitude, phase, rate in MARS_RA_SIN:
            alpha = alpha + amplitude * np.sin((phase + rate * T) * DEG)
        for amplitude, phase, rate in MARS_DEC_COS:
            delta = delta + amplitude * np.cos((phase + rate * T) * DEG)
        for amplitude, phase, rate in MARS_PM_SIN:
            w = w + amplitude * np.sin((phase + rate * T) * DEG)
    return alpha * DEG, delta * DEG, w * DEG


def spin_rate(body: str) -> float:
    """Mean rotation rate of the prime meridian, rad/s (the ``W`` rate)."""
    rate = MOON_PM[1] if _check(body) == "moon" else MARS_PM[1]
    return rate * DEG / SECONDS_PER_DAY


def body_to_j2000(body: str, jd_tt) -> np.ndarray:
    """Rotation matrix body-fixed -> J2000 equatorial of ``body`` at ``jd_tt`` (TT).

    ``r_J2000 = M @ r_body_fixed``; body-fixed ``z`` is the IAU north pole,
    ``x`` the prime meridian. Shape ``(3, 3)``, or ``(N, 3, 3)`` for N dates.
    """
    alpha, delta, w = pole_and_meridian(body, jd_tt)
    # M = R3(-(alpha + 90 deg)) R1(-(90 deg - delta)) R3(-W), multiplied out
    ca, sa = np.cos(alpha), np.sin(alpha)
    cd, sd = np.cos(delta), np.sin(delta)
    cw, sw = np.cos(w), np.sin(w)
    m = np.empty(np.shape(alpha) + (3, 3))
    m[..., 0, 0] = -sa * cw - ca * sd * sw
    m[..., 0, 1] = sa * sw - ca * sd * cw
    m[..., 0, 2] = ca * cd
    m[..., 1, 0] = ca * cw - sa * sd * sw
    m[..., 1, 1] = -ca * sw - sa * sd * cw
    m[..., 1, 2] = sa * cd
    m[..., 2, 0] = cd * sw
    m[..., 2, 1] = cd * cw
    m[..., 2, 2] = sd
    return m


def pole(body: str, jd_tt) -> np.ndarray:
    """Unit vector of ``body``'s north pole in the J2000 equatorial frame."""
    alpha, delta, _ = pole_and_meridian(body, jd_tt)
    return np.stack([np.cos(delta) * np.cos(alpha), np.cos(delta) * np.sin(alpha),
                     np.sin(delta)], axis=-1)


def gravity_j2000(body: str, r_j2000: np.ndarray, jd_tt: float) -> np.ndarray:
    """Point-mass + J2 acceleration (m/s^2) of the Moon or Mars, J2000 axes.

    ``r_j2000``: position(s) relative to the body's centre, m, shape (3,) or
    (N, 3); J2 acts about the body's IAU pole at ``jd_tt`` (TT). Constants
    from ``rocketsim.constants`` (docs/physics.md#moon-and-mars).
    """
    mu, radius, j2 = GRAVITY[_check(body)]
    m = body_to_j2000(body, jd_tt)
    r_body = np.asarray(r_j2000, dtype=np.float64) @ m      # = (M^T r) row-wise
    return gravity(r_body, mu=mu, radius=radius, j2=j2) @ m.T
