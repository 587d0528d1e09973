"""Stream telemetry to an MCAP file as the flight goes.

The file is chunked (zstd) so memory stays bounded however long the flight
(:class:`~rocketsim.telemetry.mcap_stream.McapStream`); messages are JSON with
registered JSON schemas. A body's sample (state, transform, location) is
written from its numbers alone (:meth:`TelemetryWriter.sample`), the bytes
orjson would write for the messages as dictionaries (:meth:`TelemetryWriter.state`)
without their missing values (None, or nan and infinities, which JSON cannot
spell: left out, so that every field has its schema's type). The frames are
those of :mod:`rocketsim.telemetry.frames`. Timestamps are the mission
epoch (UTC, ns since 1970) plus mission time, so Foxglove shows real dates and
the same run always writes the same bytes: nothing here reads the wall clock.

The scenario and every file it references travel in the file as attachments,
so a run can be shared as one file. :meth:`TelemetryWriter.close` writes the
summary and index; callers use the writer as a context manager so the file is
finished on success, on a program error and on Ctrl-C alike.

The file is written on a thread of its own beside the flight's
(:mod:`rocketsim.telemetry.writing_thread`): each public call hands its work
over (samples in batches of :data:`PENDING`) and returns, the thread framing,
compressing and writing it in the calls' order, so the bytes are those the
calls made in line would write. Handing over is whole or not begun (Ctrl-C and
SIGTERM held meanwhile, :mod:`rocketsim.telemetry.held_signals`), the thread's
work is never interrupted (signals reach the main thread only), and
:meth:`TelemetryWriter.close` waits for all of it: no sample is written twice
or lost, and the summary indexes what is on disk.
"""

from __future__ import annotations

import os
import stat
from collections import deque
from pathlib import Path

import numpy as np
import orjson

from rocketsim.version import __version__
from rocketsim.jit import compile_beside, entry_point
from rocketsim.telemetry import foxglove, splice
from rocketsim.telemetry.encoding import encode
from rocketsim.telemetry.held_signals import holding
from rocketsim.telemetry.frames import MISSION_FRAME, CentralFrame, FrameTree, central_frame
from rocketsim.telemetry.mcap_stream import McapStream
from rocketsim.telemetry.sample_plans import (interleaved_rows, interleaved_samples, joined, mission_transform,
                                              present, segment_rows, shape_of, without)
from rocketsim.telemetry.schemas import BODY_STATE, EVENT, schema_bytes
from rocketsim.telemetry.sink import TelemetrySink
from rocketsim.telemetry.writing_thread import WritingThread

PROFILE = ""
# Uncompressed bytes per chunk: about 18 s of one body at 10 Hz. Memory held
# while flying is one chunk; a file cut short loses at most the last one.
CHUNK_SIZE = 256 * 1024
LIBRARY = f"rocketsim {__version__}"
# samples handed to the writing thread together (TelemetryWriter.sample): some 10-60 kB
# of numbers a batch. The thread's Python holds the GIL the flight's Python needs, and some
# of it is per batch, but the last batch is written after the flight, not beside it
# (telemetry on / off, F9 mission: whole 1.22 with 128, 1.18-1.20 with 512; its first 40 s
# 1.14-1.16 with 128, 1.24 with 256, 1.29 with 512)
PENDING = 128


def _records():
    """:func:`rocketsim.telemetry.splice.records`' compiled entry (bound on first need:
    its argument types never change, and the dispatcher's typing of fifteen arguments
    costs about as much as the call). On a cold cache it is compiled beside the flight
    (queued by every writer: :func:`rocketsim.jit.compile_beside`) and loaded from the
    cache here."""
    global _RECORDS
    if _RECORDS is None:
        _RECORDS = entry_point(splice.records, *_RECORDS_ARGUMENTS)
    return _RECORDS


_RECORDS = None
_INTS = np.zeros(1, dtype=np.int64)
# arguments of records' one signature (see splice.records)
_BYTES = np.zeros(1, dtype=np.uint8)
_RECORDS_ARGUMENTS = (b"", np.zeros(1), _INTS, _INTS, 0, _BYTES, _INTS, _INTS, _INTS, _INTS, b"", _INTS,
                      _INTS, _INTS, 0, _BYTES, 0, _INTS, 0)
# where the second process compiles records among the flight's kernels: after the first
# runs' (the flight's first samples come after its own kernels have compiled, seconds in
# which the second core compiles the telemetry's)
RECORDS_PRIORITY = 1


