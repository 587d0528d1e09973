"""A wall-clock bound on a stretch of Python code: :class:`Leash`.

A thread that stays inside a leash for more than its ``seconds`` of wall time
gets the leash's exception raised in it by one watchdog thread per process:

* in the main thread, through a signal (``SIGUSR2``, its handler installed
  when a leash is first entered there): the exception is raised at the next
  bytecode of a Python loop, and a blocking call that signals interrupt
  (``time.sleep``, a lock's ``acquire``, reading a pipe or a socket) returns
  early with it;
* in any other thread, through ``PyThreadState_SetAsyncExc``: raised at the
  next bytecode the thread runs, so a Python loop stops but a call blocked in
  C (a sleep, a lock) returns first. A caller that must not wait for that
  bounds the thread from outside (:func:`rocketsim.campaigns.run_task.bounded`).

The watchdog looks at the leashes entered every quarter of the shortest one's
bound (and sleeps while none is), so a leash of ``seconds`` fires between
``seconds`` and 1.25 ``seconds`` after it was entered. ``paused()``, if given, holds the clock while it is true (a
program's CPU-time exemption for numba compiling: the bound starts again when
it ends). Nothing is raised, and nothing the leashed code computes changes,
unless the bound is passed: a leash left in time leaves no trace (a signal or
an asynchronous exception sent as it was being left is withdrawn or ignored).
"""

from __future__ import annotations

import ctypes
import math
import signal
import threading
import time
from typing import Callable

SIGNAL = signal.SIGUSR2
_MAIN = threading.main_thread().ident


class Stop(BaseException):
    """A stop from outside the leashed code (a campaign run's wall-time bound): a
    BaseException, so no ``except Exception`` swallows it, and never counted as the
    code's own error."""


class Leash:
    """Context manager: raise ``exception`` (a class) in the thread inside it after
    ``seconds`` of wall time (0 or None: no bound)."""

    __slots__ = ("seconds", "exception", "paused", "thread", "deadline", "fired", "inside")

    def __init__(self, seconds: float | None, exception: type[BaseException],
                 paused: Callable[[], bool] | None = None):
        self.seconds = seconds
        self.exception = exception
        self.paused = paused
        self.thread = None
        self.deadline = 0.0
        self.fired = False
        self.inside = False

    def __enter__(self):
        if self.seconds:
            _WATCHDOG.arm(self)
        return self

    def __exit__(self, *exc) -> bool:
        if self.inside:
            _WATCHDOG.disarm(self)
        return False


def _on_signal(signum, frame):
    """The main thread's handler: raise the exception of the main thread's leash that
    fired, if it is still entered (a late signal is ignored)."""
    leash = _WATCHDOG.fired_in_main
    if leash is not None and leash.inside and leash.fired:
        _WATCHDOG.fired_in_main = None
        raise leash.exception


def _async_raise(thread: int, exception: type[BaseException] | None) -> None:
    """Raise ``exception`` in ``thread`` at its next bytecode (None: withdraw one pending)."""
    ctypes.pythonapi.PyThreadState_SetAsyncExc(ctypes.c_ulong(thread),
                                               ctypes.py_object(exception) if exception else None)


class _Watchdog:
    """The process's one watchdog thread and the leashes entered now. It looks every
    quarter of the shortest bound entered since its last look, and waits without a
    timeout after a look with none entered (woken by the next)."""

    def __init__(self):
        self.lock = threading.Lock()
        self.armed: set[Leash] = set()
        self.period: float | None = None        # s between looks; None: idle
        self.shortest: float | None = None      # the shortest bound entered since the last look
        self.wake = threading.Event()
        self.fired_in_main: Leash | None = None
        self.thread: threading.Thread | None = None
        self.installed = False

    def arm(self, leash: Leash) -> None:
        thread = threading.get_ident()
        if thread == _MAIN and not self.installed:
            signal.signal(SIGNAL, _on_signal)
            self.installed = True
        with self.lock:
            leash.thread, leash.deadline, leash.fired, leash.inside = (
                thread, time.monotonic() + leash.seconds, False, True)
            self.armed.add(leash)
            if self.shortest is None or leash.seconds < self.shortest:
                self.shortest = leash.seconds
            if self.period is None or leash.seconds / 4 < self.period:
                self.period = max(leash.seconds / 4, 0.01)
                self.wake.set()
            if self.thread is None:
                self.thread = threading.Thread(target=self._watch, name="rocketsim-leash", daemon=True)
                self.thread.start()

    def disarm(self, leash: Leash) -> None:
        with self.lock:
            leash.inside = False
            self.armed.discard(leash)
            if leash.fired and leash.thread != _MAIN:
                _async_raise(leash.thread, None)        # left in time after all: withdrawn

    def _watch(self) -> None:
        while True:
            self.wake.wait(self.period)
            self.wake.clear()
            now = time.monotonic()
            with self.lock:
                for leash in list(self.armed):
                    if leash.fired or now < leash.deadline:
                        continue
                    if leash.paused is not None and leash.paused():
                        leash.deadline = now + leash.seconds
                        continue
                    leash.fired = True
                    if leash.thread == _MAIN and signal.getsignal(SIGNAL) is _on_signal:
                        self.fired_in_main = leash
                        signal.pthread_kill(leash.thread, SIGNAL)
                    else:
                        _async_raise(leash.thread, leash.exception)
                # idle only after a whole look without a leash entered (a program entering
                # one at every step must not wake this thread at every step)
                bounds = [leash.seconds for leash in self.armed] + [self.shortest or math.inf]
                self.period = max(min(bounds) / 4, 0.01) if min(bounds) < math.inf else None
                self.shortest = None


_WATCHDOG = _Watchdog()
