"""One flight's telemetry handed to several sinks: a file and the same run in memory.

:class:`Tee` stands where the world expects its telemetry (a
:class:`rocketsim.telemetry.sink.TelemetrySink`) and hands each call on, in
order and unchanged, to every sink behind it: a flight kept in memory and shown
live (:func:`rocketsim.api.live.fly_live`) is written to the MCAP file the live
view plays and recorded by a :class:`rocketsim.api.recorder.Recorder` as well.
The calls are those the world and :func:`rocketsim.api.telemetry_flight.fly_into` make:
``add_body``, ``sample``, ``sample_rows``, ``sample_interleaved``, ``event``,
``log``, ``error``, ``attach``, ``metadata``, ``close``, and the context manager's.
"""

from __future__ import annotations

from rocketsim.telemetry.sink import TelemetrySink


class Tee(TelemetrySink):
    """``sinks`` (each a :class:`~rocketsim.telemetry.sink.TelemetrySink`) behind one."""

    def __init__(self, sinks: list):
        self._sinks = sinks

    def add_body(self, name: str) -> None:
        for sink in self._sinks:
            sink.add_body(name)

    def sample(self, body: str, values, fields, leaving: bool = False) -> None:
        for sink in self._sinks:
            sink.sample(body, values, fields, leaving)

    def sample_rows(self, body: str, rows, fields) -> None:
        for sink in self._sinks:
            sink.sample_rows(body, rows, fields)

    def sample_interleaved(self, blocks: list[tuple]) -> None:
        for sink in self._sinks:
            sink.sample_interleaved(blocks)

    def event(self, t: float, body: str, name: str, figures: dict) -> None:
        for sink in self._sinks:
            sink.event(t, body, name, figures)

    def log(self, t: float, body: str, message: str) -> None:
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
        """Close every sink."""
        self._every(lambda sink: sink.close())

    def __enter__(self) -> "Tee":
        return self

    def __exit__(self, exc_type, exc, traceback) -> None:
        self._every(lambda sink: sink.__exit__(exc_type, exc, traceback))

    def _every(self, call) -> None:
        """``call(sink)`` for every sink, whatever one raises (the first error is raised
        after all: every file is finished)."""
        error = None
        for sink in self._sinks:
            try:
                call(sink)
            except BaseException as caught:
                error = error or caught
        if error is not None:
            raise error
