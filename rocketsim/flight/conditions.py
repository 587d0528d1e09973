"""Conditions of ``fc.wait_until`` the simulator can test in compiled code.

``fc.below("altitude", 10_000)`` is a :class:`Condition`: called, it reads the
flight computer as the program would (``fc.altitude < 10_000``), so it serves
wherever a function of no arguments does; conditions combine with ``&`` (and)
and ``|`` (or), evaluated left to right like Python's ``and`` and ``or``.
Because the simulator knows what such a condition reads, it tests it in the
same compiled call that advances the vehicle (:func:`holds`, once per step on
the state at the step's end, the state the program's readings would see), so
a vehicle waiting on one is flown many steps per call instead of one (see
:mod:`rocketsim.stepping.runs`); the test gives the same boolean at the same step as
the reading's, from the same operations on the same numbers.

Readings (:data:`READINGS`), of the navigation estimate about Earth (the
truth, or with the sensors' errors: :func:`holds` reads the same estimate; a
program flying about another body has its condition read in Python every
step, as a lambda's):

* ``altitude``: height above the WGS84 ellipsoid, m (:attr:`FlightComputer.altitude`);
* ``vertical_speed``: rate of climb relative to the ground, m/s
  (:attr:`FlightComputer.vertical_speed`);
* ``propellant``: the liquid propellant left in one stage's tanks, kg (the sum of
  their entries of :attr:`FlightComputer.propellant`, in the vehicle's order);
* ``time``: mission time, s (:attr:`FlightComputer.time`), a timeout beside another
  condition;
* ``nose_angle``: the angle between the nose (body x, from :attr:`FlightComputer.attitude`)
  and a unit direction ``towards`` (ECI), rad, compared by its cosine: below ``a``
  is ``nose . towards > cos(a)`` (:func:`nose_dot`).

The compiled form is a postfix program of rows ``(op, reading, value, a, b, c)``:
``BELOW``/``ABOVE`` push ``reading < value`` / ``reading > value`` (``a`` and ``b``:
the first state slot and the number of the stage's tanks, for ``propellant``;
``(a, b, c)`` the direction, for ``nose_angle``, whose reading is ``-nose . towards``
against ``-cos(value)``), ``AND``/``OR`` combine the two topmost. A condition on a
stage's propellant belongs to the vehicle it was made for (``vehicle``): wait on it
before the stack changes.
"""

from __future__ import annotations

import math

import numpy as np

from rocketsim.flight.navigation import estimate
from rocketsim.flight.sensors import E_GAUGES, gauged
from rocketsim.jit import njit
from rocketsim.frames.local import where_and_how_fast
from rocketsim.frames.quaternion import body_x_components
from rocketsim.layout import P_POLAR_RADIUS, P_RADIUS, P_SPIN, Q, R, V

READINGS = ("altitude", "vertical_speed", "propellant", "time", "nose_angle")
BELOW, ABOVE, AND, OR = 1.0, 2.0, 3.0, 4.0
N_CODE = 6                          # columns of a row: op, reading, value and three for the reading
NO_CONDITION = np.zeros((0, N_CODE))    # what the compiled run reads for a program not waiting on one


class Condition:
    """A condition on the readings (see the module): call it for its truth now;
    ``code`` is its compiled form."""

    __slots__ = ("_fc", "code", "_test", "vehicle")

    def __init__(self, fc, code: np.ndarray, test, vehicle=None):
        self._fc = fc
        self.code = code
        self._test = test
        self.vehicle = vehicle      # the vehicle model whose state slots the code reads (None: none)

    def __call__(self) -> bool:
        return self._test()

    def __and__(self, other: "Condition") -> "Condition":
        first, second = self._test, _condition(other, "&")._test
        return self._joined(other, AND, lambda: first() and second())

    def __or__(self, other: "Condition") -> "Condition":
        first, second = self._test, _condition(other, "|")._test
        return self._joined(other, OR, lambda: first() or second())

    def _joined(self, other: "Condition", op: float, test) -> "Condition":
        if self.vehicle is not None and other.vehicle is not None and self.vehicle is not other.vehicle:
            raise ValueError("conditions on the propellant of two different stacks cannot be combined")
        row = np.zeros((1, N_CODE))
        row[0, 0] = op
        return Condition(self._fc, np.vstack((self.code, other.code, row)), test,
                         self.vehicle if self.vehicle is not None else other.vehicle)

    def __repr__(self) -> str:
        return f"<condition of {len(self.code)} terms>"


def _condition(other, operator: str) -> Condition:
    if not isinstance(other, Condition):
        raise TypeError(f"a condition combines with {operator} only with another fc.below() or fc.above(); "
                        f"got {type(other).__name__}")
    return other


def compare(fc, reading: str, value: float, op: float) -> Condition:
    """The condition ``reading < value`` (``op`` BELOW) or ``reading > value`` (ABOVE) on
    ``altitude``, ``vertical_speed`` or ``time``."""
    read = lambda: getattr(fc, reading)       # noqa: E731
    return _compared(fc, read, (op, float(READINGS.index(reading)), value, 0.0, 0.0, 0.0), None)


