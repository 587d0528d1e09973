"""The navigation estimate a flight program reads: the truth, or the truth with sensor errors.

With ``sensors: truth`` (the default) the estimate is the truth's own view.
Otherwise position, velocity, attitude and rates carry the errors of
:mod:`rocketsim.flight.sensors`, drawn once per step (each quantity its own
seeded stream), and a :class:`~rocketsim.flight.readings.StateView` of that
state gives every derived reading, so the altitude, the orbit, the directions
and the air data inherit them. Scalar readings measured by their own sensors
(air data, radar, gauges) get their error once per step in :meth:`measured`.
"""

from __future__ import annotations

from typing import Callable

import numpy as np

from rocketsim.flight.craft import Craft
from rocketsim.flight.readings import StateView
from rocketsim.frames.quaternion import quat_from_axis_angle, quat_multiply


class Navigation:
    """The estimate of one body, kept for its step: :meth:`view` and the scalar
    readings of the step (``readings``, cleared when the step changes)."""

    def __init__(self, craft: Craft):
        self.craft = craft
        self.current: StateView | None = None     # the latest step's estimate
        self.readings: dict[str, object] = {}

    def view(self) -> StateView:
        """The estimate at the body's time (computed once per step)."""
        craft = self.craft
        t = craft.t
        if self.current is not None and self.current.t == t:
            return self.current
        truth = craft.truth()
        sensors = craft.sensors
        self.readings = {}
        if sensors is None or sensors.perfect:
            self.current = truth
            return truth
        k = craft.step_index
        tilt = sensors.vector("attitude", (0.0, 0.0, 0.0), k)
        angle = float(np.linalg.norm(tilt))
        q = truth.attitude if angle == 0.0 else quat_multiply(
            truth.attitude, quat_from_axis_angle(tilt / angle, angle))
        self.current = StateView(t, sensors.vector("position", truth.position, k),
                                 sensors.vector("velocity", truth.velocity, k), q,
                                 sensors.vector("rates", truth.body_rates, k), truth._atmosphere, craft.mu,
                                 craft.p)
        return self.current

    def measured(self, name: str, value: Callable[[], float]) -> float:
        """A scalar reading with its sensor's error (air data, radar, gauges), once per step."""
        self.view()
        if name not in self.readings:
            sensors = self.craft.sensors
            truth = value()
            self.readings[name] = truth if sensors is None or sensors.perfect else \
                sensors.scalar(name, truth, self.craft.step_index)
        return self.readings[name]
