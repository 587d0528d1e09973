"""A CPU-time bound on a flight program's Python (:class:`CpuBudget`), numba's compiling kept out of it.

A program that keeps control for more than its CPU budget in one step is stopped
(:mod:`rocketsim.flight.program`): the budget is the process's virtual (user CPU)
interval timer, whose signal raises :class:`ProgramOverBudget` in the main thread.
Time numba spends compiling or loading a kernel, and what :func:`not_counted` wraps,
is not the program's (:data:`COMPILING`).
"""

from __future__ import annotations

import signal
import threading

import numba.core.event as ev


class ProgramOverBudget(BaseException):
    """Raised inside a program that used up its CPU budget for one step.

    A BaseException, so a program's ``except Exception`` cannot swallow it.
    """


class CpuBudget:
    """Context manager: raise :class:`ProgramOverBudget` in this thread after ``seconds``
    of CPU time spent inside it.

    Uses the process's virtual (user CPU) interval timer, so a program that
    never hands back control is stopped however busy the machine is. Only
    the main thread can take signals: elsewhere no budget is enforced. A
    runner keeps one and enters it at every resume (a class, not a generator:
    entering costs two timer calls and little else).

    Over a stretch of many short calls (a program's condition read after every step
    of a compiled run) the budget is armed once (:meth:`watch`) and each call marked
    by a number in :attr:`call` (0 between calls): the timer then ticks every
    quarter of ``seconds`` and the budget is spent when five ticks fall in one call
    (between ``seconds`` and 1.25 ``seconds`` of CPU time in it).
    """

    __slots__ = ("seconds", "_armed", "_installed", "call", "_ticking", "_seen", "_ticks")

    def __init__(self, seconds: float):
        self.seconds = seconds
        self._armed = False
        self._installed = False
        self.call = 0               # the call under way while watched (0: none)
        self._ticking = False       # watched: the timer ticks (see the class)
        self._seen = 0              # the call the last tick fell in
        self._ticks = 0             # the ticks that fell in it

    def __enter__(self):
        if self._arm():
            signal.setitimer(signal.ITIMER_VIRTUAL, self.seconds)
        return self

    def __exit__(self, *exc) -> bool:
        self._disarm()
        return False

    def watch(self) -> None:
        """Arm the budget over a stretch of calls, each marked in :attr:`call` (see the
        class), until :meth:`unwatch`."""
        if self._arm():
            self.call, self._seen, self._ticks, self._ticking = 0, 0, 0, True
            tick = self.seconds / TICKS
            signal.setitimer(signal.ITIMER_VIRTUAL, tick, tick)

    def unwatch(self) -> None:
        """End the stretch :meth:`watch` began."""
        self._disarm()
        self.call, self._ticking = 0, False

    def _arm(self) -> bool:
        self._armed = self.seconds > 0 and threading.current_thread() is threading.main_thread()
        if self._armed:
            if not self._installed:
                # once per budget: the handler only acts while the timer is armed (looking
                # it up with signal.getsignal at every step costs more than the step's timer)
                if signal.getsignal(signal.SIGVTALRM) is not _expire:
                    signal.signal(signal.SIGVTALRM, _expire)
                self._installed = True
            COMPILING.active = self
        return self._armed

    def _disarm(self) -> None:
        if self._armed:
            signal.setitimer(signal.ITIMER_VIRTUAL, 0.0)
            COMPILING.active = None
            self._armed = False

    def afresh(self) -> None:
        """The running program gets its whole budget again (numba's compiling has ended)."""
        if self._ticking:
            self._ticks = 0
        else:
            signal.setitimer(signal.ITIMER_VIRTUAL, self.seconds)

    def tick(self) -> bool:
        """The timer has fired: whether the budget is spent (see the class)."""
        if not self._ticking:
            return True
        call = self.call
        if not call:
            self._ticks = 0
        elif call != self._seen:
            self._seen, self._ticks = call, 1
        else:
            self._ticks += 1
        return self._ticks > TICKS


TICKS = 4       # a watched budget's ticks per budget (CpuBudget.watch)


def _expire(signum, frame):
    budget = COMPILING.active
    if budget is None:                # a late signal, the budget left
        return
    if COMPILING.depth > 0:          # numba is compiling: not the program's time
        budget.afresh()
        return
    if budget.tick():
        raise ProgramOverBudget


class _CompileTime(ev.Listener):
    """Keeps numba's compiling, and what :func:`not_counted` wraps, out of a program's
    CPU budget.

    On a cold cache a program's first call of a reading compiles (or loads)
    a kernel, which can take longer than a budget. numba holds its compiler
    lock while it compiles or loads; while it does, the budget's timer is
    re-armed instead of stopping the program, and when the lock is let go
    the step gets its whole budget again.
    """

    def __init__(self):
        self.depth = 0
        self.active: CpuBudget | None = None      # the budget armed now, if any

    def on_start(self, event) -> None:
        self.depth += 1

    def on_end(self, event) -> None:
        self.depth -= 1
        if self.depth == 0 and self.active is not None:
            self.active.afresh()

    def __enter__(self):
        self.on_start(None)
        return self

    def __exit__(self, *exc) -> bool:
        self.on_end(None)
        return False


COMPILING = _CompileTime()
ev.register("numba:compiler_lock", COMPILING)


def not_counted() -> _CompileTime:
    """Context manager: the CPU time spent inside it is not the running program's (the
    simulator's first import of a library a call of ``fc`` needs, e.g. scipy's
    integrator for ``fc.predict``, a few tenths of a second); the step gets its whole
    budget again after it."""
    return COMPILING
