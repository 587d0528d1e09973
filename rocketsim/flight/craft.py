"""What a flight computer needs of the body it flies: the narrow interface a world implements.

A :class:`~rocketsim.flight.fc.FlightComputer` reads its body's true state
through a :class:`Craft` and acts only through its calls: hand control back
(until a time or a condition), allow a cruise, command an attitude, stop the
RCS, stage, log and record events, ask the ephemeris and the predictor. The
world (:class:`rocketsim.sim.craft.BodyCraft`) decides what each call does to
its bodies; the flight computer never writes a body's fields.
"""

from __future__ import annotations

from typing import Callable, Protocol

import numpy as np

from rocketsim.flight.readings import StateView


class Craft(Protocol):
    """One body of a world, as its flight computer sees and commands it (SI units;
    vectors in the central body's inertial frame)."""

    name: str                   # the body's channel name
    epoch: object               # the mission's :class:`~rocketsim.timescales.Epoch`
    target: object              # the mission's target (TargetSpec)
    pad_azimuth: float          # rad from north (nan without a site)

    @property
    def time(self) -> float:
        """Mission time of the world's current step, s."""

    @property
    def step_index(self) -> int:
        """The world's step count ``k`` (mission time ``k h``)."""

    @property
    def step_length(self) -> float:
        """The world's step ``h``, s."""

    @property
    def t(self) -> float:
        """The body's own mission time, s."""

    @property
    def y(self) -> np.ndarray:
        """The body's true state (read only): :mod:`rocketsim.layout` slots."""

    @property
    def p(self) -> np.ndarray:
        """The body's parameters (read only): :mod:`rocketsim.layout` slots."""

    @property
    def vehicle(self):
        """The staged vehicle's runtime model, or None for a rigid body."""

    @property
    def central(self) -> str:
        """The central body: "earth", "moon", "mars" or "sun"."""

    @property
    def mu(self) -> float:
        """The central body's gravitational parameter, m^3/s^2."""

    @property
    def mass(self) -> float:
        """The body's mass now, kg."""

    @property
    def sensors(self):
        """The body's :class:`~rocketsim.flight.sensors.Sensors` (None: the truth)."""

    @property
    def heat_shield(self):
        """The heat shield's spec (nose radius m...), or None."""

    @property
    def shield_temperature(self) -> float:
        """The lumped heat shield's temperature, K (nan without a shield)."""

    def truth(self) -> StateView:
        """The true state's readings at the body's time (one view a step; while a compiled
        run hands the state over, one for the run, moved to each step)."""

    def handed(self) -> np.ndarray | None:
        """The buffer a compiled run handed the body's state over with (with its navigation
        estimate at this step: :func:`rocketsim.flight.navigation.hand_into`), or None."""

    def is_truth(self, view: StateView | None) -> bool:
        """True when ``view`` is the truth's current view itself."""

    def flies_in_days_air(self) -> bool:
        """True when the vehicle's air arrays are the day's table (about Earth)."""

    def hand_back(self, until: float, predicate: Callable[[], bool] | None = None) -> None:
        """Hand control back to the world until mission time ``until`` (s), or, with
        ``predicate``, until it is true (checked once per step)."""

    def allow_cruise(self, until: float) -> None:
        """Allow cruise rails until mission time ``until`` (s)."""

    def command_attitude(self, command) -> None:
        """Steer to ``command`` (an :class:`~rocketsim.flight.autopilot.AttitudeCommand`);
        None stops steering and every RCS thruster."""

    def stop_rcs(self) -> None:
        """Stop every RCS thruster now."""

    def stage(self) -> str:
        """Separate the lowest stage; returns its new body's name."""

    def jettison_fairing(self) -> tuple[str, str]:
        """Drop the fairing; returns its halves' names."""

    def deploy_payload(self) -> str:
        """Release the payload; returns its name."""

    def deploy_parachute(self, index: int) -> bool:
        """Deploy the vehicle's parachute ``index`` now; False if it was already out."""

    def log(self, message: str) -> None:
        """A line on the telemetry's ``/log`` channel."""

    def event(self, name: str, figures: dict) -> None:
        """An event of this body with its figures."""

    def body_state(self, name: str, at: float | None) -> tuple[np.ndarray, np.ndarray]:
        """Position (m) and velocity (m/s) of the Sun, Earth, Moon or Mars relative to
        the central body at mission time ``at`` (s; default the body's time)."""

    def predict(self, seconds: float, delta_v, periapsis: bool):
        """``(t, r, v)`` where the body coasts in ``seconds`` (s) (the full field)."""
