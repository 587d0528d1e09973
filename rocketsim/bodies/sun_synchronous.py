"""The sun-synchronous inclination: the orbit whose node follows the mean Sun.

J2 turns an orbit's ascending node at the secular rate (Vallado,
*Fundamentals of Astrodynamics and Applications*, 4th ed., eq. 9-41;
docs/physics.md#j2)

    dOmega/dt = -(3/2) n J2 (R/p)^2 cos i,    n = sqrt(mu/a^3),  p = a (1 - e^2)

An orbit is sun-synchronous when that rate is the mean Sun's, 2 pi per
tropical year (:data:`rocketsim.constants.TROPICAL_YEAR`), so

    cos i = -(2/3) (dOmega/dt) a^(7/2) (1 - e^2)^2 / (J2 R^2 sqrt(mu))

(retrograde, 96-100 deg in low Earth orbit). Units: m, rad; Earth's WGS84
radius and mu and EGM96 J2 by default.
"""

from __future__ import annotations

import math

from rocketsim.constants import EARTH_J2, EARTH_MU, EARTH_RADIUS_EQ, TROPICAL_YEAR


def sun_synchronous_inclination(altitude: float, eccentricity: float = 0.0, mu: float = EARTH_MU,
                                radius: float = EARTH_RADIUS_EQ, j2: float = EARTH_J2) -> float:
    """Inclination (rad) that makes an orbit of semi-major axis ``radius + altitude``
    (m) and ``eccentricity`` sun-synchronous. Raises ValueError above ~5 970 km
    (circular), where no inclination turns the node fast enough."""
    a = radius + altitude
    rate = 2.0 * math.pi / TROPICAL_YEAR
    cos_i = -2.0 / 3.0 * rate * a ** 3.5 * (1.0 - eccentricity ** 2) ** 2 / (j2 * radius ** 2 * math.sqrt(mu))
    if cos_i < -1.0:
        raise ValueError(f"no sun-synchronous orbit at {altitude / 1e3:.0f} km: J2 turns the node too slowly there")
    return math.acos(cos_i)
