"""Read a run's MCAP file back, complete, truncated or corrupted, executing nothing.

Reading is JSON only (never pickle, never ``exec``): the program a run carries
is an attachment like any other. Work is bounded by the file: before a chunk
is decompressed its record is checked against the file's size and its
declared uncompressed size against :data:`MAX_RATIO` times its compressed
size (at most :data:`MAX_CHUNK` bytes; a zstd frame may not claim more than
its chunk declares; only zstd and uncompressed chunks are read), so a small
crafted file cannot demand gigabytes (:func:`chunk_problem`); a file with such
a chunk is read up to it, as a damaged one. A complete file is summarised from its
summary section, its metadata and the few event and log messages (a one-hour
flight in well under a second); a truncated or corrupted file is read record
by record up to the break, and :class:`RunFile` says what went wrong
(``problem``). The message iterators stop quietly at a break.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from pathlib import Path
from typing import Iterator

from mcap.exceptions import EndOfFile
from mcap.reader import make_reader
from mcap.records import Attachment, Channel, Message, Metadata
from mcap.stream_reader import StreamReader

from rocketsim.telemetry.names import FORMER_FIELDS

STATE_SUFFIX = "/state"
# a chunk's uncompressed size may be at most this many times its compressed size (the
# telemetry packs 5-6 : 1; zstd can claim 30 000 : 1, a 17 KB file half a gigabyte) ...
MAX_RATIO = 1000
MAX_CHUNK = 1 << 28         # ... and at most 256 MiB (the writer's chunks are 256 KiB)
TEXT_TOPICS = ("/events", "/log", "/events/log")


@dataclass
class RunFile:
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


def read_run(path: str | Path) -> RunFile:
    """Summarise the run in ``path`` (complete, truncated or corrupted alike)."""
    path = Path(path)
    try:
        return _read_indexed(path)
    except Exception:           # no usable summary section: read what precedes the break
        return _read_streamed(path)


def chunk_problem(content: bytes | memoryview, size: int) -> str | None:
    """Why the chunk record whose content (after opcode and length) starts with
    ``content`` (its fixed fields and the first bytes of its data, 64 will do) and is
    ``size`` bytes long cannot be opened in bounded work; None when it can."""
    import struct
    try:
        (uncompressed,) = struct.unpack_from("<Q", content, 16)
        (name_length,) = struct.unpack_from("<I", content, 28)
        compression = bytes(content[32:32 + name_length]).decode()
        (compressed,) = struct.unpack_from("<Q", content, 32 + name_length)
    except (struct.error, UnicodeDecodeError):
        return "a chunk's header is cut or not text"
    if compressed > size - 40 - name_length:
        return f"a chunk claims {compressed} bytes of data in a record of {size}"
    if compression not in ("zstd", ""):
        return f"a chunk is compressed with {compression!r} (rocketsim reads zstd)"
    if compression == "" and uncompressed != compressed:
        return "an uncompressed chunk's sizes differ"
    if uncompressed > min(MAX_RATIO * max(compressed, 1), MAX_CHUNK):
        return (f"a chunk claims {uncompressed} bytes from {compressed} compressed (at most "
                f"{MAX_RATIO} : 1 and {MAX_CHUNK >> 20} MiB are read)")
    if compression == "zstd":
        import zstandard
        try:
            framed = zstandard.frame_content_size(bytes(content[40 + name_length:40 + name_length + 18]))
        except zstandard.ZstdError:
            return "a chunk's data is not a zstd frame"
        if framed > uncompressed:
            return f"a chunk's zstd frame claims {framed} bytes where the chunk declares {uncompressed}"
    return None


def _check_chunks(path: Path) -> None:
    """Raise ValueError at the first chunk of ``path`` that :func:`chunk_problem` refuses,
    reading only the records' headers (a seek past each record)."""
    import struct
    size = path.stat().st_size
    with open(path, "rb") as stream:
        at = len(_MAGIC)
        while at + 9 <= size:
            stream.seek(at)
            head = stream.read(9 + 64)
            opcode, length = struct.unpack_from("<BQ", head)
            if opcode == _FOOTER or at + 9 + length > size:
                return
            if opcode == _CHUNK:
                problem = chunk_problem(head[9:], length)
                if problem:
                    raise ValueError(f"{problem}, at byte {at}")
            at += 9 + length