_EARTH = central_frame("earth", np.eye(3), float("nan"))


def _create(path: Path):
    """``path`` opened for writing as a new file: an earlier regular file there (with no
    other name) is removed first rather than truncated, as ext4 (auto_da_alloc) writes a
    file truncated to nothing out to disk when it is closed (a synchronous write a
    new file does not pay)."""
    try:
        found = os.lstat(path)
    except OSError:
        pass
    else:
        if stat.S_ISREG(found.st_mode) and found.st_nlink == 1:
            os.unlink(path)
    return open(path, "wb")


class TelemetryWriter(TelemetrySink):
    """One MCAP telemetry file: per body its state, Foxglove transform and (about
    Earth) location; the central bodies' frames (:mod:`rocketsim.telemetry.frames`);
    the events; the program's log.

    ``program_file`` names the program in the ``file`` field of its log lines. The
    file is created here (an error opening it is raised here) and written on the
    writing thread (see the module): the public methods run on the caller's thread
    and hand their work over (:meth:`_hand_over`), the rest on the writing thread
    once it has started.
    """

    def __init__(self, path: str | Path, epoch_ns: int, program_file: str = ""):
        self.path = Path(path)
        self._file = _create(self.path)
        self._writer = McapStream(self._file, PROFILE, LIBRARY, CHUNK_SIZE)
        self._epoch_ns = epoch_ns
        self._schemas = {}
        self._channels: dict[str, int] = {}
        self._bodies: dict[str, tuple[int, int]] = {}          # state, transform
        self._lead = None                                       # the body the mission frame follows
        self._sequence = 0
        self._closed = False
        self._program_file = program_file
        self._events = self._channel("/events", EVENT)
        self._event_lines = self._channel("/events/log", foxglove.LOG)
        self._logs = self._channel("/log", foxglove.LOG)
        self._frames = FrameTree()
        self._plans: dict[str, tuple] = {}      # body -> its messages' templates (sample)
        self._pending: list[tuple] = []         # blocks of samples to hand over (_add_pending)
        self._pending_rows = 0                  # the samples in them
        self._thread = WritingThread(f"telemetry {self.path.name}")
        if _RECORDS is None:
            compile_beside(splice.records, _RECORDS_ARGUMENTS, RECORDS_PRIORITY)

    def _channel(self, topic: str, schema: dict) -> int:
        channel = self._channels.get(topic)
        if channel is not None:
            return channel
        title = schema["title"]
        if title not in self._schemas:
            self._schemas[title] = self._writer.schema(title, "jsonschema", schema_bytes(schema))
        channel = self._writer.channel(topic, "json", self._schemas[title])
        self._channels[topic] = channel
        return channel

    @holding
    def _hand_over(self, call, *args) -> None:
        """Hand the samples waiting and then ``call(*args)`` (if any) to the writing thread."""
        if self._pending:
            self._thread.submit(self._write_samples, self._pending)
            self._pending, self._pending_rows = [], 0
        if call is not None:
            self._thread.submit(call, *args)

    def add_body(self, name: str) -> None:
        """Open the channels of a body: ``/<name>/state``, ``/<name>/transform``
        (foxglove.FrameTransform), and ``/<name>/location`` (foxglove.LocationFix) once it
        flies about Earth: it is written only then, the Map panel having only Earth's tiles. The
        first body added leads: ``/mission/transform`` follows it.

        Every scalar of the state message is a JSON-schema'd field that
        Foxglove's Plot panel reads by path (``/<name>/state.altitude``,
        ``.orbit.eccentricity``, ``.position[0]``): no second copy is written."""
        self._hand_over(self._add_body, name)

    def _add_body(self, name: str) -> None:
        self._bodies[name] = (self._channel(f"/{name}/state", BODY_STATE),
                              self._channel(f"/{name}/transform", foxglove.FRAME_TRANSFORM))
        if self._lead is None:
            self._lead = name
            self._mission = self._channel(f"/{MISSION_FRAME}/transform", foxglove.FRAME_TRANSFORM)

    def _stamp(self, t: float) -> int:
        return self._epoch_ns + round(t * 1e9)

    def _write(self, channel: int, stamp: int, message: dict) -> None:
        self._writer.message(channel, stamp, stamp, encode(message), self._sequence)
        self._sequence += 1

    def state(self, body: str, message: dict, frame: CentralFrame | None = None) -> None:
        """A body's state message, and the Foxglove messages drawn from it; ``frame``:
        the inertial frame it is in (default: Earth's, without an ephemeris). Values
        that are None or not finite are left out (see :data:`rocketsim.telemetry.schemas.BODY_STATE`)."""
        self._hand_over(self._state, body, present(message), _EARTH if frame is None else frame)

    def _state(self, body: str, message: dict, frame: CentralFrame) -> None:
        t = message["t"]
        stamp = self._stamp(t)
        time = foxglove.timestamp(stamp)
        (state, data), *foxglove_messages = self._messages(body, time, message, frame)
        self._write(state, stamp, data)
        for channel, data in self._frame_transforms(t, stamp) + self._mission_off_root(
                body, frame, message["position"], t, time):
            self._write(channel, stamp, data)
        for channel, data in foxglove_messages:
            self._write(channel, stamp, data)

    def sample(self, body: str, values: np.ndarray, fields, leaving: bool = False) -> None:
        """What :meth:`state` writes for the message ``fields(values, int)`` in the frame
        ``fields.frame``, from a byte template of the message (worked out once per body,
        ``fields`` and set of values missing) filled with ``values`` (float64, not to be
        changed afterwards) in one compiled call (:mod:`rocketsim.telemetry.splice`): the
        same bytes, without the dictionaries. ``leaving``: the body's last sample in a frame
        it leaves at this instant (a handover, whose next sample has the same time in the
        new frame): its state alone, the body's frame and location being those of its new
        centre from this instant on.

        Samples wait, up to :data:`PENDING` of them, and are handed to the writing thread
        together before anything else is (a message, an attachment, metadata, a body's
        channels, the end of the file): the file's order is the flight's, and writing
        them back to back keeps the writer's code and data in the processor's caches."""
        self._add_pending((body, values.reshape(1, -1), fields, leaving), 1)

    def sample_rows(self, body: str, rows: np.ndarray, fields) -> None:
        """:meth:`sample` of each row of ``rows`` (float64, one sample a row, not to be
        changed afterwards) in order: the same bytes, handed on as one block."""
        if len(rows):
            self._add_pending((body, rows, fields, False), len(rows))

    def sample_interleaved(self, blocks: list[tuple]) -> None:
        """:meth:`sample_rows` of several blocks at once, ``(body, rows, fields, first, every,
        rank)`` each (float64 rows, not to be changed afterwards): row ``j`` of a block is
        the sample at step ``first + j every``, and the samples are written by step and
        then rank (several bodies' samples from compiled runs, by step and then body):
        the same bytes, handed on as one."""
        self._add_pending((None, blocks, None, False), sum(len(block[1]) for block in blocks))

    def _add_pending(self, samples: tuple, rows: int) -> None:
        """Queue ``samples`` (``(body, block, fields, leaving)``; interleaved blocks: ``(None,
        blocks, None, False)``), ``rows`` samples, handing the queue over once it is full."""
        self._pending.append(samples)
        self._pending_rows += rows
        if self._pending_rows >= PENDING:
            self._hand_over(None)

    def _write_samples(self, samples: list[tuple]) -> None:
        """Write ``samples`` (blocks of samples, see :meth:`_add_pending`) in order, each with
        the template of its body, message shape and set of missing values (:meth:`_plan`),
        in one compiled call (:meth:`_write_rows`) but where a template is made anew:
        making one may add a frame, so the samples before it are written first. A body's
        blocks that follow one another are looked at as one. Interleaved blocks
        (:meth:`sample_interleaved`) are written in one compiled call of their own where
        each of their samples has its template already, else one sample at a time."""
        segment: list[tuple] = []           # (block of samples, their templates)
        pending = deque(samples)
        while pending:
            body, values, fields, leaving = pending.popleft()
            if body is None:                # interleaved blocks, with those that follow (later steps)
                blocks = list(values)
                while pending and pending[0][0] is None:
                    blocks += pending.popleft()[1]
                rows = interleaved_rows(blocks, self._plans)
                if rows is None:
                    pending.extendleft(reversed([(name, numbers.reshape(1, -1), shape, False)
                                                 for name, numbers, shape in interleaved_samples(blocks)]))
                    continue
                if segment:
                    self._write_rows(*segment_rows(segment))
                    segment = []
                self._write_rows(*rows)
                continue
            size = values.shape[1]
            run = [values]                  # the blocks of one body and shape that follow it: one block
            while pending and pending[0][0] == body and pending[0][2] is fields \
                    and pending[0][1].shape[1] == size and pending[0][3] == leaving:
                run.append(pending.popleft()[1])
            if len(run) > 1:
                values = np.concatenate(run)
            _, _, optional, plans = shape_of(self._plans, body, fields, size)
            missing = ~np.isfinite(values[:, optional])
            # where the set of missing values changes: a template for each stretch
            cuts = [] if len(missing) == 1 or (missing == missing[0]).all() else \
                (np.flatnonzero((missing[1:] != missing[:-1]).any(axis=1)) + 1).tolist()
            for start, end in zip([0] + cuts, cuts + [len(values)]):
                pattern = missing[start]
                key = (pattern.tobytes(), leaving)
                plan = plans.get(key)
                if plan is None:
                    if segment:
                        self._write_rows(*segment_rows(segment))
                        segment = []
                    plan = plans[key] = self._plan(body, size, fields, set(optional[pattern].tolist()),
                                                   not leaving)
                segment.append((values[start:end], plan))
        if segment:
            self._write_rows(*segment_rows(segment))

    def _write_rows(self, values: np.ndarray, row_first: np.ndarray, kind: np.ndarray, chosen: list) -> None:
        """The records of samples whose numbers are ``values`` (float64, the samples' one
        after another, sample ``k``'s from ``row_first[k]``), each written with the template
        ``chosen[kind[k]]`` (:meth:`_plan`), with the central bodies' transforms due after
        them (:meth:`_frame_transforms`: asked at the first sample and where the second of
        mission time changes, the only samples where any can be due, frames being added
        only between such calls) and, for the lead body off the root's centre, the mission
        frame's transform after each of its samples, in one compiled call."""
        times = values[row_first[:-1] + np.array([plan[2] for plan in chosen], dtype=np.int64)[kind]]
        stamps = self._epoch_ns + np.rint(times * 1e9).astype(np.int64)     # as _stamp
        seconds = np.floor(times)
        asked = np.concatenate(([True], seconds[1:] != seconds[:-1]))
        off_root = np.array([plan[4] == self._lead and not self._frames.is_root(plan[5]) for plan in chosen])
        asked |= off_root[kind]
        extras, ends, channels = [], [0], []
        added = np.zeros(len(kind) + 1, dtype=np.int64)        # extra records after each sample
        for k in np.flatnonzero(asked).tolist():
            t, stamp = times.item(k), stamps.item(k)
            more = self._frame_transforms(t, stamp)
            _, _, _, _, body, frame, position = chosen[kind.item(k)]
            if off_root[kind.item(k)]:
                place = values[row_first.item(k):row_first.item(k + 1)][position]
                more += self._mission_off_root(body, frame, place, t, foxglove.timestamp(stamp))
            for channel, data in more:
                extras.append(encode(data))
                ends.append(ends[-1] + len(extras[-1]))
                channels.append(channel)
            added[k + 1] = len(more)
        extra = b"".join(extras)
        texts, text_first = joined([plan[0] for plan in chosen], np.uint8)
        cuts, cut_first = joined([plan[1] for plan in chosen], np.int64)
        most = np.array([plan[3] for plan in chosen], dtype=np.int64)[kind].sum()
        messages = np.array([plan[1][0] for plan in chosen], dtype=np.int64)[kind].sum()
        chunk, at, index, n = self._writer.reserve(int(most) + len(extra) + splice.HEADER * len(channels),
                                                   int(messages) + len(channels))
        at, records = _records()(orjson.dumps(values, option=orjson.OPT_SERIALIZE_NUMPY), values, row_first,
                                 stamps, self._sequence, texts, text_first, cuts, cut_first, kind, extra,
                                 np.array(ends, dtype=np.int64), np.array(channels, dtype=np.int64),
                                 np.cumsum(added), 0, chunk, at, index, n)
        self._writer.added(at, records)
        self._sequence += records - n

    def _plan(self, body: str, n: int, fields, missing: set, drawn: bool) -> tuple:
        """``(text, plan, index of t, most bytes of its records, body, frame, indices of the
        position)``: the template of a body's messages (:func:`rocketsim.telemetry.splice.template`) without the object
        members whose values are ``missing`` (indices), the Foxglove ones only if ``drawn``."""
        message = fields(splice.slots(n), splice.Slot.integer)
        messages = self._messages(body, splice.time_slots(), without(message, missing), fields.frame,
                                  drawn)
        text, cuts = splice.template(messages)
        position = [slot.index for slot in message["position"]]
        return text, cuts, message["t"].index, splice.most(text, cuts), body, fields.frame, position

    def _messages(self, body: str, time: dict, message: dict, frame: CentralFrame,
                  drawn: bool = True) -> list[tuple[int, dict]]:
        """``(channel, message)``: the body's state message and (if ``drawn``) the Foxglove
        messages drawn from it at ``time`` (:func:`rocketsim.telemetry.foxglove.timestamp`):
        its transform in ``frame``, its location about Earth; and the mission frame at the
        lead body."""
        state, transform = self._bodies[body]
        parent, child = self._frames.body_frame(body, frame)
        out = [(state, message)]
        if drawn:
            out.append((transform, foxglove.frame_transform(time, parent, child, message["position"],
                                                            message["attitude"])))
        if drawn and frame.center == "earth":
            location = self._channel(f"/{body}/location", foxglove.LOCATION_FIX)
            out.append((location, foxglove.location_fix(time, body, message["latitude_deg"],
                                                        message["longitude_deg"], message["altitude"])))
        if body == self._lead and self._frames.is_root(frame):
            out.append((self._mission, mission_transform(time, parent, message["position"])))
        return out

    def _mission_off_root(self, body: str, frame: CentralFrame, position, t: float,
                          time: dict) -> list[tuple[int, dict]]:
        """The mission frame's transform at the lead body about another centre than the
        root's (none for another body or about the root's centre: its template has it)."""
        if body != self._lead or self._frames.is_root(frame):
            return []
        place = self._frames.in_root(frame, position, t)
        return [(self._mission, mission_transform(time, self._frames.root, place.tolist()))]

    def _frame_transforms(self, t: float, stamp: int) -> list[tuple[int, dict]]:
        """``(channel, FrameTransform)`` of the central bodies' frames due after a state
        message at ``t`` (s), log time ``stamp`` (ns): :meth:`rocketsim.telemetry.frames.FrameTree.due`,
        each on its body's ``/<body>/transform``."""
        due = self._frames.due(t, stamp)
        return [(self._channel(f"/{center}/transform", foxglove.FRAME_TRANSFORM), message)
                for center, message in due] if due else due

    def event(self, t: float, body: str, name: str, figures: dict) -> None:
        """An event with its figures (SI), and its line in ``/events/log``."""
        self._hand_over(self._event_out, t, body, name, dict(figures))

    def _event_out(self, t: float, body: str, name: str, figures: dict) -> None:
        stamp = self._stamp(t)
        self._write(self._events, stamp, {"t": t, "body": body, "name": name, "figures": figures})
        text = name + "".join(f" {k}={v}" for k, v in figures.items())
        self._write(self._event_lines, stamp,
                    foxglove.log_line(stamp, foxglove.INFO, text, body, "", t, body))

    def log(self, t: float, body: str, message: str) -> None:
        """A line the program logged."""
        self._hand_over(self._log_out, t, body, message)

    def _log_out(self, t: float, body: str, message: str) -> None:
        stamp = self._stamp(t)
        self._write(self._logs, stamp, foxglove.log_line(
            stamp, foxglove.INFO, message, body, self._program_file, t, body))

    def error(self, t: float, message: str) -> None:
        """The error that ended a flight (program exception, Ctrl-C...), in ``/events/log``."""
        self._hand_over(self._error_out, t, message)

    def _error_out(self, t: float, message: str) -> None:
        stamp = self._stamp(t)
        self._write(self._event_lines, stamp, foxglove.log_line(
            stamp, foxglove.ERROR, message, "rocketsim", "", t, ""))

    def attach(self, name: str, data: bytes, media_type: str = "text/plain") -> None:
        """Attach a file (scenario, vehicle, program...) to the log."""
        self._hand_over(self._writer.attachment, name, media_type, bytes(data), self._epoch_ns)

    def metadata(self, name: str, values: dict[str, str]) -> None:
        """A named map of strings (each value written as its ``str``)."""
        self._hand_over(self._writer.metadata, name, {k: str(v) for k, v in values.items()})

    @holding
    def close(self) -> None:
        """Write what was handed over, the summary and index, and close the file
        (idempotent); the error of any writing, if one failed (raised by the first
        call after it, else here)."""
        if self._closed:
            return
        self._closed = True
        try:
            self._hand_over(self._writer.finish)
        finally:
            error = self._thread.stop()
            self._file.close()
        if error is not None:
            raise error

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
