"""The target orbit of an ascent's insertion guidance: the cut-off state it asks for.

The target (:class:`Orbit`): a periapsis and an apoapsis radius and an
inclination, read as osculating two-body elements or as Kozai mean elements
(circular only; a mission's default, :mod:`rocketsim.frames.mean_elements`).
The insertion is at periapsis (flight-path angle zero); for mean elements the
cut-off state is the osculating state of the mean orbit at the argument of
latitude of the predicted cut-off point (J2's short-period terms: up to 6 km of
radius at 200 km, 0.04 deg of inclination). The node is fixed when given, else
free: the target plane is then, at every cycle, the plane of the inclination
through the predicted cut-off point (:func:`plane_through`), so that the
guidance never spends propellant on a node nobody asked for.

:func:`rocketsim.guidance.peg.cycle` asks :meth:`Orbit.at` for the cut-off state at the
predicted cut-off point every cycle.

Units SI (m, s, kg, m/s, rad), vectors in the inertial frame of the flight
(ECI about Earth), numpy arrays.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from rocketsim.constants import EARTH_J2, EARTH_MU, EARTH_RADIUS_EQ
from rocketsim.frames.elements import Elements, state_to_elements
from rocketsim.frames.mean_elements import mean_elements_of_state, state_of_mean_elements
from rocketsim.frames.vectors import cross


class Target(NamedTuple):
    """What the cut-off must reach: ``radius`` (m from the centre), ``speed`` (m/s) and
    ``flight_path`` (rad above the local horizontal) in the plane of unit ``normal``
    (the direction of ``r x v``)."""

    radius: float
    speed: float
    flight_path: float
    normal: np.ndarray


def plane_normal(inclination: float, raan: float) -> np.ndarray:
    """Unit normal (``r x v`` direction) of the plane of ``inclination`` and ascending node
    ``raan`` (rad), in the frame whose equator they are measured in."""
    s = math.sin(inclination)
    return np.array([s * math.sin(raan), -s * math.cos(raan), math.cos(inclination)])


def plane_through(position, velocity, inclination: float) -> float:
    """The ascending node (rad) of the plane of ``inclination`` through ``position`` whose
    direction of motion there is nearer the ``velocity``'s (of the two planes of that
    inclination through a point; the nearest one when the point's latitude exceeds the
    inclination). With the node ``W``: ``n . r = 0`` is ``rho sin(W - phi) = -z cot(i)``,
    ``rho``, ``phi`` the position's distance from the axis and its right ascension. An
    equatorial plane has no node: 0."""
    x, y, z = (float(c) for c in position)
    rho, phi = math.hypot(x, y), math.atan2(y, x)
    if abs(math.sin(inclination)) * rho == 0.0:
        return 0.0
    s = max(-1.0, min(1.0, -z * math.cos(inclination) / (rho * math.sin(inclination))))
    best = None
    for node in (phi + math.asin(s), phi + math.pi - math.asin(s)):
        along = cross(plane_normal(inclination, node), position)
        score = float(along @ velocity)
        if best is None or score > best[0]:
            best = (score, node % (2.0 * math.pi))
    return best[1]


@dataclass(frozen=True)
class Orbit:
    """A target orbit: ``periapsis`` and ``apoapsis`` radii (m) and ``inclination`` (rad)
    about a body of ``mu`` (m^3/s^2), in the plane of node ``raan`` (rad) or, with ``raan``
    None, in whichever plane of that inclination passes through the cut-off point
    (:func:`plane_through`). ``mean``: Kozai mean elements with that body's J2
    (``radius`` its reference radius, m), circular only; else osculating two-body
    elements. The insertion is at periapsis."""

    periapsis: float
    apoapsis: float
    inclination: float
    raan: float | None = None
    mean: bool = False
    mu: float = EARTH_MU
    radius: float = EARTH_RADIUS_EQ
    j2: float = EARTH_J2

    def __post_init__(self):
        if not 0.0 < self.periapsis <= self.apoapsis:
            raise ValueError(f"a target orbit needs 0 < periapsis <= apoapsis, got {self.periapsis:g} m, "
                             f"{self.apoapsis:g} m")
        if self.mean and self.apoapsis != self.periapsis:
            raise ValueError("a target in mean elements is circular (periapsis = apoapsis)")

    @property
    def energy(self) -> float:
        """The orbit's two-body energy, J/kg (mean elements: the mean orbit's)."""
        return -self.mu / (self.periapsis + self.apoapsis)

    def at(self, point, velocity) -> Target:
        """The cut-off state wanted at ``point`` (m) for a vehicle moving along ``velocity``
        (m/s: which of the two planes of the inclination through the point, when the node
        is free). Osculating elements: the periapsis of the orbit. Mean elements: the
        osculating state of the mean circle at the argument of latitude of ``point``, in
        the osculating plane through ``point`` (free node) or of the osculating node
        (fixed node). J2 is symmetric about the pole, so the osculating state at node
        ``W`` is the one at node 0 turned by ``W`` about the pole: the osculating
        inclination, radius, speed and flight-path angle depend on the argument of
        latitude alone (taken at node 0, the mean argument corrected once so that the
        osculating state's matches the point's)."""
        point = np.asarray(point, dtype=float)
        if not self.mean:
            node = plane_through(point, velocity, self.inclination) if self.raan is None else self.raan
            a = 0.5 * (self.periapsis + self.apoapsis)
            return Target(self.periapsis, math.sqrt(self.mu * (2.0 / self.periapsis - 1.0 / a)), 0.0,
                          plane_normal(self.inclination, node))
        node = plane_through(point, velocity, self.inclination) if self.raan is None else self.raan
        u = _latitude_argument(point, self.inclination, node)
        r, v = self._osculating(u)
        r, v = self._osculating(u - math.remainder(_latitude_argument(r, self.inclination, 0.0) - u, 2.0 * math.pi))
        h = cross(r, v)
        inclination = math.atan2(math.hypot(h[0], h[1]), h[2])
        offset = math.atan2(h[0], -h[1])                  # the osculating node at mean node 0
        node = plane_through(point, velocity, inclination) if self.raan is None else self.raan + offset
        radius, speed = math.sqrt(float(r @ r)), math.sqrt(float(v @ v))
        return Target(radius, speed, math.asin(float(r @ v) / (radius * speed)), plane_normal(inclination, node))

    def reached(self, position, velocity) -> tuple[float, float, float]:
        """The periapsis and apoapsis radii (m) and the inclination (rad) of the orbit of the
        state ``position``, ``velocity`` (m, m/s), in this target's elements (Kozai mean or
        osculating): the figures to compare with the target's. (A mean target read in
        osculating elements is kilometres off: J2's short-period terms.)"""
        elements = (mean_elements_of_state(position, velocity, self.mu, self.radius, self.j2) if self.mean
                    else state_to_elements(np.asarray(position, dtype=float), np.asarray(velocity, dtype=float),
                                           self.mu))
        return elements.periapsis, elements.apoapsis, elements.i

    def _osculating(self, u: float):
        """The osculating state of the mean circle at node 0 and argument of latitude ``u``."""
        return state_of_mean_elements(Elements(self.periapsis, 0.0, self.inclination, 0.0, 0.0,
                                               u % (2.0 * math.pi), self.mu), self.radius, self.j2)


def _latitude_argument(point, inclination: float, node: float) -> float:
    """The angle (rad) of ``point`` from the ascending node ``node`` in the plane of
    ``inclination`` (of the point's projection into it)."""
    line = np.array([math.cos(node), math.sin(node), 0.0])
    return math.atan2(float(cross(plane_normal(inclination, node), line) @ point), float(line @ point))
