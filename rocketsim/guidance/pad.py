"""The landing pad and the navigation estimate seen from it: the frames a return's guidance works in.

A return's guidance reasons about the ground: where the stage is over the
rotating Earth, how far it is from its pad, which way is east. :class:`Pad`
holds a target point on the WGS84 ellipsoid (geodetic latitude and longitude,
height 0) as an Earth-fixed (ECEF) position and its local east, north, up
axes (:func:`rocketsim.frames.geodetic.enu_basis`), and reads a flight
computer's estimate (``fc.position``, ``fc.velocity``, ECI) into that frame
(:mod:`rocketsim.frames.earth_fixed`: ECI and ECEF coincide at mission time 0,
the Earth turning at ``EARTH_OMEGA`` since). It reads the navigation estimate
only, never the truth: under ``sensors: realistic`` its numbers carry the
sensors' errors.
"""

from __future__ import annotations

import math

import numpy as np

from rocketsim.frames.earth_fixed import ecef_to_eci, eci_to_ecef, eci_to_ecef_velocity
from rocketsim.frames.geodetic import enu_basis, geodetic_to_ecef


class Pad:
    """A landing point at geodetic ``latitude``, ``longitude`` (rad) on the ellipsoid."""

    def __init__(self, latitude: float, longitude: float):
        self.latitude = latitude
        self.longitude = longitude
        self.position = np.asarray(geodetic_to_ecef(latitude, longitude, 0.0), dtype=float)
        self.axes = enu_basis(latitude, longitude)         # rows east, north, up (ECEF)

    @classmethod
    def target_of(cls, fc) -> "Pad":
        """The mission's target pad (``fc.target.pad``)."""
        pad = fc.target.pad
        if pad is None:
            raise ValueError("the mission names no target pad (mission.target.pad)")
        return cls(pad.latitude, pad.longitude)

    def state(self, fc) -> tuple[np.ndarray, np.ndarray]:
        """Earth-fixed position (m) and velocity over the ground (m/s) of ``fc``'s estimate."""
        r, v, t = fc.position, fc.velocity, fc.time
        return eci_to_ecef(r, t), eci_to_ecef_velocity(r, v, t)

    def local(self, fc) -> tuple[np.ndarray, np.ndarray]:
        """East, north, up of ``fc``'s estimate from the pad (m) and its ground velocity
        in the same axes (m/s)."""
        r, v = self.state(fc)
        return self.axes @ (r - self.position), self.axes @ v

    def offset(self, point) -> np.ndarray:
        """East and north (m) of an Earth-fixed ``point`` (m) from the pad, on the pad's
        tangent plane."""
        return (self.axes @ (np.asarray(point, dtype=float) - self.position))[:2]

    def horizontal(self, east: float, north: float) -> np.ndarray:
        """The Earth-fixed vector ``east`` e + ``north`` n (the pad's axes)."""
        return east * self.axes[0] + north * self.axes[1]

    def to_eci(self, direction, time: float) -> np.ndarray:
        """An Earth-fixed direction at mission ``time`` (s) in ECI axes (what ``fc.point_at``
        takes)."""
        return ecef_to_eci(np.asarray(direction, dtype=float), time)

    def from_eci(self, direction, time: float) -> np.ndarray:
        """An ECI direction at mission ``time`` (s) in Earth-fixed axes."""
        return eci_to_ecef(np.asarray(direction, dtype=float), time)

    def local_to_eci(self, enu, time: float) -> np.ndarray:
        """A vector of the pad's east, north, up axes in ECI axes at mission ``time`` (s)."""
        return self.to_eci(np.asarray(enu, dtype=float) @ self.axes, time)

    def ground_distance(self, fc) -> float:
        """Horizontal distance (m) of ``fc``'s estimate from the pad."""
        offset, _ = self.local(fc)
        return math.hypot(offset[0], offset[1])

