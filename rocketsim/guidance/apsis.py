"""The velocity a burn at an apsis aims for: the orbit through here whose other apsis is given.

A capture, a circularisation or a deorbit burn flown at (or near) an apsis
aims for the velocity, along the local horizontal in the present orbit's
plane, of the orbit whose apsides are the present radius ``r`` and another
radius ``R``: by the vis-viva equation, with ``a = (r + R) / 2``,

    v = sqrt(mu (2 / r - 1 / a)) = sqrt(mu (2 / r - 2 / (r + R)))

(Bate, Mueller & White, *Fundamentals of Astrodynamics*, 1971, eq. 1.8-3):
``R = r`` is the circular velocity, ``R`` above or below ``r`` makes here the
periapsis or the apoapsis. The shipped programs' lunar orbit insertion, Mars
orbit insertion and Mars deorbit burns re-aim at it every step
(:func:`rocketsim.flight.maneuvers.burn`).

Units SI (m, m/s, m^3/s^2), vectors in the frame of the flight.
"""

from __future__ import annotations

import math

import numpy as np


def apsis_velocity(position, velocity, other_apsis: float, mu: float) -> np.ndarray:
    """The velocity (m/s) at ``position`` (m), along the local horizontal ahead in the
    plane of ``position`` and ``velocity`` (m/s), of the orbit about ``mu`` whose apsides
    are ``|position|`` and ``other_apsis`` (m)."""
    r = np.asarray(position, dtype=float)
    v = np.asarray(velocity, dtype=float)
    distance = float(np.linalg.norm(r))
    along = np.cross(np.cross(r, v), r)
    return math.sqrt(mu * (2.0 / distance - 2.0 / (distance + other_apsis))) * along / np.linalg.norm(along)
