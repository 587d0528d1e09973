"""Read a shared run back: its summary, events, tables and a re-flight check.

Nothing here executes the program a run carries: summarising, tabulating and
exporting only read the file (JSON, never pickle, never ``exec``). Only
:func:`verify` flies the run again, and it refuses a run with a program
unless called with ``trust=True``.

A complete file is summarised from its summary section, its metadata and
the few event and log messages (a one-hour flight in well under a second);
a truncated or corrupted file is read record by record up to the break and
:class:`Run` says what went wrong (``problem``).
"""

from __future__ import annotations

import json
import math
import os
import tempfile
from dataclasses import dataclass, field
from pathlib import Path, PurePosixPath
from typing import Iterator

from mcap.exceptions import EndOfFile
from mcap.reader import make_reader
from mcap.records import Attachment, Channel, Message, Metadata, Schema
from mcap.stream_reader import StreamReader

STATE_SUFFIX = "/state"
TEXT_TOPICS = ("/events", "/log", "/events/log")

# components of the vector fields of a state message, in their order
_AXES = {"position": "xyz", "velocity": "xyz", "body_rates": "xyz", "attitude": "wxyz"}


class UntrustedProgram(Exception):
    """Re-flying would execute the program the run carries, and trust was not given."""


@dataclass
class Run:
    """What a run's file says, read without executing anything.

    ``final`` maps each body to its last state message; ``counts`` each topic
    to its number of messages; ``problem`` is None for a sound file, else why
    the rest could not be read.
    """

    path: Path
    metadata: dict[str, dict[str, str]] = field(default_factory=dict)
    attachments: dict[str, bytes] = field(default_factory=dict)
    counts: dict[str, int] = field(default_factory=dict)
    events: list[dict] = field(default_factory=list)
    logs: list[dict] = field(default_factory=list)
    errors: list[dict] = field(default_factory=list)
    final: dict[str, dict] = field(default_factory=dict)
    start_ns: int | None = None
    end_ns: int | None = None
    problem: str | None = None

    @property
    def bodies(self) -> list[str]:
        return [topic[1:-len(STATE_SUFFIX)] for topic in self.counts if _is_state(topic)]

    @property
    def program(self) -> str | None:
        """Name of the attached program, if the run carries one."""
        return next((name for name in self.attachments if name.startswith("program/")), None)

    @property
    def summary(self) -> dict | None:
        """The flight summary the simulator wrote at the end (None if it never finished)."""
        text = self.metadata.get("summary", {}).get("json")
        return json.loads(text) if text else None


def _is_state(topic: str) -> bool:
    return topic.endswith(STATE_SUFFIX) and topic.count("/") == 2


def read_run(path: str | Path) -> Run:
    """Summarise the run in ``path`` (complete, truncated or corrupted alike)."""
    path = Path(path)
    try:
        return _read_indexed(path)
    except Exception:           # no usable summary section: read what precedes the break
        return _read_streamed(path)


def _read_indexed(path: Path) -> Run:
    run = Run(path)
    with open(path, "rb") as stream:
        reader = make_reader(stream)
        summary = reader.get_summary()
        if summary is None or summary.statistics is None:
            raise ValueError("no summary section")
        topics = {c.id: c.topic for c in summary.channels.values()}
        run.counts = {topics[i]: n for i, n in sorted(summary.statistics.channel_message_counts.items())}
        run.start_ns = summary.statistics.message_start_time
        run.end_ns = summary.statistics.message_end_time
        run.metadata = {m.name: dict(m.metadata) for m in reader.iter_metadata()}
        run.attachments = {a.name: bytes(a.data) for a in reader.iter_attachments()}
        for _, channel, message in reader.iter_messages(topics=list(TEXT_TOPICS)):
            _keep_text(run, channel.topic, message.data)
        for topic in [t for t in run.counts if _is_state(t)]:
            for _, _, message in reader.iter_messages(topics=[topic], reverse=True):
                run.final[topic[1:-len(STATE_SUFFIX)]] = _message(message.data, STATE_SUFFIX)
                break
    return run


class _Break(Exception):
    """Where and why a damaged file stops being readable."""


_MAGIC = b"\x89MCAP0\r\n"
_CHUNK = 0x06


