"""The world's side of the flight computer's interface: one body as its program sees it.

:class:`BodyCraft` implements :class:`rocketsim.flight.craft.Craft` over a
world and one of its bodies: the readings are the body's true state, and each
command is carried out by the world (the program runner hands control back,
the schedule reads the cruise allowance and the attitude command, staging
splits the body). While a compiled run hands the body's state over after each
step (a condition read in Python), the truth's view is one for the run,
following the hand-over buffer (:meth:`~rocketsim.flight.readings.StateView.following`),
and is the body's view at that step.
"""

from __future__ import annotations

import math
from typing import Callable

import numpy as np

from rocketsim.flight.navigation import STATE, handed_estimate
from rocketsim.flight.readings import StateView
from rocketsim.layout import N_STATE
from rocketsim.sim.body import Body

class BodyCraft:
    """``body`` of ``world`` (a :class:`~rocketsim.sim.world.World`) behind the
    :class:`~rocketsim.flight.craft.Craft` interface."""

    def __init__(self, world, body: Body):
        self._world = world
        self._body = body
        self.name = body.name
        self.epoch = world.epoch
        self.target = world.target
        self.pad_azimuth = world.pad_azimuth
        self._following: tuple | None = None    # (hand-over buffer, the truth's view following it)

    # --- readings -----------------------------------------------------------
    @property
    def time(self) -> float:
        world = self._world
        return world.k * world.h        # World.t without its call: a condition reads it every step

    @property
    def step_index(self) -> int:
        return self._world.k

    @property
    def step_length(self) -> float:
        return self._world.h

    @property
    def t(self) -> float:
        return self._body.t

    @property
    def y(self) -> np.ndarray:
        return self._body.y

    @property
    def p(self) -> np.ndarray:
        return self._body.p

    @property
    def vehicle(self):
        return self._body.vehicle

    @property
    def central(self) -> str:
        return self._body.central

    @property
    def mu(self) -> float:
        return self._body.mu

    @property
    def mass(self) -> float:
        return self._body.mass

    @property
    def sensors(self):
        return self._body.sensors

    @property
    def heat_shield(self):
        checks = self._body.checks
        return None if checks is None else checks.shield

    @property
    def shield_temperature(self) -> float:
        checks = self._body.checks
        return math.nan if checks is None or checks.shield is None else float(checks.temperature)

    def truth(self) -> StateView:
        body = self._body
        view = body._view
        if view is not None and view.t == body.t:
            return view
        given = body.handed_with(body.y)
        if given is None:
            return body.view()
        following = self._following     # the state handed over by a compiled run: one view a run
        if following is None or following[0] is not given:
            # the truth's own numbers, or with perfect sensors the estimate's, the same, and
            # the place's readings the run computed with them
            sensors = body.sensors
            state, readings = handed_estimate(given) if sensors is None or sensors.perfect else \
                (given[STATE:STATE + N_STATE], None)
            following = self._following = (given, body.view_of(body.t, state).following(state, readings))
        view = body._view = following[1]
        view.at(body.t)
        return view

    def handed(self) -> np.ndarray | None:
        body = self._body
        return body.handed_with(body.y)

    def is_truth(self, view: StateView | None) -> bool:
        return view is self._body._view

    def flies_in_days_air(self) -> bool:
        return self._body.flies_in_days_air()

    # --- commands (each tells the world first: World.acting) -----------------------
    def hand_back(self, until: float, predicate: Callable[[], bool] | None = None) -> None:
        self._body.runner.hand_back(until, predicate)

    def allow_cruise(self, until: float) -> None:
        self._world.acting()
        self._body.cruise_until = until

    def command_attitude(self, command) -> None:
        self._world.acting()
        self._body.attitude_command = command
        if command is None:
            self.stop_rcs()

    def stop_rcs(self) -> None:
        self._world.acting()
        if self._body.vehicle is not None:
            self._body.vehicle.arrays.aero.rcs_cmd[:] = 0.0

    def stage(self) -> str:
        self._world.acting()
        return self._world.separate(self._body).name

    def jettison_fairing(self) -> tuple[str, str]:
        self._world.acting()
        return tuple(half.name for half in self._world.jettison_fairing(self._body))

    def deploy_payload(self) -> str:
        self._world.acting()
        return self._world.deploy_payload(self._body).name

    def deploy_parachute(self, index: int) -> bool:
        self._world.acting()
        return self._body.watch.deploy(index, "program")

    def log(self, message: str) -> None:
        self._world.acting()
        self._world.log(self._body, message)

    def event(self, name: str, figures: dict) -> None:
        self._world.acting()
        self._world.event(self._body, name, figures)

    def body_state(self, name: str, at: float | None = None) -> tuple[np.ndarray, np.ndarray]:
        return self._world.body_state(self._body, name, at)

    def predict(self, seconds: float, delta_v=None, periapsis: bool = False):
        return self._world.predict(self._body, seconds, delta_v, periapsis)
