"""Transfer arcs between every departure and arrival date of a grid, and their burns.

For every pair (departure date, arrival date) the transfer arc is a Lambert
solution (:func:`rocketsim.transfer.lambert`, zero revolutions, prograde) between
the bodies' positions from the ephemeris; the burns at its ends are priced with
:mod:`rocketsim.transfer.burns`. Over a grid of dates the arcs are the porkchop
plot that :mod:`rocketsim.transfer.windows` searches for launch windows.

Targets (patched conics):

* ``"mars"``: heliocentric arc from the Earth's centre at departure to
  Mars' centre at arrival (the spheres of influence are points). C3 and the
  departure asymptote's declination come from the excess velocity at Earth;
  escape from a circular parking orbit, capture into the requested orbit.
* ``"moon"``: geocentric arc from a circular parking orbit to the Moon's
  centre (the Moon's motion from the ephemeris, its gravity ignored until
  arrival). Assumes the parking orbit lies in the Moon's orbital plane at
  arrival and the burn is made 179 degrees of transfer angle before the
  arrival point (a near-Hohmann departure from periapsis; an exact 180
  degrees would leave the plane undefined). C3 is the geocentric energy
  ``v1^2 - 2 mu / r_park`` (negative: bound), the departure Δv is
  ``|v1 - v_circular|``, the "declination" the Moon's at arrival, which the
  parking orbit's inclination must reach.

Dates are Julian dates in TT (``jd_tt``); times of flight in days. The
ephemeris is a parameter ``ephemeris(body, jd_tt, center) -> (r, v)`` (m,
m/s, J2000 equatorial, ``jd_tt`` an array giving ``(N, 3)``), by default
:func:`rocketsim.ephemeris.solar_system.state`; the tests pass synthetic ones.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy as np

from rocketsim.constants import (
    EARTH_MU,
    EARTH_RADIUS_EQ,
    MARS_MU,
    MARS_RADIUS_EQ,
    MOON_MU,
    MOON_RADIUS,
    SECONDS_PER_DAY,
    SUN_MU,
)
from rocketsim.errors import InputError
from rocketsim.transfer.burns import asymptote_direction, c3, capture_dv, escape_dv_c3
from rocketsim.transfer.lambert import lambert

# Validity span of the project's truncated VSOP87D/ELP2000 series
# (rocketsim/ephemeris/generate.py: "validity span 1950-2100"), as TT Julian
# dates of 1950-01-01 and 2100-01-01.
EPHEMERIS_SPAN_JD = (2433282.5, 2488069.5)

MOON_TRANSFER_ANGLE = math.radians(179.0)


@dataclass(frozen=True)
class Target:
    """How a transfer to a target is set up (see the module)."""

    name: str
    center: str                 # body at the centre of the transfer arc
    center_mu: float            # m^3/s^2
    departure_mu: float         # body orbited before departure
    departure_radius: float     # m, its equatorial radius (parking altitude origin)
    arrival_body: str
    arrival_mu: float
    arrival_radius: float       # m
    tof_days: tuple[float, float]   # default time-of-flight range searched


TARGETS = {
    "mars": Target("mars", "sun", SUN_MU, EARTH_MU, EARTH_RADIUS_EQ, "mars", MARS_MU,
                   MARS_RADIUS_EQ, (90.0, 500.0)),
    "moon": Target("moon", "earth", EARTH_MU, EARTH_MU, EARTH_RADIUS_EQ, "moon", MOON_MU,
                   MOON_RADIUS, (2.0, 8.0)),
}


def target(name: str) -> Target:
    """The :class:`Target` called ``name`` ("mars" or "moon")."""
    try:
        return TARGETS[str(name).lower()]
    except KeyError:
        raise InputError(f"unknown target {name!r}: expected one of {', '.join(TARGETS)}",
                         field="target") from None


def default_ephemeris(body, jd_tt, center):
    """The bodies' ``(r, v)`` from the project's series (see the module)."""
    from rocketsim.ephemeris.solar_system import state
    return state(body, jd_tt, center=center)


@dataclass(frozen=True)
class Orbits:
    """Parking orbit at departure and capture orbit at arrival (altitudes, m)."""

    parking_altitude: float = 200e3
    capture_periapsis_altitude: float = 400e3
    capture_apoapsis_altitude: float | None = None   # None: circular


@dataclass
class Arcs:
    """Transfer arcs and burn prices over a grid (arrays of one common shape)."""

    departure_jd: np.ndarray
    arrival_jd: np.ndarray
    tof_days: np.ndarray
    c3: np.ndarray                  # m^2/s^2
    vinf_departure: np.ndarray      # (..., 3) m/s
    vinf_arrival: np.ndarray        # m/s (speed)
    dv_departure: np.ndarray        # m/s
    dv_arrival: np.ndarray          # m/s
    rla: np.ndarray                 # rad
    dla: np.ndarray                 # rad
    valid: np.ndarray               # bool: a transfer was computed here

    @property
    def dv_total(self) -> np.ndarray:
        return self.dv_departure + self.dv_arrival


def check_dates(jd_tt, what: str) -> None:
    """InputError if a TT Julian date lies outside the ephemeris span."""
    jd = np.asarray(jd_tt, dtype=float)
    lo, hi = EPHEMERIS_SPAN_JD
    outside = (jd < lo) | (jd > hi)
    if np.any(outside):
        bad = float(jd[outside].ravel()[0])
        raise InputError(f"JD(TT) {bad:.1f} lies outside the span of the ephemerides, "
                         "1950-01-01 to 2100-01-01", field=what)


def arcs(departure_jd, arrival_jd, *, target_name: str = "mars", orbits: Orbits = Orbits(),
         ephemeris: Callable | None = None, departure_states=None,
         arrival_states=None) -> Arcs:
    """Transfer arcs between every departure and arrival date (broadcast together).

    ``departure_jd`` and ``arrival_jd`` are TT Julian dates that broadcast
    (e.g. ``(N, 1)`` and ``(1, M)`` for a grid). Pairs with a time of flight
    under one hour are marked invalid (their fields are NaN).
    ``departure_states``/``arrival_states`` optionally give precomputed
    ``(r, v)`` of the departure and arrival bodies at those dates.
    """
    tgt = target(target_name)
    eph = ephemeris or default_ephemeris
    dep = np.asarray(departure_jd, dtype=float)
    arr = np.asarray(arrival_jd, dtype=float)
    shape = np.broadcast_shapes(dep.shape, arr.shape)
    if departure_states is None:
        departure_states = body_states(eph, "earth", dep, tgt.center)
    if arrival_states is None:
        arrival_states = body_states(eph, tgt.arrival_body, arr, tgt.center)
    r_dep, v_dep = departure_states
    r_arr, v_arr = arrival_states
    tof = (arr - dep) * SECONDS_PER_DAY
    tof_b = np.broadcast_to(tof, shape)
    valid = tof_b > 3600.0
    idx = np.nonzero(valid)
    r_dep_b = np.broadcast_to(r_dep, shape + (3,))[idx]
    v_dep_b = np.broadcast_to(v_dep, shape + (3,))[idx]
    r_arr_b = np.broadcast_to(r_arr, shape + (3,))[idx]
    v_arr_b = np.broadcast_to(v_arr, shape + (3,))[idx]

    r_park = tgt.departure_radius + orbits.parking_altitude
    if tgt.name == "moon":
        r1, v_circ = _lunar_departure_points(r_arr_b, v_arr_b, r_park, tgt.center_mu)
    else:
        r1 = r_dep_b
    v1, v2 = lambert(tgt.center_mu, r1, r_arr_b, tof_b[idx])

    rp_cap = tgt.arrival_radius + orbits.capture_periapsis_altitude
    ra_cap = (rp_cap if orbits.capture_apoapsis_altitude is None
              else tgt.arrival_radius + orbits.capture_apoapsis_altitude)
    vinf_arr = np.linalg.norm(v2 - v_arr_b, axis=-1)
    if tgt.name == "moon":
        vinf_dep = v1 - v_circ            # the departure burn itself
        energy = np.sum(v1 * v1, axis=-1) - 2.0 * tgt.center_mu / r_park
        dv_dep = np.linalg.norm(vinf_dep, axis=-1)
        rla, dla = asymptote_direction(r_arr_b)
    else:
        vinf_dep = v1 - v_dep_b
        energy = c3(vinf_dep)
        dv_dep = escape_dv_c3(tgt.departure_mu, r_park, energy)
        rla, dla = asymptote_direction(vinf_dep)
    dv_arr = capture_dv(tgt.arrival_mu, rp_cap, ra_cap, vinf_arr)

    def full(values, extra=()):
        out = np.full(shape + extra, np.nan)
        out[idx] = values
        return out

    return Arcs(np.broadcast_to(dep, shape), np.broadcast_to(arr, shape),
                tof_b / SECONDS_PER_DAY, full(energy), full(vinf_dep, (3,)), full(vinf_arr),
                full(dv_dep), full(dv_arr), full(rla), full(dla), valid)


def body_states(eph, body, jd, center):
    """``(r, v)`` of ``body`` about ``center`` at the TT Julian dates ``jd`` from ``eph``,
    each shaped ``jd.shape + (3,)`` (m, m/s)."""
    flat = np.ascontiguousarray(jd, dtype=float).reshape(-1)
    r, v = eph(body, flat, center)
    r = np.asarray(r, dtype=float).reshape(jd.shape + (3,))
    v = np.asarray(v, dtype=float).reshape(jd.shape + (3,))
    return r, v


def _lunar_departure_points(r_moon, v_moon, r_park, mu):
    """Parking-orbit departure points 179 deg before the Moon, in its plane."""
    h = np.cross(r_moon, v_moon)
    h_hat = h / np.linalg.norm(h, axis=-1, keepdims=True)
    u = r_moon / np.linalg.norm(r_moon, axis=-1, keepdims=True)
    w = np.cross(h_hat, u)                       # direction of the Moon's motion
    theta = MOON_TRANSFER_ANGLE
    r1_hat = math.cos(theta) * u - math.sin(theta) * w
    r1 = r_park * r1_hat
    v_circ = math.sqrt(mu / r_park) * np.cross(h_hat, r1_hat)
    return r1, v_circ
