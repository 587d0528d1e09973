"""Stream telemetry to an MCAP file as the flight goes.

The file is chunked (zstd) so memory stays bounded however long the flight
(:class:`~rocketsim.telemetry.mcap_stream.McapStream`); messages are JSON with
registered JSON schemas. A body's sample (state, transform, location) is
written from its numbers alone (:meth:`TelemetryWriter.sample`), the bytes
orjson would write for the messages as dictionaries (:meth:`TelemetryWriter.state`). Timestamps are the mission
epoch (UTC, ns since 1970) plus mission time, so Foxglove shows real dates and
the same run always writes the same bytes: nothing here reads the wall clock.

The scenario and every file it references travel in the file as attachments,
so a run can be shared as one file. :meth:`TelemetryWriter.close` writes the
summary and index; callers use the writer as a context manager so the file is
finished on success, on a program error and on Ctrl-C alike.
"""

from __future__ import annotations

import math
from collections import deque
from itertools import islice
from pathlib import Path

import numpy as np
import orjson

from rocketsim.version import __version__
from rocketsim._jit import entry_point
from rocketsim.frames.earth_fixed import earth_rotation_angle
from rocketsim.telemetry import foxglove, splice
from rocketsim.telemetry.mcap_stream import McapStream
from rocketsim.telemetry.schemas import BODY_STATE, EVENT, schema_bytes

PROFILE = ""
# Uncompressed bytes per chunk: about 18 s of one body at 10 Hz. Memory held
# while flying is one chunk; a file cut short loses at most the last one.
CHUNK_SIZE = 256 * 1024
LIBRARY = f"rocketsim {__version__}"
# samples written together (TelemetryWriter.sample): a few kB of numbers held
PENDING = 32
_NO_TEXT = np.frombuffer(b"", dtype=np.uint8)      # a template's text: read-only bytes


def encode(message: dict) -> bytes:
    """JSON bytes of a message: compact, keys in insertion order, floats in
    their shortest round-trip form (orjson: ~2 us for a state message where
    the standard library takes ~15 us). NaN and infinities become null, as
    JSON has no spelling for them; numpy scalars and arrays are written as numbers."""
    return orjson.dumps(message, default=_plain, option=orjson.OPT_SERIALIZE_NUMPY)


def _records():
    """:func:`rocketsim.telemetry.splice.records`' compiled entry (bound on first need:
    its argument types never change, and the dispatcher's typing of fourteen arguments
    costs about as much as the call)."""
    global _RECORDS
    if _RECORDS is None:
        ints = np.zeros(1, dtype=np.int64)
        _RECORDS = entry_point(splice.records, b"", np.zeros((1, 1)), ints, 0, _NO_TEXT, ints, b"",
                               ints, 0, 0, np.zeros(1, dtype=np.uint8), 0, ints, 0)
    return _RECORDS


