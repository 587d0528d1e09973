"""The sun-synchronous inclination: the orbit whose mean node follows the mean Sun.

J2 turns an orbit's ascending node at the secular rate, in mean elements
(Kozai's, :mod:`rocketsim.frames.mean_elements`; the semi-major axis, the
eccentricity and the inclination of the orbit with its short-period J2
ripple removed). To first order in J2 (Vallado, *Fundamentals of
Astrodynamics and Applications*, 4th ed., eq. 9-41; docs/physics.md#j2)

    dOmega/dt = -(3/2) n J2 (R/p)^2 cos i,    n = sqrt(mu/a^3),  p = a (1 - e^2);

J2 acting on its own first-order motion adds a second-order secular term
(Brouwer, "Solution of the problem of artificial satellite theory without
drag", Astron. J. 64, 378, 1959, the node's secular rate with J4 = 0):

    dOmega/dt = n [-3 g cos i + (3/8) g^2 ((-5 + 12 eta + 9 eta^2) cos i
                                         + (-35 - 36 eta - 5 eta^2) cos^3 i)],
    g = (J2/2) (R/p)^2,  eta = sqrt(1 - e^2).

The second-order term is -0.08 % of the rate of a 700 km sun-synchronous
orbit, -0.0008 deg/day: left out, the orbit's mean node drifts from the
Sun's by that much (measured on a 30-day rails flight in the tests).

An orbit is sun-synchronous when the rate is the mean Sun's, 2 pi per
tropical year (:data:`rocketsim.constants.TROPICAL_YEAR`): retrograde,
96-100 deg in low Earth orbit. Units: m, rad; Earth's WGS84 radius and mu and
EGM96 J2 by default.
"""

from __future__ import annotations

import math

from rocketsim.constants import EARTH_J2, EARTH_MU, EARTH_RADIUS_EQ, TROPICAL_YEAR


def _rate_terms(a: float, e: float, mu: float, radius: float, j2: float):
    """``(n, A, B)`` with the secular node rate ``n (A cos i + B cos^3 i)`` (rad/s)."""
    eta = math.sqrt(1.0 - e * e)
    g = 0.5 * j2 * (radius / (a * eta * eta)) ** 2
    n = math.sqrt(mu / a**3)
    first = -3.0 * g + 0.375 * g * g * (-5.0 + 12.0 * eta + 9.0 * eta * eta)
    return n, first, 0.375 * g * g * (-35.0 - 36.0 * eta - 5.0 * eta * eta)


def nodal_rate(a: float, e: float, i: float, mu: float = EARTH_MU, radius: float = EARTH_RADIUS_EQ,
               j2: float = EARTH_J2) -> float:
    """Secular rate (rad/s) of the ascending node of mean elements ``a`` (m), ``e``,
    ``i`` (rad), to second order in J2."""
    n, first, third = _rate_terms(a, e, mu, radius, j2)
    c = math.cos(i)
    return n * (first * c + third * c**3)


def sun_synchronous_inclination(altitude: float, eccentricity: float = 0.0, mu: float = EARTH_MU,
                                radius: float = EARTH_RADIUS_EQ, j2: float = EARTH_J2) -> float:
    """Mean inclination (rad) that makes an orbit of mean semi-major axis
    ``radius + altitude`` (m) and ``eccentricity`` sun-synchronous. Raises
    ValueError above ~5 970 km (circular), where no inclination turns the node
    fast enough."""
    a = radius + altitude
    n, first, third = _rate_terms(a, eccentricity, mu, radius, j2)
    want = 2.0 * math.pi / TROPICAL_YEAR / n
    c = want / first                                    # first order, then Newton on the cubic
    for _ in range(8):
        c -= (first * c + third * c**3 - want) / (first + 3.0 * third * c * c)
    if not c >= -1.0:
        raise ValueError(f"no sun-synchronous orbit at {altitude / 1e3:.0f} km: J2 turns the node too slowly there")
    return math.acos(c)


def sun_synchronous_osculating_inclination(a: float, e: float, raan: float, argp: float, nu: float,
                                           mu: float = EARTH_MU, radius: float = EARTH_RADIUS_EQ,
                                           j2: float = EARTH_J2) -> float:
    """Osculating inclination (rad) that makes the orbit of osculating ``a`` (m),
    ``e``, ``raan``, ``argp`` and ``nu`` (rad) sun-synchronous: the one whose
    Kozai mean elements have the sun-synchronous mean inclination for their mean
    semi-major axis and eccentricity (by fixed-point iteration; each gains a
    factor ~J2)."""
    from rocketsim.frames.elements import Elements
    from rocketsim.frames.mean_elements import osculating_to_mean
    i = sun_synchronous_inclination(a - radius, e, mu, radius, j2)
    for _ in range(6):
        mean = osculating_to_mean(Elements(a, e, i, raan, argp, nu, mu), radius, j2)
        i += sun_synchronous_inclination(mean.a - radius, mean.e, mu, radius, j2) - mean.i
    return i
