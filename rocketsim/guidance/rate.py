"""How often a flight program's guidance must wake as a reading nears the limit it acts at.

A real flight computer's guidance runs at a few hertz and its autopilot at
the control rate; only as a cut-off nears does the guidance look every
control step, so the cut-off falls in the step the limit is crossed. A
program does the same with ``fc.sleep(approach.next_update())``, the
simulator flying the steps between its wake-ups in compiled runs.

:class:`Approach` extrapolates a reading linearly at the rate it changed
between its last two updates: while the limit is more than two update
intervals away at that rate the program may sleep that interval (the longest
of ``periods`` that allows it), otherwise it wakes every step. A reading
that accelerates towards its limit is caught by the factor of two as long as
its rate changes by less than that within an interval.
"""

from __future__ import annotations

import math


class Approach:
    """A reading on its way to ``limit``: ``rising`` it climbs to it (else it falls);
    ``periods`` the update intervals (s) the guidance may sleep, longest first."""

    def __init__(self, limit: float, rising: bool = False, periods: tuple[float, ...] = (1.0, 0.1)):
        self.limit = limit
        self.sign = 1.0 if rising else -1.0
        self.periods = periods
        self.last = None            # (reading, mission time s) at the last update
        self.gap = self.rate = math.inf

    def ahead(self, value: float, time: float) -> bool:
        """Record the reading ``value`` at mission ``time`` (s); whether the limit is still
        ahead of it."""
        self.gap = self.sign * (self.limit - value)
        if self.last is not None and time > self.last[1]:
            self.rate = self.sign * (value - self.last[0]) / (time - self.last[1])
        self.last = (value, time)
        return self.gap > 0.0

    def next_update(self) -> float:
        """Seconds until the next update (0: the next step); 0 once the limit is reached."""
        for wait in self.periods:
            if self.gap > 2.0 * wait * self.rate:
                return wait
        return 0.0