_RECORDS = None


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
        self._plans: dict[str, tuple] = {}      # body -> its messages' template (sample)
        self._pending: deque[tuple] = deque()   # samples waiting to be written (sample)

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
        self._flush()
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
        self._flush()
        t = message["t"]
        stamp = self._stamp(t)
        time = foxglove.timestamp(stamp)
        (state, data), *foxglove_messages = self._messages(body, time, message)
        self._write(state, stamp, data)
        earth = self._earth_turn(t, stamp)
        if earth is not None:
            self._write(self._earth, stamp, earth)
        for channel, data in foxglove_messages:
            self._write(channel, stamp, data)

    def sample(self, body: str, values: np.ndarray, fields) -> None:
        """What :meth:`state` writes for the message ``fields(values, int)``, from a byte
        template of the message (worked out once per body and ``fields``) filled with
        ``values`` (float64, not to be changed afterwards) in one compiled call
        (:mod:`rocketsim.telemetry.splice`): the same bytes, without the dictionaries.

        Samples wait, up to :data:`PENDING` of them, and are written together before
        anything else is (a message, an attachment, metadata, a body's channels, the
        end of the file): the file's order is the flight's, and writing them back to
        back keeps the writer's code and data in the processor's caches."""
        self._pending.append((body, values, fields))
        if len(self._pending) >= PENDING:
            self._flush()

    def _flush(self) -> None:
        """Write the samples waiting (see :meth:`sample`): each run of samples of one
        body and message shape in one compiled call, leaving the queue once written (a
        Ctrl-C in between leaves the rest for :meth:`close`)."""
        pending = self._pending
        while pending:
            body, values, fields = pending[0]
            plan = self._plans.get(body)
            if plan is None or plan[0] is not fields or plan[1] != values.shape[0]:
                plan = self._plans[body] = self._plan(body, values.shape[0], fields)
            _, size, text, cuts, t_index, most = plan
            run = [values]
            for other, more, shape in islice(pending, 1, None):
                if other != body or shape is not fields or more.shape[0] != size:
                    break
                run.append(more)
            stamps, extras, ends = [], [], [0]
            for values in run:
                t = values.item(t_index)
                stamp = self._stamp(t)
                earth = self._earth_turn(t, stamp)
                if earth is not None:
                    extras.append(encode(earth))
                ends.append(ends[-1] + (0 if earth is None else len(extras[-1])))
                stamps.append(stamp)
            block = np.stack(run)
            extra = b"".join(extras)
            chunk, at, index, n = self._writer.reserve(most * len(run) + len(extra), 4 * len(run))
            at, records = _records()(orjson.dumps(block, option=orjson.OPT_SERIALIZE_NUMPY), block,
                                     np.array(stamps, dtype=np.int64), self._sequence, text, cuts,
                                     extra, np.array(ends, dtype=np.int64), self._earth, 0, chunk, at,
                                     index, n)
            self._writer.added(at, records)
            self._sequence += records - n
            for _ in run:
                pending.popleft()

    def _plan(self, body: str, n: int, fields) -> tuple:
        """``(fields, n, text, plan, index of t, most bytes of its records)``:
        the template of a body's three messages (:func:`rocketsim.telemetry.splice.template`)."""
        message = fields(splice.slots(n), splice.Slot.integer)
        messages = self._messages(body, splice.time_slots(), message)
        text, cuts = splice.template(messages)
        return fields, n, text, cuts, message["t"].index, splice.most(text, cuts)

    def _messages(self, body: str, time: dict, message: dict) -> list[tuple[int, dict]]:
        """``(channel, message)``: the body's state message and the Foxglove transform and
        location drawn from it, at ``time`` (:func:`rocketsim.telemetry.foxglove.timestamp`)."""
        state, transform, location = self._bodies[body]
        return [(state, message),
                (transform, foxglove.frame_transform(time, foxglove.INERTIAL_FRAME, body,
                                                     message["position"], message["attitude"])),
                (location, foxglove.location_fix(time, body, message["latitude_deg"],
                                                 message["longitude_deg"], message["altitude"]))]

    def _earth_turn(self, t: float, stamp: int) -> dict | None:
        """The Earth's transform to write after a state message at ``t`` (s), once per
        second of mission time: Foxglove interpolates between transforms, and the
        Earth turns 0.004 deg in a second."""
        second = math.floor(t)
        if self._earth_at == second:
            return None
        self._earth_at = second
        return foxglove.earth_transform(foxglove.timestamp(stamp), earth_rotation_angle(t))

    def event(self, t: float, body: str, name: str, figures: dict) -> None:
        """An event with its figures (SI), and its line in ``/events/log``."""
        self._flush()
        stamp = self._stamp(t)
        self._write(self._events, stamp, {"t": t, "body": body, "name": name, "figures": figures})
        text = name + "".join(f" {k}={v}" for k, v in figures.items())
        self._write(self._event_lines, stamp,
                    foxglove.log_line(stamp, foxglove.INFO, text, body, "", t, body))

    def log(self, t: float, body: str, message: str) -> None:
        """A line the program logged."""
        self._flush()
        stamp = self._stamp(t)
        self._write(self._logs, stamp, foxglove.log_line(
            stamp, foxglove.INFO, message, body, self._program_file, t, body))

    def error(self, t: float, message: str) -> None:
        """The error that ended a flight (program exception, Ctrl-C...), in ``/events/log``."""
        self._flush()
        stamp = self._stamp(t)
        self._write(self._event_lines, stamp, foxglove.log_line(
            stamp, foxglove.ERROR, message, "rocketsim", "", t, ""))

    def attach(self, name: str, data: bytes, media_type: str = "text/plain") -> None:
        """Attach a file (scenario, vehicle, program...) to the log."""
        self._flush()
        self._writer.attachment(name, media_type, data, self._epoch_ns)

    def metadata(self, name: str, values: dict[str, str]) -> None:
        self._flush()
        self._writer.metadata(name, {k: str(v) for k, v in values.items()})

    def close(self) -> None:
        """Write the summary and index and close the file (idempotent)."""
        if self._closed:
            return
        self._closed = True
        try:
            self._flush()
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
