"""Stream telemetry to an MCAP file as the flight goes.

The file is chunked (zstd) so memory stays bounded however long the flight
(:class:`~rocketsim.telemetry.mcap_stream.McapStream`, about 1 us per message);
messages are JSON with registered JSON schemas. Timestamps are the mission
epoch (UTC, ns since 1970) plus mission time, so Foxglove shows real dates and
the same run always writes the same bytes: nothing here reads the wall clock.

The scenario and every file it references travel in the file as attachments,
so a run can be shared as one file. :meth:`TelemetryWriter.close` writes the
summary and index; callers use the writer as a context manager so the file is
finished on success, on a program error and on Ctrl-C alike.
"""

from __future__ import annotations

import math
from pathlib import Path

import orjson

from rocketsim import __version__
from rocketsim.frames.earth_fixed import earth_rotation_angle
from rocketsim.telemetry import foxglove
from rocketsim.telemetry.mcap_stream import McapStream
from rocketsim.telemetry.schemas import BODY_STATE, EVENT, schema_bytes

PROFILE = ""
# Uncompressed bytes per chunk: about 18 s of one body at 10 Hz. Memory held
# while flying is one chunk; a file cut short loses at most the last one.
CHUNK_SIZE = 256 * 1024
LIBRARY = f"rocketsim {__version__}"


def encode(message: dict) -> bytes:
    """JSON bytes of a message: compact, keys in insertion order, floats in
    their shortest round-trip form (orjson: ~2 us for a state message where
    the standard library takes ~15 us). NaN and infinities become null, as
    JSON has no spelling for them; numpy scalars and arrays are written as numbers."""
    return orjson.dumps(message, default=_plain, option=orjson.OPT_SERIALIZE_NUMPY)


def _plain(value):
    if hasattr(value, "item"):          # numpy scalars orjson does not take natively
        return value.item()
    raise TypeError(f"cannot write {type(value).__name__} to telemetry")


class TelemetryWriter:
    """One MCAP telemetry file: per body its state, Foxglove transform and
    location; the events; the program's log; the Earth's turn.

    ``program_file`` names the program in the ``file`` field of its log lines.
    """

    def __init__(self, path: str | Path, epoch_ns: int, program_file: str = ""):
        self.path = Path(path)
        self._file = open(self.path, "wb")
        self._writer = McapStream(self._file, PROFILE, LIBRARY, CHUNK_SIZE)
        self._epoch_ns = epoch_ns
        self._schemas = {}
        self._channels: dict[str, int] = {}
        self._bodies: dict[str, tuple[int, int, int]] = {}     # state, transform, location
        self._sequence = 0
        self._closed = False
        self._program_file = program_file
        self._events = self._channel("/events", EVENT)
        self._event_lines = self._channel("/events/log", foxglove.LOG)
        self._logs = self._channel("/log", foxglove.LOG)
        self._earth = self._channel("/earth/transform", foxglove.FRAME_TRANSFORM)
        self._earth_at = None

    def _channel(self, topic: str, schema: dict) -> int:
        title = schema["title"]
        if title not in self._schemas:
            self._schemas[title] = self._writer.schema(title, "jsonschema", schema_bytes(schema))
        channel = self._writer.channel(topic, "json", self._schemas[title])
        self._channels[topic] = channel
        return channel

    def add_body(self, name: str) -> None:
        """Open the channels of a body: ``/<name>/state``, ``/<name>/transform``
        (foxglove.FrameTransform) and ``/<name>/location`` (foxglove.LocationFix).

        Every scalar of the state message is a JSON-schema'd field that
        Foxglove's Plot panel reads by path (``/<name>/state.altitude``,
        ``.orbit.eccentricity``, ``.position[0]``): no second copy is written."""
        self._bodies[name] = (self._channel(f"/{name}/state", BODY_STATE),
                              self._channel(f"/{name}/transform", foxglove.FRAME_TRANSFORM),
                              self._channel(f"/{name}/location", foxglove.LOCATION_FIX))

    def _stamp(self, t: float) -> int:
        return self._epoch_ns + round(t * 1e9)

    def _write(self, channel: int, stamp: int, message: dict) -> None:
        self._writer.message(channel, stamp, stamp, encode(message), self._sequence)
        self._sequence += 1

    def state(self, body: str, message: dict) -> None:
        """A body's state message, and the Foxglove messages drawn from it."""
        t = message["t"]
        stamp = self._stamp(t)
        state, transform, location = self._bodies[body]
        time = foxglove.timestamp(stamp)
        self._write(state, stamp, message)
        second = math.floor(t)
        if self._earth_at != second:
            # once per second of mission time: Foxglove interpolates between
            # transforms, and the Earth turns 0.004 deg in a second
            self._write(self._earth, stamp, foxglove.earth_transform(time, earth_rotation_angle(t)))
            self._earth_at = second
        self._write(transform, stamp, foxglove.frame_transform(
            time, foxglove.INERTIAL_FRAME, body, message["position"], message["attitude"]))
        self._write(location, stamp, foxglove.location_fix(
            time, body, message["latitude_deg"], message["longitude_deg"], message["altitude"]))

    def event(self, t: float, body: str, name: str, figures: dict) -> None:
        """An event with its figures (SI), and its line in ``/events/log``."""
        stamp = self._stamp(t)
        self._write(self._events, stamp, {"t": t, "body": body, "name": name, "figures": figures})
        text = name + "".join(f" {k}={v}" for k, v in figures.items())
        self._write(self._event_lines, stamp,
                    foxglove.log_line(stamp, foxglove.INFO, text, body, "", t, body))

    def log(self, t: float, body: str, message: str) -> None:
        """A line the program logged."""
        stamp = self._stamp(t)
        self._write(self._logs, stamp, foxglove.log_line(
            stamp, foxglove.INFO, message, body, self._program_file, t, body))

    def error(self, t: float, message: str) -> None:
        """The error that ended a flight (program exception, Ctrl-C...), in ``/events/log``."""
        stamp = self._stamp(t)
        self._write(self._event_lines, stamp, foxglove.log_line(
            stamp, foxglove.ERROR, message, "rocketsim", "", t, ""))

    def attach(self, name: str, data: bytes, media_type: str = "text/plain") -> None:
        """Attach a file (scenario, vehicle, program...) to the log."""
        self._writer.attachment(name, media_type, data, self._epoch_ns)

    def metadata(self, name: str, values: dict[str, str]) -> None:
        self._writer.metadata(name, {k: str(v) for k, v in values.items()})

    def close(self) -> None:
        """Write the summary and index and close the file (idempotent)."""
        if self._closed:
            return
        self._closed = True
        try:
            self._writer.finish()
        finally:
            self._file.close()

    def __enter__(self) -> "TelemetryWriter":
        return self

    def __exit__(self, exc_type, exc, traceback) -> None:
        if exc_type is None:
            self.close()
            return
        try:
            self.close()
        except OSError:
            pass            # a full disk: the error already on its way is the one to report
