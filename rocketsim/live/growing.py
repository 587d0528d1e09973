"""An MCAP file's records read as they are written (mcap.dev/spec, version 0).

:class:`GrowingMcap` reads the data section of a file that a writer may still
be appending to: each call of :meth:`GrowingMcap.next_record` returns the next
record once it is wholly on disk, else None, and never reads a record twice.
It stops at the Data End record (the summary after it repeats what came
before). A live view follows a flight's telemetry file this way, so what it
serves is what the file holds, record for record.

The records are parsed with the ``mcap`` package (schemas, channels, chunks and
their decompression); the messages inside a chunk are cut out here
(:func:`chunk_messages`), as the ``mcap`` package's reader makes an object per
record, too slow for a live view of a coasting orbit, which must serve a few
hundred thousand messages a second.
"""

from __future__ import annotations

import io
import os
import struct
from dataclasses import dataclass
from pathlib import Path
from typing import Container

from mcap.data_stream import ReadDataStream
from mcap.opcode import Opcode
from mcap.records import Channel, Chunk, Schema
from mcap.stream_reader import get_chunk_data_stream

MAGIC = b"\x89MCAP0\r\n"
_RECORD = struct.Struct("<BQ")                      # opcode, content length
_MESSAGE = struct.Struct("<HIQQ")                   # a message's channel, sequence, log and publish time
_TIMES = struct.Struct("<QQ")                       # a chunk's first and last message log times
READ = 4 << 20                                      # bytes read from the file at most at once


class DamagedFile(ValueError):
    """A file that is not MCAP, or whose records cannot be read."""


@dataclass(frozen=True)
class Record:
    """One record: its opcode (:class:`mcap.opcode.Opcode`) and its content bytes."""

    opcode: int
    content: bytes

    def parsed(self):
        """The record as the ``mcap`` package reads it (Schema, Channel, Chunk)."""
        return _READERS[self.opcode](ReadDataStream(io.BytesIO(self.content)))


_READERS = {Opcode.SCHEMA: Schema.read, Opcode.CHANNEL: Channel.read, Opcode.CHUNK: Chunk.read}


class GrowingMcap:
    """The data section of the MCAP file ``path``, record by record, as it is written
    (the file is opened once it exists). What the file holds beyond the records read is
    read in one go (at most :data:`READ` bytes) and cut into records here."""

    def __init__(self, path: str | Path):
        self.path = Path(path)
        self._file = None
        self._read_to = 0               # bytes of the file read into the buffer
        self._buffer = b""              # the bytes read, not yet returned as records
        self._at = 0                    # where the next record starts in the buffer
        self.ended = False              # the Data End record was read

    def next_record(self, wanted: Container[int] | None = None) -> Record | None:
        """The next whole record on disk (None: not yet written, or the data section
        has ended, :attr:`ended`), passing over those whose opcode is not ``wanted``
        (None: every one is); :class:`DamagedFile` if the file is not MCAP."""
        if self.ended:
            return None
        if self._file is None:
            try:
                self._file = open(self.path, "rb")
            except FileNotFoundError:
                return None
        if self._read_to == 0:
            if not self._more(len(MAGIC)):
                return None
            if self._buffer[:len(MAGIC)] != MAGIC:
                raise DamagedFile(f"{self.path} is not an MCAP file")
            self._at = len(MAGIC)
        header, size, data_end = _RECORD.unpack_from, _RECORD.size, Opcode.DATA_END
        while self._more(size):
            opcode, length = header(self._buffer, self._at)
            if not self._more(size + length):
                return None
            start = self._at + size
            self._at = start + length
            self.ended = opcode == data_end
            if wanted is None or opcode in wanted:
                return Record(opcode, self._buffer[start:self._at])
            if self.ended:
                return None
        return None

    def _more(self, n: int) -> bool:
        """Whether ``n`` bytes from the next record's start are in the buffer, after
        reading what the file holds beyond it if they were not."""
        if len(self._buffer) - self._at >= n:
            return True
        size = os.fstat(self._file.fileno()).st_size
        if size < self._read_to:
            raise DamagedFile(f"{self.path} shrank while it was read")
        missing = n - (len(self._buffer) - self._at)
        if size - self._read_to < missing:
            return False
        data = os.pread(self._file.fileno(), max(missing, min(size - self._read_to, READ)), self._read_to)
        self._read_to += len(data)
        self._buffer = self._buffer[self._at:] + data
        self._at = 0
        return len(self._buffer) >= n

    def close(self) -> None:
        if self._file is not None:
            self._file.close()


def chunk_messages(chunk: Chunk) -> tuple[list[tuple[int, int, bytes]], list[Record]]:
    """``(messages, records)`` of a chunk: each message as ``(channel id, log time ns,
    data)`` in order, and the schema and channel records it holds (a writer may put
    them in chunks; rocketsim's does not)."""
    stream, size = get_chunk_data_stream(chunk)
    data = stream.read(size)
    messages, records = [], []
    at, end = 0, len(data)
    header, fields, message = _RECORD.unpack_from, _MESSAGE.unpack_from, Opcode.MESSAGE
    try:
        while at < end:
            opcode, length = header(data, at)
            start = at + _RECORD.size
            at = start + length
            if opcode == message:
                channel, _, log_time, _ = fields(data, start)
                messages.append((channel, log_time, data[start + _MESSAGE.size:at]))
            elif opcode in (Opcode.SCHEMA, Opcode.CHANNEL):
                records.append(Record(opcode, data[start:at]))
    except struct.error:
        raise DamagedFile("a record runs past the end of its chunk") from None
    if at > end:
        raise DamagedFile("a record runs past the end of its chunk")
    return messages, records


def chunk_times(record: Record) -> tuple[int, int]:
    """``(first, last)`` log times (ns) of the messages of a chunk record, unread."""
    return _TIMES.unpack_from(record.content)


def message_of(record: Record) -> tuple[int, int, bytes]:
    """``(channel id, log time ns, data)`` of a message record outside any chunk."""
    channel, _, log_time, _ = _MESSAGE.unpack_from(record.content)
    return channel, log_time, record.content[_MESSAGE.size:]
