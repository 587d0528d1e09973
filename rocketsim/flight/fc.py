"""``fc``: what a flight program sees of its vehicle, and how it hands back control.

This is the foundation's part of the flight-computer API: the scheduling calls
(:meth:`FlightComputer.step`, :meth:`~FlightComputer.sleep`,
:meth:`~FlightComputer.wait_until`), logging and events, and the readings of
the vehicle's state. All values are SI (m, s, kg, rad) unless a name ends in
``_deg``; vectors are numpy arrays in the inertial frame (ECI of the mission
epoch) unless stated.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Callable

import numpy as np

from rocketsim.frames.elements import Elements

if TYPE_CHECKING:  # pragma: no cover
    from rocketsim.sim.world import Body, World


class FlightComputer:
    """The program's handle on one body of the world."""

    def __init__(self, world: "World", body: "Body"):
        self._world = world
        self._body = body

    # --- timing -------------------------------------------------------------
    def step(self) -> None:
        """Hand control back; the program resumes at the next step."""
        self._body.runner.hand_back(self._world.t + self._world.h)

    def sleep(self, seconds: float) -> None:
        """Hand control back for ``seconds`` of mission time (at least one step)."""
        if not seconds >= 0:
            raise ValueError(f"fc.sleep() needs a duration >= 0 s, got {seconds!r}")
        self._body.runner.hand_back(self._world.t + max(seconds, self._world.h))

    def wait_until(self, predicate: Callable[[], bool]) -> None:
        """Hand control back until ``predicate()`` is true (checked once per step)."""
        if not callable(predicate):
            raise TypeError("fc.wait_until() needs a function, e.g. lambda: fc.altitude > 1e5")
        self._body.runner.hand_back(self._world.t + self._world.h, predicate)

    # --- output -------------------------------------------------------------
    def log(self, *parts) -> None:
        """Write a line to the telemetry's ``/log`` channel."""
        self._world.log(self._body, " ".join(str(p) for p in parts))

    def event(self, name: str, **figures) -> None:
        """Record a named event with its figures (numbers or strings)."""
        self._world.event(self._body, str(name), figures)

    # --- readings -----------------------------------------------------------
    @property
    def time(self) -> float:
        """Mission time, s since the epoch (liftoff)."""
        return self._world.t

    @property
    def utc(self):
        """UTC as a timezone-aware datetime (leap seconds ignored)."""
        return self._world.epoch.utc_at(self._world.t)

    @property
    def position(self) -> np.ndarray:
        """Centre-of-mass position, ECI, m."""
        return self._body.position.copy()

    @property
    def velocity(self) -> np.ndarray:
        """Inertial velocity, ECI, m/s."""
        return self._body.velocity.copy()

    @property
    def attitude(self) -> np.ndarray:
        """Unit quaternion (w, x, y, z), body axes -> ECI."""
        return self._body.attitude.copy()

    @property
    def body_rates(self) -> np.ndarray:
        """Body rates about x (roll), y, z, rad/s."""
        return self._body.body_rates.copy()

    @property
    def mass(self) -> float:
        """Current mass, kg."""
        return self._body.mass

    @property
    def altitude(self) -> float:
        """Height above the WGS84 ellipsoid, m."""
        return self._body.geodetic()[2]

    @property
    def latitude(self) -> float:
        """Geodetic latitude, rad."""
        return self._body.geodetic()[0]

    @property
    def longitude(self) -> float:
        """Longitude, east positive, rad."""
        return self._body.geodetic()[1]

    # --- the air (the day's weather at the vehicle) -------------------------
    @property
    def air_density(self) -> float:
        """Density of the air at the vehicle, kg/m^3 (zero above 600 km)."""
        return self._air()[0]

    @property
    def air_pressure(self) -> float:
        """Static pressure of the air at the vehicle, Pa (zero above 600 km)."""
        return self._air()[1]

    @property
    def air_temperature(self) -> float:
        """Temperature of the air at the vehicle, K."""
        return self._air()[2]

    @property
    def speed_of_sound(self) -> float:
        """Speed of sound at the vehicle, m/s."""
        return self._air()[3]

    @property
    def wind(self) -> np.ndarray:
        """The wind at the vehicle (air velocity over the ground), ECI, m/s."""
        return self._air()[4].copy()

    @property
    def air_velocity(self) -> np.ndarray:
        """Velocity relative to the air, ``v - omega_E x r - wind``, ECI, m/s."""
        return self._air()[5].copy()

    @property
    def airspeed(self) -> float:
        """Speed relative to the air, m/s."""
        return float(np.linalg.norm(self._air()[5]))

    @property
    def mach(self) -> float:
        """Airspeed over the local speed of sound."""
        return self.airspeed / self.speed_of_sound

    @property
    def dynamic_pressure(self) -> float:
        """``q = rho |v_air|^2 / 2``, Pa."""
        return 0.5 * self.air_density * self.airspeed ** 2

    def _air(self):
        return self._body.air(self._world.atmosphere)

    @property
    def orbit(self) -> Elements:
        """Osculating orbital elements about the central body (ECI axes)."""
        return self._body.elements()