def records(path: str | Path) -> Iterator:
    """Every readable record of an MCAP file in file order, chunks opened.

    A file cut inside a chunk still gives the messages of that chunk's
    readable part (zstd decompresses a frame's prefix). Raises
    :class:`_Break` after the last readable record of a damaged file.
    """
    import io
    import struct

    data = Path(path).read_bytes()
    if not data.startswith(_MAGIC):
        raise _Break("it does not start as an MCAP file")
    at, whole = len(_MAGIC), []
    while at + 9 <= len(data):
        opcode, length = struct.unpack_from("<BQ", data, at)
        if at + 9 + length > len(data):
            break
        whole.append(data[at:at + 9 + length])
        at += 9 + length
    try:
        yield from StreamReader(io.BytesIO(b"".join(whole)), skip_magic=True, validate_crcs=True).records
    except EndOfFile:
        pass                    # the end of the complete records
    except Exception as error:
        raise _Break(f"a record is corrupt ({type(error).__name__}: {error})") from None
    if at >= len(data) - len(_MAGIC) and data.endswith(_MAGIC):
        return
    if at + 9 <= len(data) and data[at] == _CHUNK:
        yield from _partial_chunk(data[at + 9:])
    raise _Break(f"the file is cut short at byte {len(data)} (inside a record that starts at byte {at})")


def _partial_chunk(body: bytes) -> Iterator:
    """The complete records at the start of a chunk cut short (zstd or uncompressed)."""
    import io
    import struct

    try:
        (compression_length,) = struct.unpack_from("<I", body, 28)
        compression = body[32:32 + compression_length].decode()
        start = 32 + compression_length + 8
        if compression == "zstd":
            import zstandard
            inner = zstandard.ZstdDecompressor().decompressobj().decompress(body[start:])
        elif compression == "":
            inner = body[start:]
        else:
            return
    except Exception:
        return
    try:
        yield from StreamReader(io.BytesIO(inner), skip_magic=True).records
    except Exception:
        return


def _read_streamed(path: Path) -> Run:
    run = Run(path)
    channels: dict[int, str] = {}
    last_state: dict[str, bytes] = {}
    try:
        for record in records(path):
            if isinstance(record, Channel):
                channels[record.id] = record.topic
                run.counts.setdefault(record.topic, 0)
            elif isinstance(record, Message):
                topic = channels.get(record.channel_id, f"#{record.channel_id}")
                run.counts[topic] = run.counts.get(topic, 0) + 1
                run.start_ns = record.log_time if run.start_ns is None else min(run.start_ns, record.log_time)
                run.end_ns = record.log_time if run.end_ns is None else max(run.end_ns, record.log_time)
                if topic in TEXT_TOPICS:
                    _keep_text(run, topic, record.data)
                elif _is_state(topic):
                    last_state[topic] = record.data
            elif isinstance(record, Metadata):
                run.metadata[record.name] = dict(record.metadata)
            elif isinstance(record, Attachment):
                run.attachments[record.name] = bytes(record.data)
        run.problem = "the file ends without its summary section"
    except _Break as error:
        run.problem = f"{error}; {sum(run.counts.values())} messages read"
    except Exception as error:
        run.problem = f"unreadable ({type(error).__name__}: {error}); {sum(run.counts.values())} messages read"
    for topic, data in last_state.items():
        try:
            run.final[topic[1:-len(STATE_SUFFIX)]] = _message(data, STATE_SUFFIX)
        except ValueError as error:
            run.problem = f"{error} in {topic}; {run.problem}"
    if not run.counts and run.problem:
        run.problem = "not an MCAP file, or nothing in it is readable: " + run.problem
    return run


# what a summary reads of each message, and its types: a damaged file's message that
# lacks them is refused as damage (ValueError), not shown as a KeyError
_NUMBER = (int, float, type(None))
_FIELDS = {"/events": {"t": _NUMBER, "body": str, "name": str, "figures": dict},
           "/log": {"message": str}, "/events/log": {"message": str, "level": int},
           STATE_SUFFIX: {"t": _NUMBER, "altitude": _NUMBER, "latitude_deg": _NUMBER,
                          "longitude_deg": _NUMBER, "speed": _NUMBER}}


