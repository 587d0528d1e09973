"""One thread that runs calls in the order they were handed to it, beside the caller's.

A telemetry file is written on such a thread (:class:`rocketsim.telemetry.writer.TelemetryWriter`):
the flight hands it batches of samples and messages and flies on, while the
thread frames them (a compiled call that releases the GIL), compresses them
(zstd), takes their CRC-32 and writes them, the last three releasing the GIL
too; the flight's compiled runs release it as well, so the thread's Python
runs beside them. Calls run one at a time in the order submitted, so the
file's bytes are those the same calls made in line would write. The queue is
bounded (:data:`DEPTH` calls): a flight that outruns its file waits for it
rather than holding its whole telemetry in memory.

A call that raises stops the thread's work: the calls after it are dropped,
and the error is raised to the caller at its next :meth:`WritingThread.submit`
(and returned by :meth:`WritingThread.stop`), as it would have been raised in
line, one call later.
"""

from __future__ import annotations

import queue
import threading

# calls waiting at most: a call is a batch of samples (some 10-60 kB) or one message,
# attachment or metadata record, so some megabytes of a flight's telemetry at the most
DEPTH = 64


class WritingThread:
    """Run calls on one thread of their own (named ``name``), in order."""

    def __init__(self, name: str, depth: int = DEPTH):
        self._calls: queue.Queue = queue.Queue(depth)
        self._error: BaseException | None = None
        self._thread = threading.Thread(target=self._serve, name=name, daemon=True)
        self._thread.start()

    def submit(self, call, *args) -> None:
        """Run ``call(*args)`` after every call submitted before it (waiting while
        :data:`DEPTH` calls wait); first raise the error of an earlier call, if one raised."""
        if self._error is not None:
            raise self._error
        self._calls.put((call, args))

    def stop(self) -> BaseException | None:
        """Wait for every call submitted to have run and end the thread (again: nothing);
        the error of a call, if one raised (returned, for the caller to raise once it
        has closed what the calls wrote to)."""
        if self._thread.is_alive():
            self._calls.put(None)
            self._thread.join()
        return self._error

    def _serve(self) -> None:
        while (item := self._calls.get()) is not None:
            if self._error is None:
                call, args = item
                try:
                    call(*args)
                except BaseException as error:      # raised to the caller (see the module)
                    self._error = error
