"""Impact prediction: where and when a coasting path meets the WGS84 ellipsoid.

A vacuum, two-body prediction (``fc.impact_point``, ``fc.time_to_impact``):
the path from the position and velocity now is the Kepler conic of the
central body's point mass; no drag, no thrust, no J2. It meets the ground
(the WGS84 ellipsoid, no terrain) where

    f(nu) = (x^2 + y^2) / a^2 + z^2 / b^2 - 1 = 0,   r(nu) = p / (1 + e cos nu)

first changes sign from positive (above) to negative (below) along the true anomaly ``nu`` ahead
of the vehicle (found by a scan in STEPS steps of the arc to periapsis,
then bisected to 1e-12 rad; the scan and bisection are compiled). The time of flight follows from Kepler's
equation (the eccentric anomaly on an ellipse, the hyperbolic anomaly on a
hyperbola; Vallado, *Fundamentals of Astrodynamics and Applications*, 4th
ed., sections 2.2-2.3), and the impact longitude from the Earth's rotation
over that time (``theta = omega_E t``, :mod:`rocketsim.frames.earth_fixed`).

What it leaves out: the drag of the air below ~100 km (a falling stage lands
short of it, by kilometres from high up) and J2 (about 1 km over a
ten-minute arc; tests/unit/flight/test_impact.py measures both against the flown
trajectory). Frames: ECI of the mission epoch in, geodetic latitude and
longitude (rad) out. Units SI.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from rocketsim.jit import njit
from rocketsim.constants import EARTH_RADIUS_EQ, EARTH_RADIUS_POLAR
from rocketsim.frames.earth_fixed import eci_to_ecef
from rocketsim.frames.geodetic import ecef_to_geodetic
from rocketsim.frames.vectors import cross

STEPS = 720                 # scan of the arc to periapsis for the ground crossing


@dataclass(frozen=True)
class Impact:
    """A predicted impact: ``time`` (s from now), geodetic ``latitude`` and
    ``longitude`` (rad), ``position`` (ECI at impact, m) and ``speed`` (inertial, m/s)."""

    time: float
    latitude: float
    longitude: float
    position: np.ndarray
    speed: float


def predict_impact(r, v, t: float, mu: float, radius_eq: float = EARTH_RADIUS_EQ,
                   radius_polar: float = EARTH_RADIUS_POLAR) -> Impact | None:
    """The first crossing of the ellipsoid ahead on the vacuum conic of ``(r, v)``
    (ECI, m and m/s) at mission time ``t`` (s), about a point mass ``mu``
    (m^3/s^2) with the ellipsoid's radii (m). ``None`` if the conic never
    meets it (an orbit clear of the ground, or a path already below it)."""
    r = np.asarray(r, dtype=float)
    v = np.asarray(v, dtype=float)
    if _outside(r[0], r[1], r[2], radius_eq, radius_polar) <= 0.0:
        return None                                   # on or under the ground already
    h = cross(r, v)
    h2 = float(h @ h)
    if h2 == 0.0:
        return None                                   # a purely radial path: not handled
    rn = math.sqrt(r @ r)
    e_vec = cross(v, h) / mu - r / rn
    e = math.sqrt(e_vec @ e_vec)
    p = h2 / mu
    if p / (1.0 + e) > radius_eq:
        return None                                   # periapsis above every point of the ground
    # perifocal axes: P to periapsis, Q 90 deg ahead in the direction of motion
    w = h / math.sqrt(h2)
    if e > 1e-12:
        pa = e_vec / e
    else:
        pa = r / rn
    qa = cross(w, pa)
    nu0 = math.atan2(r @ qa, r @ pa)

    # a ground crossing lies between now and the next periapsis (nu = 2 pi, or 0 if
    # falling already: nu0 < 0); on a hyperbola the arc ends at the asymptote
    end = 2.0 * math.pi if nu0 >= 0.0 else 0.0
    start = nu0
    if e >= 1.0:
        end = min(end, math.acos(-1.0 / e) - 1e-9)
    span = end - start
    if span <= 0.0:
        return None
    nu = _ground_crossing(pa, qa, p, e, start, span, radius_eq, radius_polar)
    if math.isnan(nu):
        return None
    dt = _time_between(nu0, nu, e, p, mu)
    position = _on_conic(pa, qa, p, e, nu)
    lat, lon, _ = ecef_to_geodetic(eci_to_ecef(position, t + dt))
    speed = math.sqrt(mu * (2.0 / math.sqrt(position @ position) - (1.0 - e * e) / p))
    return Impact(dt, lat, lon, position, speed)


@njit
def _outside(x, y, z, a, b):
    """``(x^2 + y^2)/a^2 + z^2/b^2 - 1``: positive above the ellipsoid, zero on it."""
    return (x * x + y * y) / (a * a) + z * z / (b * b) - 1.0


@njit
def _on_conic(pa, qa, p, e, nu):
    """The point (m) at true anomaly ``nu`` (rad) of the conic ``r = p / (1 + e cos nu)``
    with unit perifocal axes ``pa`` (to periapsis) and ``qa`` (90 deg ahead)."""
    return p / (1.0 + e * math.cos(nu)) * (math.cos(nu) * pa + math.sin(nu) * qa)


@njit
def _height_sign(pa, qa, p, e, nu, a, b):
    """:func:`_outside` of the conic's point at ``nu`` (:func:`_on_conic`, in scalars)."""
    c, s = math.cos(nu), math.sin(nu)
    radius = p / (1.0 + e * c)
    return _outside(radius * (c * pa[0] + s * qa[0]), radius * (c * pa[1] + s * qa[1]),
                    radius * (c * pa[2] + s * qa[2]), a, b)