def _message(data: bytes, kind: str) -> dict:
    """A message's JSON, with the fields of ``kind`` (a topic or STATE_SUFFIX) of their types."""
    message = json.loads(data)
    if not isinstance(message, dict) or not all(
            isinstance(message.get(key, ...), types) for key, types in _FIELDS[kind].items()):
        raise ValueError(f"a damaged {kind} message")
    return message


def _keep_text(run: Run, topic: str, data: bytes) -> None:
    message = _message(data, topic)
    if topic == "/events":
        run.events.append(message)
    elif topic == "/log":
        run.logs.append(message)
    elif message.get("level", 0) >= 4:       # foxglove.Log ERROR / FATAL
        run.errors.append(message)


# --- tables ---------------------------------------------------------------------

def flat_row(message: dict) -> dict:
    """A state message as one flat row: vectors by component (``position_x``,
    ``attitude_w``...), the orbit as ``orbit_*``, other values as they are."""
    row = {}
    for key, value in message.items():
        if isinstance(value, list):
            axes = _AXES.get(key) or [str(i) for i in range(len(value))]
            row.update({f"{key}_{a}": v for a, v in zip(axes, value)})
        elif isinstance(value, dict):
            row.update({f"{key}_{k}": v for k, v in value.items() if not isinstance(v, (dict, list))})
        else:
            row[key] = value
    return row


def states(path: str | Path, body: str) -> Iterator[dict]:
    """The state messages of ``body`` in time order (stops quietly at a break)."""
    topic = f"/{body}{STATE_SUFFIX}"
    try:
        with open(path, "rb") as stream:
            reader = make_reader(stream)
            if reader.get_summary() is not None:
                for _, _, message in reader.iter_messages(topics=[topic]):
                    yield json.loads(message.data)
                return
    except Exception:
        pass
    channel_id = None
    try:
        for record in records(path):
            if isinstance(record, Channel) and record.topic == topic:
                channel_id = record.id
            elif isinstance(record, Message) and record.channel_id == channel_id:
                yield json.loads(record.data)
    except Exception:
        return


def table(path: str | Path, body: str) -> dict[str, list]:
    """Columns of ``body``'s state messages, flattened by :func:`flat_row`."""
    columns: dict[str, list] = {}
    n = 0
    for message in states(path, body):
        row = flat_row(message)
        for key in row:
            if key not in columns:
                columns[key] = [None] * n
        for key, column in columns.items():
            column.append(row.get(key))
        n += 1
    return columns


def export(path: str | Path, out_dir: str | Path, kind: str = "csv") -> list[Path]:
    """Write one table per body (``<body>.csv`` or ``.parquet``) and ``events.csv``
    into ``out_dir``; return the files written. Floats keep every digit."""
    out_dir = Path(out_dir)
    if kind == "parquet":
        try:
            import pyarrow
            import pyarrow.parquet
        except ImportError:
            raise ImportError("parquet export needs pyarrow: pip install 'rocketsim[parquet]'") from None
    out_dir.mkdir(parents=True, exist_ok=True)
    run = read_run(path)
    written = []
    for body in run.bodies:
        columns = table(path, body)
        target = out_dir / f"{body}.{kind}"
        if kind == "csv":
            _write_csv(target, columns)
        else:
            # a column with no value in this run (e.g. the throttle of an engine group
            # that never ran) is float, not parquet's null type
            pyarrow.parquet.write_table(pyarrow.table({
                key: pyarrow.array(values, type=pyarrow.float64()) if all(v is None for v in values)
                else values for key, values in columns.items()}), target)
        written.append(target)
    events = out_dir / "events.csv"
    _write_csv(events, {"t": [e["t"] for e in run.events], "body": [e["body"] for e in run.events],
                        "name": [e["name"] for e in run.events],
                        "figures": [json.dumps(e["figures"]) for e in run.events]})
    written.append(events)
    return written


def _write_csv(target: Path, columns: dict[str, list]) -> None:
    import csv
    names = list(columns)
    with open(target, "w", newline="") as stream:
        out = csv.writer(stream)
        out.writerow(names)
        for row in zip(*(columns[k] for k in names)):
            out.writerow(["" if v is None else repr(v) if isinstance(v, float) else v for v in row])


# --- verification ----------------------------------------------------------------

@dataclass
class Verdict:
    """The re-flight compared with the file: ``identical``, how many messages
    were compared, and the first difference (None when identical)."""

    identical: bool
    compared: int
    difference: dict | None = None
    flight_error: str | None = None