def _read_indexed(path: Path) -> RunFile:
    run = RunFile(path)
    _check_chunks(path)         # before the reader decompresses anything
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
_FOOTER = 0x02


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
    at, whole, refused = len(_MAGIC), [], None
    while at + 9 <= len(data):
        opcode, length = struct.unpack_from("<BQ", data, at)
        if at + 9 + length > len(data):
            break
        if opcode == _CHUNK:
            refused = chunk_problem(memoryview(data)[at + 9:at + 9 + min(length, 64)], length)
            if refused:
                break
        whole.append(data[at:at + 9 + length])
        at += 9 + length
    try:
        yield from StreamReader(io.BytesIO(b"".join(whole)), skip_magic=True, validate_crcs=True).records
    except EndOfFile:
        pass                    # the end of the complete records
    except Exception as error:
        raise _Break(f"a record is corrupt ({type(error).__name__}: {error})") from None
    if refused:
        raise _Break(f"{refused}, at byte {at}: not read")
    if at >= len(data) - len(_MAGIC) and data.endswith(_MAGIC):
        return
    if at + 9 <= len(data) and data[at] == _CHUNK:
        yield from _partial_chunk(data[at + 9:])
    raise _Break(f"the file is cut short at byte {len(data)} (inside a record that starts at byte {at})")


def _partial_chunk(body: bytes) -> Iterator:
    """The complete records at the start of a chunk cut short (zstd or uncompressed),
    decompressed no further than the chunk declares (:func:`chunk_problem`)."""
    import io
    import struct

    if chunk_problem(body[:64], 1 << 62) is not None:     # its length is unknown: cut short
        return
    try:
        (uncompressed,) = struct.unpack_from("<Q", body, 16)
        (compression_length,) = struct.unpack_from("<I", body, 28)
        compression = body[32:32 + compression_length].decode()
        start = 32 + compression_length + 8
        if compression == "zstd":
            import zstandard
            inner, pieces, made = zstandard.ZstdDecompressor().decompressobj(), [], 0
            # fed in small pieces (a zstd block of 3 bytes can make 128 KiB), up to the chunk's size
            for piece in range(start, len(body), 256):
                pieces.append(inner.decompress(body[piece:piece + 256]))
                made += len(pieces[-1])
                if made >= uncompressed:
                    break
            inner = b"".join(pieces)[:uncompressed]
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


def _read_streamed(path: Path) -> RunFile:
    run = RunFile(path)
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
                          "longitude_deg": _NUMBER, "inertial_speed": _NUMBER}}


def _message(data: bytes, kind: str) -> dict:
    """A message's JSON, with the fields of ``kind`` (a topic or STATE_SUFFIX) of their types;
    a state written before a field was renamed has it under today's name
    (:data:`rocketsim.telemetry.names.FORMER_FIELDS`)."""
    message = json.loads(data)
    if kind == STATE_SUFFIX and isinstance(message, dict):
        message = {FORMER_FIELDS.get(key, key): value for key, value in message.items()}
    if not isinstance(message, dict) or not all(
            isinstance(message.get(key, ...), types) for key, types in _FIELDS[kind].items()):
        raise ValueError(f"a damaged {kind} message")
    return message


def _keep_text(run: RunFile, topic: str, data: bytes) -> None:
    message = _message(data, topic)
    if topic == "/events":
        run.events.append(message)
    elif topic == "/log":
        run.logs.append(message)
    elif message.get("level", 0) >= 4:       # foxglove.Log ERROR / FATAL
        run.errors.append(message)


def states(path: str | Path, body: str) -> Iterator[dict]:
    """The state messages of ``body`` in time order (stops quietly at a break)."""
    topic = f"/{body}{STATE_SUFFIX}"
    try:
        _check_chunks(Path(path))
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


def iter_raw_messages(path: str | Path) -> Iterator[tuple[str, int, bytes]]:
    """``(topic, log_time_ns, data bytes)`` of every message in file order, up to any
    break (a sound file is read chunk by chunk; a damaged one record by record)."""
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


def messages(path: str | Path, topics: list[str] | None = None) -> Iterator[tuple[str, int, dict]]:
    """Yield ``(topic, log_time_ns, message)`` in log-time order (ValueError: a chunk that
    :func:`chunk_problem` refuses)."""
    _check_chunks(Path(path))
    with open(path, "rb") as stream:
        reader = make_reader(stream)
        for _schema, channel, message in reader.iter_messages(topics=topics):
            yield channel.topic, message.log_time, json.loads(message.data)


def raw_messages(path: str | Path) -> list[tuple[str, int, bytes]]:
    """Every message as ``(topic, log_time_ns, data bytes)``, in file order
    (:func:`iter_raw_messages` as a list)."""
    return list(iter_raw_messages(path))


def attachments(path: str | Path) -> dict[str, bytes]:
    """Attachments by name."""
    with open(path, "rb") as stream:
        reader = make_reader(stream)
        return {a.name: bytes(a.data) for a in reader.iter_attachments()}


def metadata(path: str | Path) -> dict[str, dict[str, str]]:
    """Metadata records by name."""
    with open(path, "rb") as stream:
        reader = make_reader(stream)
        return {m.name: dict(m.metadata) for m in reader.iter_metadata()}
