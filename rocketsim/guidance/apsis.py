"""Burns at an apsis: the velocity they aim for, the approach that puts the periapsis
where it is wanted, and the burn centred on the coming periapsis.

A capture, a circularisation or a deorbit burn flown at (or near) an apsis
aims for the velocity, along the local horizontal in the present orbit's
plane, of the orbit whose apsides are the present radius ``r`` and another
radius ``R``: by the vis-viva equation, with ``a = (r + R) / 2``,

    v = sqrt(mu (2 / r - 1 / a)) = sqrt(mu (2 / r - 2 / (r + R)))

(Bate, Mueller & White, *Fundamentals of Astrodynamics*, 1971, eq. 1.8-3):
``R = r`` is the circular velocity, ``R`` above or below ``r`` makes here the
periapsis or the apoapsis (:func:`apsis_velocity`).

An arrival at a planet or the Moon aims its approach at the point beside the
body, across the incoming asymptote, whose hyperbola has its periapsis at
``r_p``: the impact parameter (the asymptote's miss distance) is, from the
conservation of energy and angular momentum between infinity and periapsis
(``b v_inf = r_p v_p``, ``v_p^2 = v_inf^2 + 2 mu / r_p``),

    b = r_p sqrt(1 + 2 mu / (r_p v_inf^2))

(Bate, Mueller & White, sec. 8.3; :func:`impact_parameter`).

:func:`burn_at_periapsis` flies the capture: the burn centred on the coming
periapsis (its time and state from ``fc.predict``, the full field; the burn's
length from the rocket equation), re-aimed every step at the apsis velocity
(:func:`rocketsim.flight.maneuvers.burn`). The shipped programs' lunar orbit
insertion and Mars orbit insertion fly it, the Mars deorbit burn aims at
:func:`apsis_velocity` from where it is.

Units SI (m, s, m/s, m^3/s^2), vectors in the frame of the flight.
"""

from __future__ import annotations

import math

import numpy as np

from rocketsim.constants import SECONDS_PER_DAY
from rocketsim.flight.maneuvers import burn, burn_time
from rocketsim.frames.vectors import cross


def apsis_velocity(position, velocity, other_apsis: float, mu: float) -> np.ndarray:
    """The velocity (m/s) at ``position`` (m), along the local horizontal ahead in the
    plane of ``position`` and ``velocity`` (m/s), of the orbit about ``mu`` whose apsides
    are ``|position|`` and ``other_apsis`` (m)."""
    r = np.asarray(position, dtype=float)
    v = np.asarray(velocity, dtype=float)
    distance = float(np.linalg.norm(r))
    along = cross(cross(r, v), r)
    return math.sqrt(mu * (2.0 / distance - 2.0 / (distance + other_apsis))) * along / np.linalg.norm(along)


def impact_parameter(periapsis: float, v_inf: float, mu: float) -> float:
    """The miss distance (m) of the incoming asymptote of the hyperbola about ``mu`` that
    arrives at ``v_inf`` (m/s) and has its periapsis at radius ``periapsis`` (m)."""
    return periapsis * math.sqrt(1.0 + 2.0 * mu / (periapsis * v_inf * v_inf))


def burn_at_periapsis(fc, other_apsis: float | None, mu: float, label: str, thrust: float, isp: float,
                      horizon: float = 3 * SECONDS_PER_DAY, rcs_turn: bool = False) -> float:
    """Coast to half the burn's length before the next periapsis about the central body
    (``mu``; within ``horizon`` s) and burn there to the orbit whose other apsis is
    ``other_apsis`` (m; None: circular), re-aimed every step at :func:`apsis_velocity`
    from where the vehicle is. ``thrust`` (N), ``isp`` (s), ``label`` and ``rcs_turn``
    as for :func:`~rocketsim.flight.maneuvers.burn`. Returns the delta-v spent (m/s)."""
    t_p, r_p, v_p = fc.predict(horizon, periapsis=True)
    radius = float(np.linalg.norm(r_p))
    wanted = apsis_velocity(r_p, v_p, radius if other_apsis is None else other_apsis, mu)
    length = burn_time(fc.mass, float(np.linalg.norm(v_p) - np.linalg.norm(wanted)), thrust, isp)
    fc.cruise(max(t_p - 0.5 * length - fc.time, 0.0))

    def aim():
        here = float(np.linalg.norm(fc.position))
        return apsis_velocity(fc.position, fc.velocity, here if other_apsis is None else other_apsis, mu)
    return burn(fc, aim, label, thrust, isp, rcs_turn=rcs_turn)