@njit
def _ground_crossing(pa, qa, p, e, start, span, a, b):
    """True anomaly (rad) of the first crossing of the ellipsoid ``(a, b)`` from above
    to below on ``[start, start + span]`` of the conic: a scan in STEPS steps, then
    bisection to 1e-12 rad; nan if none."""
    a_prev = start
    f_prev = _height_sign(pa, qa, p, e, start, a, b)
    for k in range(1, STEPS + 1):
        a_next = start + span * k / STEPS
        f_next = _height_sign(pa, qa, p, e, a_next, a, b)
        if f_prev > 0.0 >= f_next:
            lo, hi = a_prev, a_next
            while hi - lo > 1e-12:
                mid = 0.5 * (lo + hi)
                if _height_sign(pa, qa, p, e, mid, a, b) > 0.0:
                    lo = mid
                else:
                    hi = mid
            return hi
        a_prev, f_prev = a_next, f_next
    return math.nan


def _time_between(nu0: float, nu1: float, e: float, p: float, mu: float) -> float:
    """Time (s) to go from true anomaly ``nu0`` to ``nu1 >= nu0`` (rad) on the conic
    of eccentricity ``e`` and semi-latus rectum ``p`` (m): Kepler's equation."""
    if e < 1.0:
        a = p / (1.0 - e * e)
        n = math.sqrt(mu / a ** 3)

        def mean(nu):
            turns = math.floor((nu + math.pi) / (2.0 * math.pi))
            x = nu - 2.0 * math.pi * turns                  # in [-pi, pi)
            big_e = 2.0 * math.atan(math.sqrt((1.0 - e) / (1.0 + e)) * math.tan(0.5 * x))
            return big_e - e * math.sin(big_e) + 2.0 * math.pi * turns
        return (mean(nu1) - mean(nu0)) / n
    a = p / (e * e - 1.0)
    n = math.sqrt(mu / a ** 3)

    def mean(nu):
        f = 2.0 * math.atanh(math.sqrt((e - 1.0) / (e + 1.0)) * math.tan(0.5 * nu))
        return e * math.sinh(f) - f
    return (mean(nu1) - mean(nu0)) / n