def lay_out(run: Run, folder: Path) -> Path:
    """Write the run's attached files into ``folder`` in their original layout
    (metadata ``files``: paths relative to the scenario's folder); return the
    scenario's path. Paths are kept inside ``folder``."""
    layout = run.metadata.get("files")
    if not layout or "scenario" not in layout:
        raise ValueError("the run does not record the layout of its files (written by an older rocketsim)")
    by_role = {name.rsplit("/", 1)[0]: data for name, data in run.attachments.items()}   # role/file name
    depth = 0
    for rel in layout.values():
        level = 0
        for part in PurePosixPath(rel).parts:
            level += -1 if part == ".." else 0 if part == "." else 1
            depth = max(depth, -level)
    home = folder.joinpath(*[f"d{i}" for i in range(depth)])
    root = folder.resolve()
    scenario = None
    for role, rel in layout.items():
        target = Path(os.path.normpath(home / rel))
        if root not in target.resolve().parents or role not in by_role:
            raise ValueError(f"the run's file {rel!r} ({role}) cannot be laid out")
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_bytes(by_role[role])
        if role == "scenario":
            scenario = target
    return scenario


def verify(path: str | Path, trust: bool = False) -> Verdict:
    """Fly the run again from its attachments and compare every message.

    A run that carries a program is flown only with ``trust=True``: flying
    executes that program. Raises :class:`UntrustedProgram` otherwise.
    """
    from rocketsim.scenario.load import load
    from rocketsim.sim.flight import fly

    run = read_run(path)
    if run.program and not trust:
        raise UntrustedProgram(run.program)
    info = run.metadata.get("rocketsim", {})
    with tempfile.TemporaryDirectory(prefix="rocketsim-verify-") as folder:
        scenario = lay_out(run, Path(folder) / "files")
        again = Path(folder) / "again.mcap"
        flight_error = None
        try:
            fly(load(scenario), again, step=float(info["step_s"]), duration=float(info["duration_s"]))
        except Exception as error:      # the original may have ended the same way
            flight_error = f"{type(error).__name__}: {error}"
        return _compare(_messages(Path(path)), _messages(again), flight_error)


def _messages(path: Path) -> Iterator[tuple[str, int, bytes]]:
    """(topic, log time, data) in file order, up to any break (a sound file is
    read chunk by chunk; a damaged one record by record)."""
    if read_run(path).problem is None:
        with open(path, "rb") as stream:
            for _, channel, message in make_reader(stream).iter_messages(log_time_order=False):
                yield channel.topic, message.log_time, bytes(message.data)
        return
    channels: dict[int, str] = {}
    try:
        for record in records(path):
            if isinstance(record, Channel):
                channels[record.id] = record.topic
            elif isinstance(record, Message):
                yield channels.get(record.channel_id, ""), record.log_time, bytes(record.data)
    except Exception:
        return


def _compare(original, again, flight_error) -> Verdict:
    n = 0
    end = object()
    while True:
        a, b = next(original, end), next(again, end)
        if a is end and b is end:
            return Verdict(True, n, None, flight_error)
        if a != b:
            return Verdict(False, n, _difference(n, a, b, end), flight_error)
        n += 1


def _difference(index: int, a, b, end) -> dict:
    where = a if a is not end else b
    found = {"index": index, "topic": where[0], "log_time_ns": where[1]}
    if a is end or b is end:
        found["field"] = "(the " + ("file" if a is end else "re-flight") + " has no more messages)"
        return found
    if a[0] != b[0] or a[1] != b[1]:
        found["field"] = f"(topic/time: re-flight has {b[0]} at {b[1]} ns)"
        return found
    try:
        first, second = flat_row(json.loads(a[2])), flat_row(json.loads(b[2]))
    except ValueError:
        found["field"] = "(the message is not JSON)"
        return found
    for key in list(first) + [k for k in second if k not in first]:
        x, y = first.get(key, "(missing)"), second.get(key, "(missing)")
        if x != y and not (isinstance(x, float) and isinstance(y, float) and math.isnan(x) and math.isnan(y)):
            found.update(field=key, file=x, reflight=y)
            return found
    found["field"] = "(same values, different bytes)"
    return found
