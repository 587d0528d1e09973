"""Conditions of ``fc.wait_until`` the simulator can test in compiled code.

``fc.below("altitude", 10_000)`` is a :class:`Condition`: called, it reads the
flight computer as the program would (``fc.altitude < 10_000``), so it serves
wherever a function of no arguments does; conditions combine with ``&`` (and)
and ``|`` (or), evaluated left to right like Python's ``and`` and ``or``.
Because the simulator knows what such a condition reads, it tests it in the
same compiled call that advances the vehicle (:func:`holds`, once per step on
the state at the step's end, the state the program's readings would see), so
a vehicle waiting on one is flown many steps per call instead of one (see
:mod:`rocketsim.sim.runs`); the test gives the same boolean at the same step as
the reading's, from the same operations on the same numbers.

Readings (:data:`READINGS`), both of the true state about Earth (a program
with sensor errors, or one flying about another body, has its condition read
in Python every step, as a lambda's):

* ``altitude``: height above the WGS84 ellipsoid, m (:attr:`FlightComputer.altitude`);
* ``vertical_speed``: rate of climb relative to the ground, m/s
  (:attr:`FlightComputer.vertical_speed`).

The compiled form is a postfix program of rows ``(op, reading, value)``:
``BELOW``/``ABOVE`` push ``reading < value`` / ``reading > value``, ``AND``/``OR``
combine the two topmost.
"""

from __future__ import annotations

import math

import numpy as np

from rocketsim._jit import njit
from rocketsim.frames.local import where_and_how_fast
from rocketsim.layout import P_POLAR_RADIUS, P_RADIUS, P_SPIN, R, V

READINGS = ("altitude", "vertical_speed")
BELOW, ABOVE, AND, OR = 1.0, 2.0, 3.0, 4.0
NO_CONDITION = np.zeros((0, 3))     # what the compiled run reads for a program not waiting on one


class Condition:
    """A condition on the readings (see the module): call it for its truth now;
    ``code`` is its compiled form."""

    __slots__ = ("_fc", "code", "_test")

    def __init__(self, fc, code: np.ndarray, test):
        self._fc = fc
        self.code = code
        self._test = test

    def __call__(self) -> bool:
        return self._test()

    def __and__(self, other: "Condition") -> "Condition":
        first, second = self._test, _condition(other, "&")._test
        return Condition(self._fc, np.vstack((self.code, other.code, ((AND, 0.0, 0.0),))),
                         lambda: first() and second())

    def __or__(self, other: "Condition") -> "Condition":
        first, second = self._test, _condition(other, "|")._test
        return Condition(self._fc, np.vstack((self.code, other.code, ((OR, 0.0, 0.0),))),
                         lambda: first() or second())

    def __repr__(self) -> str:
        return f"<condition of {len(self.code)} terms>"


def _condition(other, operator: str) -> Condition:
    if not isinstance(other, Condition):
        raise TypeError(f"a condition combines with {operator} only with another fc.below() or fc.above(); "
                        f"got {type(other).__name__}")
    return other


def compare(fc, reading: str, value: float, op: float) -> Condition:
    """The condition ``reading < value`` (``op`` BELOW) or ``reading > value`` (ABOVE)."""
    index = READINGS.index(reading)
    if op == BELOW:
        test = lambda: getattr(fc, reading) < value      # noqa: E731
    else:
        test = lambda: getattr(fc, reading) > value      # noqa: E731
    return Condition(fc, np.array(((op, float(index), value),)), test)


@njit
def holds(code, t, y, p):
    """The truth of the compiled condition ``code`` (rows ``(op, reading, value)``, see
    the module) on the state ``y`` at mission time ``t`` (s) of a body with parameters
    ``p``: the readings as :class:`~rocketsim.flight.readings.StateView` computes them
    (:func:`~rocketsim.frames.local.where_and_how_fast`; the vertical speed the dot
    product of the surface velocity with the local up)."""
    _, _, height, enu, surface = where_and_how_fast(y[R:R + 3], y[V:V + 3], t, p[P_SPIN], p[P_RADIUS],
                                                    p[P_POLAR_RADIUS])
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
        else:
            if math.isnan(climb):
                climb = surface @ enu[2]
            reading = climb
        stack[top] = reading < code[row, 2] if op == BELOW else reading > code[row, 2]
        top += 1
    return stack[0]