def compare_nose(fc, towards, angle: float, op: float) -> Condition:
    """The condition on the angle (rad, 0..pi) between the nose and the unit vector
    ``towards`` (ECI): ``BELOW`` is ``nose . towards > cos(angle)``, read as the negated
    dot product against ``-cos(angle)`` (see the module)."""
    a, b, c = (float(x) for x in towards)
    read = lambda: -nose_dot(fc.attitude, a, b, c)       # noqa: E731
    return _compared(fc, read, (op, float(READINGS.index("nose_angle")), -math.cos(angle), a, b, c), None)


@njit
def nose_dot(q, a, b, c):
    """``nose . (a, b, c)``: the nose (body x in ECI) of the attitude quaternion ``q``
    (w, x, y, z, body -> ECI) dotted with a direction; :func:`holds` and the condition's
    Python test both call it, so the two agree to the bit."""
    nx, ny, nz = body_x_components(q[0], q[1], q[2], q[3])
    return nx * a + ny * b + nz * c


def compare_propellant(fc, vehicle, stage: int, value: float, op: float) -> Condition:
    """The condition on the liquid propellant (kg) of stage ``stage`` (an index) of the
    vehicle model ``vehicle``, read as the sum of its tanks' entries of ``fc.propellant``."""
    names = [name for name, s in zip(vehicle.tank_names, vehicle.tank_stage) if s == stage]
    first = vehicle.tanks.start + vehicle.tank_names.index(names[0]) if names else 0
    read = lambda: sum(fc.propellant[name] for name in names)        # noqa: E731
    return _compared(fc, read, (op, float(READINGS.index("propellant")), value, float(first), float(len(names)),
                                0.0), vehicle)


def _compared(fc, read, row: tuple, vehicle) -> Condition:
    value = row[2]
    test = (lambda: read() < value) if row[0] == BELOW else (lambda: read() > value)
    return Condition(fc, np.array((row,)), test, vehicle)


@njit
def holds(code, t, y, p, errors=None, j=0, gauges=0):
    """:func:`holds_on`, of the truth itself without ``errors``."""
    if errors is None:
        return holds_on(code, t, y, p, np.zeros((0, 0, 3)), 0, 0)
    return holds_on(code, t, y, p, errors, j, gauges)


@njit
def holds_on(code, t, y, p, errors, j, gauges):
    """The truth of the compiled condition ``code`` (rows ``(op, reading, value, a, b,
    c)``, see the module) on the state ``y`` at mission time ``t`` (s) of a body with
    parameters ``p``: the readings as :class:`~rocketsim.flight.readings.StateView`
    computes them (:func:`~rocketsim.frames.local.where_and_how_fast`; the vertical
    speed the dot product of the surface velocity with the local up), a stage's
    propellant as the sum of its tanks' slots, the time ``t``, the nose's dot product
    (:func:`nose_dot`). With the sensors' ``errors`` (:meth:`rocketsim.flight.sensors.Sensors.run_errors`,
    none: the truth) the readings are those of the navigation estimate of their row
    ``j`` (:func:`rocketsim.flight.navigation.estimate`) and each tank's propellant its
    gauge's (:func:`~rocketsim.flight.sensors.gauged`; the column of the tank at state
    slot ``s`` is ``E_GAUGES + s - gauges``), as the flight computer reads them."""
    measuring = errors.shape[0] > 0
    if measuring:
        r, v, q, _ = estimate(y, errors, j)
    else:
        r, v, q = y[R:R + 3], y[V:V + 3], y[Q:Q + 4]
    _, _, height, enu, surface = where_and_how_fast(r, v, t, p[P_SPIN], p[P_RADIUS], p[P_POLAR_RADIUS])
    climb = math.nan
    stack = np.zeros(code.shape[0], dtype=np.bool_)
    top = 0
    for row in range(code.shape[0]):
        op = code[row, 0]
        if op == AND or op == OR:
            top -= 1
            stack[top - 1] = (stack[top - 1] and stack[top]) if op == AND else (stack[top - 1] or stack[top])
            continue
        if code[row, 1] == 0.0:
            reading = height
        elif code[row, 1] == 2.0:
            reading = 0.0           # the order of Python's sum over the tanks
            for k in range(int(code[row, 3]), int(code[row, 3]) + int(code[row, 4])):
                reading += gauged(y[k], errors, j, E_GAUGES + k - gauges) if measuring else y[k]
        elif code[row, 1] == 3.0:
            reading = t
        elif code[row, 1] == 4.0:
            reading = -nose_dot(q, code[row, 3], code[row, 4], code[row, 5])
        else:
            if math.isnan(climb):
                climb = surface @ enu[2]
            reading = climb
        stack[top] = reading < code[row, 2] if op == BELOW else reading > code[row, 2]
        top += 1
    return stack[0]
