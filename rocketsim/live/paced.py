"""A flight's telemetry handed on unchanged, the flight waiting for its live view.

:class:`PacedTelemetry` stands where the world expects its telemetry (the
interface of :class:`rocketsim.telemetry.writer.TelemetryWriter`) and hands each
call on, in order and unchanged, to every sink behind it: the MCAP writer whose
file the live view plays (:class:`rocketsim.live.server.LiveServer`), and, for
a flight kept in memory, a :class:`rocketsim.api.recorder.Recorder`. Before a
sample, an event or a log line it waits while the live view is backlogged (its
clock behind the file at the warp, or paused): the flight waits between its
steps' batches and never changes one, so the file's bytes are those of the same
flight flown headless, at every warp, with or without a viewer.
"""

from __future__ import annotations

# longest single wait (s) before looking again (Ctrl-C reaches the flight meanwhile)
WAIT = 0.1


class PacedTelemetry:
    """``sinks`` (telemetry with the writer's interface) behind one, the flight pacing
    on ``live`` (a :class:`~rocketsim.live.server.LiveServer`)."""

    def __init__(self, sinks: list, live):
        self._sinks = sinks
        self._live = live

    def _pace(self) -> None:
        while self._live.backlogged:
            self._live.wait_for_room(WAIT)

    def add_body(self, name: str) -> None:
        for sink in self._sinks:
            sink.add_body(name)

    def sample(self, body: str, values, fields, leaving: bool = False) -> None:
        self._pace()
        for sink in self._sinks:
            sink.sample(body, values, fields, leaving)

    def sample_rows(self, body: str, rows, fields) -> None:
        self._pace()
        for sink in self._sinks:
            sink.sample_rows(body, rows, fields)

    def sample_interleaved(self, blocks: list[tuple]) -> None:
        self._pace()
        for sink in self._sinks:
            sink.sample_interleaved(blocks)

    def event(self, t: float, body: str, name: str, figures: dict) -> None:
        self._pace()
        for sink in self._sinks:
            sink.event(t, body, name, figures)

    def log(self, t: float, body: str, message: str) -> None:
        self._pace()
        for sink in self._sinks:
            sink.log(t, body, message)

    def error(self, t: float, message: str) -> None:
        for sink in self._sinks:
            sink.error(t, message)

    def attach(self, name: str, data: bytes, media_type: str = "text/plain") -> None:
        for sink in self._sinks:
            sink.attach(name, data, media_type)

    def metadata(self, name: str, values: dict[str, str]) -> None:
        for sink in self._sinks:
            sink.metadata(name, values)

    def close(self) -> None:
        """Close every sink (the first error raised after all are closed)."""
        error = None
        for sink in self._sinks:
            try:
                sink.close()
            except BaseException as caught:
                error = error or caught
        if error is not None:
            raise error

    def __enter__(self) -> "PacedTelemetry":
        return self

    def __exit__(self, exc_type, exc, traceback) -> None:
        error = None
        for sink in self._sinks:
            try:
                sink.__exit__(exc_type, exc, traceback)
            except BaseException as caught:
                error = error or caught
        if error is not None:
            raise error
