"""What can be read off one body's state at one instant, truth or estimate.

A :class:`StateView` takes a state (position, velocity, attitude, rates in the
ECI of the mission epoch, at mission time ``t``) and derives, lazily and once,
everything a flight program or the telemetry reads: geodetic position,
surface and orbital velocities, local directions, attitude angles, the air,
gravity and the orbit. The same class serves the truth (telemetry) and the
navigation estimate (a program with realistic sensors), so every derived
quantity inherits the estimate's errors.

Conventions: body ``x`` is the nose. ``pitch`` is the nose's elevation above
the local horizon, ``heading`` its azimuth from north towards east, ``roll``
the turn about the nose from the reference attitude whose body ``z`` lies in
the vertical plane through the nose on the ground side of the horizon
(``z = sin(pitch) h - cos(pitch) up``, ``h`` the horizontal heading): a
vehicle flying level with its belly down has roll 0. With the nose within
0.01 deg of vertical the heading is that of body ``z`` and roll is 0.
"""

from __future__ import annotations

import math
from functools import cached_property

import numpy as np

from rocketsim.atmosphere.relative_wind import air_velocity
from rocketsim.atmosphere.table import air_at, wind_earth_fixed
from rocketsim.bodies.gravity import gravity
from rocketsim.constants import EARTH_MU, EARTH_RADIUS_EQ
from rocketsim.frames.earth_fixed import ecef_to_eci, eci_to_ecef
from rocketsim.frames.elements import Elements, state_to_elements, time_to_apoapsis
from rocketsim.frames.geodetic import ecef_to_geodetic, enu_basis
from rocketsim.frames.quaternion import quat_to_matrix

_VERTICAL = math.cos(0.01 * math.pi / 180.0)
_CALM = np.zeros(3)             # no wind: the air velocity is then the surface velocity


