"""The body's own drag, learnt in flight: a drag-area table scaled by what the accelerometers feel.

A falling stage's drag area ``C_D A`` (m^2) against Mach comes from its
aerodynamic data (a table a program carries); the real stage differs from the
table by a factor the guidance can measure. With the engines off, the
non-gravitational acceleration the accelerometers read (``fc.acceleration``,
in g) is the air's force over the mass, and the dynamic pressure ``q`` is read
by the air data, so the drag area flown is::

    C_D A = m a / q

(a lean's lift adds ``sqrt(1 + (L/D)^2) - 1`` to it: 2 % at a lift-to-drag ratio of
0.2, left in). :class:`DragArea` keeps the ratio of that to the table's value at
the Mach number read, smoothed by a first-order filter of time constant
``time_constant`` in the logarithm of the ratio (so a factor and its inverse weigh
alike), and only where ``q`` is at least ``min_q`` (in thinner air the reading is
mostly the sensors' noise). The scale starts at 1. Units SI.
"""

from __future__ import annotations

import math

import numpy as np

MIN_Q = 2000.0          # Pa: no estimate below this dynamic pressure
TIME_CONSTANT = 3.0     # s


class DragArea:
    """The scale of a drag-area table (``area`` m^2 against increasing ``mach``) that the
    readings say the body flies with (see the module)."""

    def __init__(self, mach, area, time_constant: float = TIME_CONSTANT, min_q: float = MIN_Q):
        self.mach = np.asarray(mach, dtype=float)
        self.area = np.asarray(area, dtype=float)
        self.time_constant = time_constant
        self.min_q = min_q
        self.scale = 1.0
        self._log = 0.0
        self._last = None           # mission time (s) of the last estimate

    def table(self, mach: float) -> float:
        """The table's drag area (m^2, unscaled) at Mach ``mach``."""
        return float(np.interp(mach, self.mach, self.area))

    def update(self, time: float, mass: float, acceleration: float, dynamic_pressure: float,
               mach: float) -> float:
        """Take the readings at mission ``time`` (s): ``mass`` (kg), the non-gravitational
        ``acceleration`` (m/s^2, engines off), ``dynamic_pressure`` (Pa) and ``mach``; returns
        the scale. Readings with less than ``min_q`` leave it as it was."""
        if dynamic_pressure < self.min_q or acceleration <= 0.0:
            return self.scale
        measured = math.log(mass * acceleration / dynamic_pressure / self.table(mach))
        if self._last is None:
            self._log = measured
        else:
            share = 1.0 - math.exp(-max(time - self._last, 0.0) / self.time_constant)
            self._log += share * (measured - self._log)
        self._last = time
        self.scale = math.exp(self._log)
        return self.scale
