"""The CPU time a live view spends beside its flight, against the flight's own.

At ``max`` warp a live view serves only what its share of CPU allows
(:class:`rocketsim.live.server.LiveServer`), and that share is counted in CPU
time, not wall time: on a machine shared with other jobs a flight takes
longer by the wall clock but not by its CPU, and a share of the wall clock
would then let the view spend more of the flight's CPU the busier the machine.

The view's CPU is its player thread's and that of the threads the Foxglove SDK
runs in its Rust core (sending the messages to the viewers): every CPU second
of the process that is not a Python thread's, counted since :class:`CpuShare`
was made. The flight's is the rest of the process's (its own thread, its
telemetry writer). A thread's CPU is read from Linux's ``/proc/self/task/<id>/schedstat``
(ns on CPU, the clock ``time.thread_time`` reads); where that cannot be read,
only the player's own thread is counted as the view's.
"""

from __future__ import annotations

import os
import threading
import time


class CpuShare:
    """The live view's CPU against its flight's, from now on; made on the player's
    thread and asked on it; :meth:`close` at the end (the threads' files kept open
    meanwhile, as reading one again is some 50 times quicker than opening it)."""

    def __init__(self):
        self._player = threading.get_ident()
        self._files: dict[int, int] = {}        # native thread id -> its schedstat, open
        self._start = self._python_cpu()
        self._process = time.process_time()
        self._own = time.thread_time()

    def _thread_cpu(self, native_id: int) -> float | None:
        """CPU seconds of the thread ``native_id`` of this process (None: not readable,
        or the thread has ended)."""
        try:
            if native_id not in self._files:
                self._files[native_id] = os.open(f"/proc/self/task/{native_id}/schedstat", os.O_RDONLY)
            return int(os.pread(self._files[native_id], 64, 0).split()[0]) / 1e9
        except (OSError, ValueError, IndexError):
            if native_id in self._files:
                os.close(self._files.pop(native_id))
            return None

    def _python_cpu(self) -> dict[int, float] | None:
        """CPU seconds of each of this process's Python threads but the player, by native
        id (None: unreadable)."""
        spent = {}
        for thread in threading.enumerate():
            if thread.ident == self._player or thread.native_id is None:
                continue
            cpu = self._thread_cpu(thread.native_id)
            if cpu is None:
                if thread.is_alive():
                    return None
                continue
            spent[thread.native_id] = cpu
        return spent

    def spent(self) -> tuple[float, float]:
        """``(view, flight)``: CPU seconds of the live view and of the rest of the process
        since this was made. A Python thread that ended meanwhile counts as the view's
        (more than it spent, never less)."""
        process = time.process_time() - self._process
        own = time.thread_time() - self._own
        others = self._python_cpu() if self._start is not None else None
        if others is None:
            return own, max(process - own, 0.0)
        for ended in self._files.keys() - others.keys():
            os.close(self._files.pop(ended))
        flight = sum(cpu - self._start.get(native_id, 0.0) for native_id, cpu in others.items())
        flight = max(min(flight, process - own), 0.0)
        return process - flight, flight

    def close(self) -> None:
        """Close the threads' files."""
        for fd in self._files.values():
            os.close(fd)
        self._files.clear()