class StateView:
    """Derived readings of one state at mission time ``t`` (SI units, ECI vectors)."""

    def __init__(self, t: float, r, v, q, w, atmosphere=None, mu: float = EARTH_MU):
        """``atmosphere``: a function returning the day's AtmosphereTable (called
        only when the air is read)."""
        self.t = t
        self.position = np.asarray(r, dtype=float)
        self.velocity = np.asarray(v, dtype=float)
        self.attitude = np.asarray(q, dtype=float)
        self.body_rates = np.asarray(w, dtype=float)
        self._atmosphere = atmosphere
        self.mu = mu

    # --- where ------------------------------------------------------------
    @cached_property
    def geodetic(self) -> tuple[float, float, float]:
        """(latitude rad, longitude rad, height above WGS84 m)."""
        lat, lon, h = ecef_to_geodetic(eci_to_ecef(self.position, self.t))
        return float(lat), float(lon), float(h)

    @cached_property
    def enu(self) -> np.ndarray:
        """Rows: local east, north, up unit vectors in ECI axes."""
        lat, lon, _ = self.geodetic
        return ecef_to_eci(enu_basis(lat, lon), self.t)

    # --- motion -----------------------------------------------------------
    @cached_property
    def surface_velocity(self) -> np.ndarray:
        """Velocity relative to the rotating Earth, ECI axes (m/s)."""
        return air_velocity(self.position, self.velocity, _CALM)

    @property
    def vertical_speed(self) -> float:
        return float(self.surface_velocity @ self.enu[2])

    @property
    def horizontal_speed(self) -> float:
        v = self.surface_velocity
        return float(np.linalg.norm(v - (v @ self.enu[2]) * self.enu[2]))

    @property
    def radial(self) -> np.ndarray:
        return self.position / np.linalg.norm(self.position)

    @property
    def prograde(self) -> np.ndarray:
        return self.velocity / np.linalg.norm(self.velocity)

    @property
    def normal(self) -> np.ndarray:
        h = np.cross(self.position, self.velocity)
        return h / np.linalg.norm(h)

    @property
    def surface_prograde(self) -> np.ndarray:
        v = self.surface_velocity
        speed = np.linalg.norm(v)
        return v / speed if speed > 0 else self.enu[2].copy()

    # --- attitude -----------------------------------------------------------
    @cached_property
    def axes(self) -> np.ndarray:
        """Body x (nose), y, z as the columns of the body -> ECI matrix."""
        return quat_to_matrix(self.attitude)

    @cached_property
    def euler(self) -> tuple[float, float, float]:
        """(pitch, heading, roll) in radians (see the module's conventions)."""
        east, north, up = self.enu
        nose, z_body = self.axes[:, 0], self.axes[:, 2]
        sin_pitch = float(np.clip(nose @ up, -1.0, 1.0))
        pitch = math.asin(sin_pitch)
        if abs(sin_pitch) >= _VERTICAL:
            # the reference z is the heading itself (nose up) or its opposite
            belly = math.copysign(1.0, sin_pitch) * z_body
            heading = math.atan2(belly @ east, belly @ north)
            return pitch, heading % (2 * math.pi), 0.0
        horizontal = nose - sin_pitch * up
        horizontal /= np.linalg.norm(horizontal)
        heading = math.atan2(horizontal @ east, horizontal @ north)
        z_ref = sin_pitch * horizontal - math.cos(pitch) * up
        roll = math.atan2(nose @ np.cross(z_ref, z_body), z_ref @ z_body)
        return pitch, heading % (2 * math.pi), roll

    # --- air --------------------------------------------------------------
    @cached_property
    def air(self) -> tuple:
        """(density, pressure, temperature, speed of sound, wind ECI, air velocity ECI)."""
        lat, lon, height = self.geodetic
        rho, p, temperature, sound, east, north = air_at(*self._atmosphere().arrays(), height)
        wind = ecef_to_eci(wind_earth_fixed(east, north, lat, lon), self.t)
        return rho, p, temperature, sound, wind, air_velocity(self.position, self.velocity, wind)

    @property
    def airspeed(self) -> float:
        return float(np.linalg.norm(self.air[5]))

    @property
    def mach(self) -> float:
        return self.airspeed / self.air[3]

    @property
    def dynamic_pressure(self) -> float:
        return 0.5 * self.air[0] * self.airspeed ** 2

    @property
    def angle_of_attack(self) -> float:
        """Angle between the nose and the air-relative velocity (rad, 0 in still air)."""
        v_air = self.air[5]
        speed = np.linalg.norm(v_air)
        if speed == 0.0:
            return 0.0
        return math.acos(float(np.clip(self.axes[:, 0] @ v_air / speed, -1.0, 1.0)))

    # --- gravity and orbit ------------------------------------------------
    @property
    def gravity(self) -> float:
        """Magnitude of the local gravitational acceleration (point mass + J2), m/s^2."""
        return float(np.linalg.norm(gravity(self.position)))

    @property
    def effective_gravity(self) -> float:
        """``|g| - v_h^2 / r``, ``v_h`` the inertial horizontal speed (EQUATIONS.md)."""
        r = np.linalg.norm(self.position)
        v = self.velocity
        v_radial = v @ self.position / r
        v_h2 = max(float(v @ v - v_radial ** 2), 0.0)
        return self.gravity - v_h2 / r

    @cached_property
    def orbit(self) -> Elements:
        return state_to_elements(self.position, self.velocity, self.mu)

    @property
    def time_to_apoapsis(self) -> float:
        return time_to_apoapsis(self.position, self.velocity, self.mu)

    @property
    def periapsis_altitude(self) -> float:
        """Periapsis radius less Earth's equatorial radius, m."""
        return self.orbit.periapsis - EARTH_RADIUS_EQ

    @property
    def apoapsis_altitude(self) -> float:
        """Apoapsis radius less Earth's equatorial radius, m (inf if unbound)."""
        return self.orbit.apoapsis - EARTH_RADIUS_EQ
