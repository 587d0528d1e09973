"""What numba's compiling looks like from the command line.

On a new machine (or after an upgrade) the first flight compiles its kernels,
tens of seconds; afterwards they load from the cache
(:func:`rocketsim.jit.cache_dir`). numba announces each compile it starts
and ends (its event API, ``numba.core.event``, kind ``numba:compile``: fired
only when a kernel is compiled, not when it is loaded from the cache).
:class:`Compiles` counts them; :func:`compile_message` shows them on a
terminal. numba's own helper functions (its overloads of numpy and builtins,
compiled inside the kernels that use them) are not counted.

Imported by the commands that fly, which import numba anyway.
"""

from __future__ import annotations

import sys
import time
from contextlib import contextmanager
from typing import Callable

import numba.core.event as ev

FIRST_RUN = "compiling flight kernels for this machine, first run only"


def _name(event) -> str:
    func = event.data["dispatcher"].py_func
    return f"{func.__module__}.{func.__qualname__}"


class Compiles(ev.Listener):
    """Counts the kernels numba compiles while registered; ``on_change(self)``, if given,
    is called when a compile starts and when one ends."""

    def __init__(self, on_change: Callable[["Compiles"], None] | None = None):
        self.done = 0
        self.current: list[str] = []        # the kernels being compiled, callers first
        self.started: float | None = None    # time.perf_counter() of the first compile
        self._on_change = on_change

    def on_start(self, event) -> None:
        name = _name(event)
        if name.startswith("numba."):
            return
        if self.started is None:
            self.started = time.perf_counter()
        self.current.append(name)
        if self._on_change is not None:
            self._on_change(self)

    def on_end(self, event) -> None:
        if _name(event).startswith("numba."):
            return
        self.current.pop()
        self.done += 1
        if self._on_change is not None:
            self._on_change(self)

    def seconds(self) -> float:
        """Wall time since the first compile began (s; 0 if none did)."""
        return 0.0 if self.started is None else time.perf_counter() - self.started

    @contextmanager
    def listening(self):
        ev.register("numba:compile", self)
        try:
            yield self
        finally:
            ev.unregister("numba:compile", self)


@contextmanager
def compile_message(stream=None):
    """On a terminal (``stream``, default stderr), one line kept up to date while
    kernels compile: how many are done and which is compiling; when the block
    ends, how many were compiled in how long. Nothing when the stream is not a
    terminal or nothing compiled."""
    stream = stream or sys.stderr
    if not stream.isatty():
        yield
        return

    def show(compiles: Compiles) -> None:
        now = compiles.current[-1].removeprefix("rocketsim.") if compiles.current else ""
        stream.write(f"\r{FIRST_RUN}: {compiles.done} compiled {now}\x1b[K")
        stream.flush()

    compiles = Compiles(show)
    with compiles.listening():
        try:
            yield
        finally:
            if compiles.done:
                kernels = "kernel" if compiles.done == 1 else "kernels"
                stream.write(f"\rcompiled {compiles.done} flight {kernels} for this machine in "
                             f"{compiles.seconds():.0f} s (kept for the next runs)\x1b[K\n")
                stream.flush()
