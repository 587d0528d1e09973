"""Pricing the burns at both ends of a patched-conic transfer.

The transfer arc (from :func:`rocketsim.transfer.lambert`) leaves the
departure body with a hyperbolic excess velocity ``v_inf = v1 - v_body`` and
arrives with ``v2 - v_target``. The relations (docs/physics.md#burns; Curtis,
*Orbital Mechanics for Engineering Students*, sections 8.6-8.7):

* characteristic energy ``C3 = |v_inf|^2``;
* escape from a circular parking orbit of radius ``r_p`` with a single
  tangential burn: ``dv = sqrt(v_inf^2 + 2 mu / r_p) - sqrt(mu / r_p)``;
* capture at periapsis ``r_p`` into an orbit of apoapsis ``r_a``:
  ``dv = sqrt(v_inf^2 + 2 mu / r_p) - sqrt(2 mu r_a / (r_p (r_p + r_a)))``;
* the departure asymptote's right ascension and declination, from the
  direction of ``v_inf`` in the J2000 equatorial frame (the declination
  limits which launch sites can reach the asymptote directly).

Units SI (m, m/s, m^2/s^2, m^3/s^2, rad). Everything broadcasts.
"""

from __future__ import annotations

import numpy as np


def v_infinity(v_spacecraft, v_body):
    """Hyperbolic excess velocity vector relative to a body (m/s, last axis 3)."""
    return np.asarray(v_spacecraft, dtype=float) - np.asarray(v_body, dtype=float)


def c3(v_inf):
    """Characteristic energy ``|v_inf|^2`` (m^2/s^2) of an excess-velocity vector."""
    v_inf = np.asarray(v_inf, dtype=float)
    return np.sum(v_inf * v_inf, axis=-1)


def escape_dv(mu, r_park, v_inf):
    """Δv (m/s) from a circular orbit of radius ``r_park`` (m) to excess speed ``v_inf`` (m/s)
    about a body of gravitational parameter ``mu`` (m^3/s^2).

    One impulsive burn at the periapsis of the departure hyperbola, tangent
    to the parking orbit. ``v_inf`` is a speed; ``v_inf**2`` may be given
    negative through :func:`escape_dv_c3` for bound (e.g. lunar) transfers.
    """
    return escape_dv_c3(mu, r_park, np.square(v_inf))


def escape_dv_c3(mu, r_park, c3_value):
    """Δv (m/s) from a circular orbit of radius ``r_park`` (m) to energy ``C3`` (m^2/s^2)
    about a body of gravitational parameter ``mu`` (m^3/s^2).

    Valid for negative ``C3`` too (an ellipse with periapsis at ``r_park``),
    as long as ``C3 > -mu / r_park`` (the burn raises the apoapsis).
    """
    mu = np.asarray(mu, dtype=float)
    r_park = np.asarray(r_park, dtype=float)
    return np.sqrt(c3_value + 2.0 * mu / r_park) - np.sqrt(mu / r_park)


def capture_dv(mu, r_periapsis, r_apoapsis, v_inf):
    """Δv (m/s) to brake from excess speed ``v_inf`` (m/s) into an orbit ``r_periapsis`` ×
    ``r_apoapsis`` (m) about a body of gravitational parameter ``mu`` (m^3/s^2).

    One impulsive burn at the periapsis of the arrival hyperbola, which is
    also the periapsis of the captured ellipse (``r_apoapsis >= r_periapsis``;
    equal for a circular orbit).
    """
    mu = np.asarray(mu, dtype=float)
    rp = np.asarray(r_periapsis, dtype=float)
    ra = np.asarray(r_apoapsis, dtype=float)
    v_hyperbola = np.sqrt(np.square(v_inf) + 2.0 * mu / rp)
    v_ellipse = np.sqrt(2.0 * mu * ra / (rp * (rp + ra)))
    return v_hyperbola - v_ellipse


def asymptote_direction(v_inf):
    """Right ascension and declination (rad) of an excess-velocity vector.

    ``v_inf`` in the J2000 equatorial frame (last axis 3). Returns
    ``(ra, dec)`` with ``ra`` in [0, 2 pi) and ``dec`` in [-pi/2, pi/2]:
    for a departure, the RLA and DLA of the outgoing asymptote.
    """
    v = np.asarray(v_inf, dtype=float)
    ra = np.mod(np.arctan2(v[..., 1], v[..., 0]), 2.0 * np.pi)
    dec = np.arctan2(v[..., 2], np.hypot(v[..., 0], v[..., 1]))
    return ra, dec
