"""Ctrl-C and SIGTERM held across a file operation, so that a file is never half-updated.

A Python signal handler runs in the main thread between two bytecodes, so a
Ctrl-C raising ``KeyboardInterrupt`` can land between a record written and its
index entry noted, and the summary written at the end would then disagree with
what is on disk. :data:`held` is a context manager (and, through :func:`holding`,
a decorator): inside it, SIGINT and SIGTERM whose handlers are Python functions
are only noted; when the outermost ``with`` ends, the handlers are put back and
each signal noted is handed to its handler, which raises there. Signals left to
the system (default or ignored) are left alone: they stop the process or do
nothing, as before. In another thread than the main one nothing is held, as no
handler can run there.

The handlers are swapped through ``_signal``, the C module behind
:mod:`signal`: ``signal.signal`` and ``signal.getsignal`` turn every handler
returned into an enum member, a cost several times the swap's own, and the
operations held are a sample's or a message's writing.
"""

from __future__ import annotations

import _signal
import functools
import signal
import threading

SIGNALS = (signal.SIGINT, signal.SIGTERM)


class _Held:
    """The context manager of the module (one per process: the handlers are)."""

    def __init__(self):
        self._depth = 0
        self._previous: list[tuple[int, object]] = []
        self._noted: list[tuple[int, object]] = []
        self._main = threading.main_thread()

    def _note(self, signum, frame) -> None:
        self._noted.append((signum, frame))

    def __enter__(self) -> None:
        if threading.current_thread() is not self._main:
            return
        if self._depth == 0:
            previous = [(s, h) for s in SIGNALS if callable(h := _signal.getsignal(s))]
            swapped = []
            try:
                for s, handler in previous:
                    _signal.signal(s, self._note)
                    swapped.append((s, handler))
            except BaseException:       # a signal not yet held raised: nothing was begun
                for s, handler in swapped:
                    _signal.signal(s, handler)
                self._noted = []
                raise
            self._previous = previous
        self._depth += 1

    def __exit__(self, *exc) -> None:
        if threading.current_thread() is not self._main:
            return
        self._depth -= 1
        if self._depth:
            return
        previous, self._previous = self._previous, []
        for s, handler in previous:
            _signal.signal(s, handler)
        noted, self._noted = self._noted, []
        handlers = dict(previous)
        for signum, frame in noted:
            handlers[signum](signum, frame)


held = _Held()


def holding(method):
    """``method`` run inside :data:`held`."""
    @functools.wraps(method)
    def wrapper(*args, **kwargs):
        with held:
            return method(*args, **kwargs)
    return wrapper
