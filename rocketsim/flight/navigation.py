"""The navigation estimate a flight program reads: the truth, or the truth with sensor errors.

With ``sensors: truth`` (the default) the estimate is the truth's own view.
Otherwise position, velocity, attitude and rates carry the errors of
:mod:`rocketsim.flight.sensors`, drawn once per step (each quantity its own
seeded stream), and a :class:`~rocketsim.flight.readings.StateView` of that
state gives every derived reading, so the altitude, the orbit, the directions
and the air data inherit them. Scalar readings measured by their own sensors
(air data, radar, gauges) get their error once per step in :meth:`measured`.

The estimate itself is one compiled call (:func:`estimate`), the same the
compiled runs make where the autopilot steers on it and a compiled condition
reads it (:mod:`rocketsim.stepping.runs`): each axis its measured value, the
attitude the truth's turned by the measured small rotation.

A compiled run that asks a program's condition read in Python after each step
(``fc.wait_until(lambda: ...)``, :func:`rocketsim.stepping.runs.fly_run`) hands it
the step in one float64 buffer (:func:`hand_into`): the true state and the
estimate, which :meth:`Navigation.view` then takes as it is (the same kernel on the
same numbers: the same bits) rather than drawing it again, in one view for the run
that follows the buffer from step to step
(:meth:`~rocketsim.flight.readings.StateView.following`), its place's readings (the
height, the climb rate...) computed in the run. Its slots: :data:`ANSWER` (the Python
side's answer), the estimate's place readings from :data:`READINGS`, its 13 numbers
(position, velocity, attitude quaternion, rates) from :data:`ESTIMATE`, the state from
:data:`STATE`.
"""

from __future__ import annotations

import math
from typing import Callable

import numpy as np

from rocketsim.jit import copy_into, njit
from rocketsim.flight.craft import Craft
from rocketsim.flight.readings import N_READINGS, StateView, place_readings_into
from rocketsim.flight.sensors import E_ATTITUDE, E_POSITION, E_RATES, E_VELOCITY, measured
from rocketsim.frames.quaternion import quat_from_axis_angle, quat_multiply
from rocketsim.layout import N_STATE, Q, R, V, W

# the slots of a run's hand-over buffer (hand_into)
ANSWER = 0                              # NO_ANSWER while asking; 0.0: go on, 1.0: the run ends there
NO_ANSWER = 2.0
READINGS = 1                            # the estimate's place readings (place_readings_into)
ESTIMATE = READINGS + N_READINGS
STATE = ESTIMATE + N_STATE


@njit
def estimate(y, errors, j):
    """The navigation estimate ``(r, v, q, w)`` (position m, velocity m/s, ECI; attitude
    quaternion body -> ECI; body rates rad/s) of the true state ``y`` with the errors of
    row ``j`` of ``errors`` (:meth:`rocketsim.flight.sensors.Sensors.run_errors`): each
    axis of the position, velocity and rates measured (:func:`~rocketsim.flight.sensors.measured`),
    the attitude the truth's turned by the rotation vector of the three measured
    attitude errors (a tilt of zero leaves it), its angle the norm of ``np.linalg.norm``
    (the square root of the same BLAS dot product)."""
    r, v, w, tilt = np.empty(3), np.empty(3), np.empty(3), np.empty(3)
    for i in range(3):
        r[i] = measured(y[R + i], errors, j, E_POSITION + i)
        v[i] = measured(y[V + i], errors, j, E_VELOCITY + i)
        tilt[i] = measured(0.0, errors, j, E_ATTITUDE + i)
        w[i] = measured(y[W + i], errors, j, E_RATES + i)
    angle = math.sqrt(tilt @ tilt)
    if angle == 0.0:
        return r, v, y[Q:Q + 4].copy(), w
    return r, v, quat_multiply(y[Q:Q + 4], quat_from_axis_angle(tilt / angle, angle)), w


def hand_over_buffer(n: int) -> np.ndarray:
    """A hand-over buffer (:func:`hand_into`) for a state of ``n`` numbers."""
    return np.zeros(STATE + n)


@njit
def hand_into(out, y, errors, j, t, p):
    """Fill the hand-over buffer ``out`` with the true state ``y`` and its navigation
    estimate (with the sensors' ``errors`` of row ``j``; none: the truth), the estimate's
    place readings at mission time ``t`` (s) with the body's parameters ``p``
    (:func:`~rocketsim.flight.readings.place_readings_into`: what a condition reads
    first, there without a call from Python), its answer slot :data:`NO_ANSWER`."""
    if errors.shape[0] > 0:
        r, v, q, w = estimate(y, errors, j)
        copy_into(out, ESTIMATE + R, r)
        copy_into(out, ESTIMATE + V, v)
        copy_into(out, ESTIMATE + Q, q)
        copy_into(out, ESTIMATE + W, w)
    else:
        for i in range(N_STATE):
            out[ESTIMATE + i] = y[i]
    copy_into(out, STATE, y)
    place_readings_into(out[READINGS:ESTIMATE], t, out[ESTIMATE + R:ESTIMATE + R + 3],
                        out[ESTIMATE + V:ESTIMATE + V + 3], p)
    out[ANSWER] = NO_ANSWER


def handed_estimate(buffer: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The estimate in a hand-over buffer (:func:`hand_into`) and its place's readings, views
    of the buffer (for :meth:`~rocketsim.flight.readings.StateView.following`)."""
    return buffer[ESTIMATE:STATE], buffer[READINGS:ESTIMATE]


def tanks(vehicle) -> tuple[str, ...]:
    """The tanks whose propellant gauges a run's errors carry (:meth:`Sensors.run_errors`):
    a staged vehicle's, in its order; none for a rigid body."""
    return () if vehicle is None else tuple(vehicle.tank_names)


class Navigation:
    """The estimate of one body, kept for its step (mission time :attr:`t`): :meth:`view`
    and the scalar readings of the step (``readings``, cleared when the step changes)."""

    def __init__(self, craft: Craft):
        self.craft = craft
        self.t = math.nan                         # the step of current and readings (mission time s)
        self.current: StateView | None = None     # the latest step's estimate
        self.source: StateView | None = None      # the truth's view it was made from
        self.readings: dict[str, object] = {}
        self._following: tuple | None = None      # (hand-over buffer, the estimate's view following it)
        self._perfect: bool | None = None         # the body's sensors are the truth's (known at the first view)

    def view(self) -> StateView:
        """The estimate at the body's time (computed once per step)."""
        craft = self.craft
        t = craft.t
        if t == self.t:
            return self.current
        self.t = t
        if self.readings:
            self.readings = {}
        truth = self.source = craft.truth()
        perfect = self._perfect
        if perfect is None:
            sensors = craft.sensors
            perfect = self._perfect = sensors is None or sensors.perfect
        if perfect:
            self.current = truth
            return truth
        given = craft.handed()
        if given is not None:           # the estimate, from the compiled run: one view a run
            following = self._following
            if following is None or following[0] is not given:
                following = self._following = (given, truth.following(*handed_estimate(given)))
            view = self.current = following[1]
            view.at(t)
            return view
        k = craft.step_index
        errors, first = craft.sensors.run_errors(k, tanks(craft.vehicle))
        r, v, q, w = estimate(craft.y, errors, k - first)
        self.current = StateView(t, r, v, q, w, truth._atmosphere, craft.mu, craft.p)
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
