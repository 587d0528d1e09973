"""The kinds of body a world flies: a rigid body, a tumbling part, a staged vehicle.

Every body has a state ``y`` and parameters ``p`` (the slots of
:mod:`rocketsim.layout`), its own mission time ``t`` (s), the central body it
falls about (``central``, ``mu`` m^3/s^2), its events and, when a program
flies it, a program runner and a flight computer. The kinds add only what
they need:

* :class:`Body`: a rigid body of fixed mass and inertia (``p``), no air;
* :class:`Part`: a rigid body that tumbles through the air (a fairing half, a
  deployed payload) with its mean drag area per mass and its length;
* :class:`Vehicle`: a staged vehicle whose mass, engines and aerodynamics come
  from its runtime arrays (:class:`rocketsim.vehicle.build.VehicleModel`), the
  stages it still carries, and, with an ``aero:`` section, its once-per-step
  checks.

Fields a kind does not have read as ``None`` (class attributes), so the
world asks ``body.vehicle is None`` whatever the kind.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import partial
from typing import Callable, ClassVar

import numpy as np

from rocketsim.jit import Entries
from rocketsim.constants import EARTH_MU
from rocketsim.dynamics.central import air_about
from rocketsim.flight.fc import FlightComputer
from rocketsim.flight.program import ProgramRunner
from rocketsim.flight.readings import StateView
from rocketsim.flight.sensors import Sensors
from rocketsim.layout import P_MASS, Q, R, V, W
from rocketsim.scenario.models import VehicleSpec
from rocketsim.sim.flight_events import FlightEvents
from rocketsim.sim.vehicle_checks import VehicleChecks
from rocketsim.vehicle.build import VehicleModel
from rocketsim.vehicle.mass_properties import vehicle_mass_properties


@dataclass
class Body:
    """A rigid body in flight: its state, parameters, program and record."""

    name: str
    y: np.ndarray
    p: np.ndarray
    runner: ProgramRunner | None = None
    fc: FlightComputer | None = None
    flying: bool = True
    events: list[dict] = field(default_factory=list)
    mu: float = EARTH_MU
    t: float = 0.0
    atmosphere: Callable[[], object] | None = None    # the day's table, built on first use
    sensors: Sensors | None = None
    _view: StateView | None = None
    watch: FlightEvents | None = None       # liftoff, max-Q, MECO/SECO, orbit
    attitude_command: object | None = None  # what the autopilot steers to (fc.point, hold...)
    cruise_until: float = -math.inf         # mission time fc.cruise allows cruise rails until
    central: str = "earth"                  # the body whose frame and gravity it flies in
    kernels: Entries = field(default_factory=Entries)   # compiled entries bound to its arrays
    # (state, buffer): the buffer a compiled run handed the state y over with, with the step's
    # navigation estimate (rocketsim.flight.navigation.hand_into); read while y is that state
    handed: tuple | None = None

    vehicle: ClassVar[VehicleModel | None] = None
    stack: ClassVar[VehicleSpec | None] = None
    checks: ClassVar[VehicleChecks | None] = None
    steering: ClassVar[tuple | None] = None
    drag: ClassVar[tuple | None] = None

    @property
    def position(self) -> np.ndarray:
        return self.y[R:R + 3]

    @property
    def velocity(self) -> np.ndarray:
        return self.y[V:V + 3]

    @property
    def attitude(self) -> np.ndarray:
        return self.y[Q:Q + 4]

    @property
    def body_rates(self) -> np.ndarray:
        return self.y[W:W + 3]

    @property
    def mass(self) -> float:
        """kg"""
        return float(self.p[P_MASS])

    def view(self) -> StateView:
        """The truth's readings at the body's time (one view per step)."""
        if self._view is None or self._view.t != self.t:
            self._view = self.view_of(self.t, self.y)
        return self._view

    def view_of(self, t: float, y: np.ndarray) -> StateView:
        """The truth's readings of the state ``y`` at mission time ``t`` (s) of this body."""
        # the central body's air: the day's about Earth, Mars's about Mars, none elsewhere
        air = self.atmosphere if self.central == "earth" else partial(air_about, self.central, None)
        return StateView.of_state(t, y, air, self.mu, self.p)

    def handed_with(self, y: np.ndarray) -> np.ndarray | None:
        """The buffer a compiled run handed the state ``y`` over with (:attr:`handed`), or None."""
        handed = self.handed
        return handed[1] if handed is not None and handed[0] is y else None

    def flies_in_days_air(self) -> bool:
        """A staged vehicle whose arrays hold the day's air (its readings' air)."""
        return self.vehicle.arrays.air[2] is self.atmosphere().density     # the density column


@dataclass
class Part(Body):
    """A rigid body tumbling through the air: ``drag`` is its ``(mean drag area /
    mass m^2/kg, length m)`` (:mod:`rocketsim.vehicle.tumbling`)."""

    drag: tuple | None = None


@dataclass
class Vehicle(Body):
    """A staged vehicle: its runtime model, the stages it still carries, and the
    checks of a vehicle with aerodynamics (breakup, heat shield, touchdown)."""

    vehicle: VehicleModel | None = None
    stack: VehicleSpec | None = None        # the stages this body still carries (to separate)
    checks: VehicleChecks | None = None
    steering: tuple | None = None           # the autopilot's step folded into this step's advance

    @property
    def mass(self) -> float:
        """kg, from the propellant the vehicle carries (its compiled entry bound, as the
        runs': a program reads it at most wake-ups)."""
        arrays = self.vehicle.arrays
        return self.kernels.call(vehicle_mass_properties, arrays, arrays, self.y)[0]


def channel_name(name: str) -> str:
    """``name`` as a telemetry channel name: letters, digits, ``-`` and ``_``."""
    return "".join(c if c.isalnum() or c in "-_" else "_" for c in name) or "vehicle"
