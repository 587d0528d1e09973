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

from mcap.data_stream import ReadDataStream
from mcap.opcode import Opcode
from mcap.records import Channel, Chunk, Schema
from mcap.stream_reader import get_chunk_data_stream

MAGIC = b"\x89MCAP0\r\n"
_RECORD = struct.Struct("<BQ")                      # opcode, content length
_MESSAGE = struct.Struct("<HIQQ")                   # a message's channel, sequence, log and publish time
_TIMES = struct.Struct("<QQ")                       # a chunk's first and last message log times


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
    (the file is opened once it exists)."""

    def __init__(self, path: str | Path):
        self.path = Path(path)
        self._file = None
        self._at = 0                    # where the next record starts (after the magic: 8)
        self.ended = False              # the Data End record was read

    def next_record(self) -> Record | None:
        """The next whole record on disk (None: not yet written, or the data section
        has ended, :attr:`ended`); :class:`DamagedFile` if the file is not MCAP."""
        if self.ended:
            return None
        if self._file is None:
            try:
                self._file = open(self.path, "rb")
            except FileNotFoundError:
                return None
        size = os.fstat(self._file.fileno()).st_size
        if self._at == 0:
            if size < len(MAGIC):
                return None
            if self._read(0, len(MAGIC)) != MAGIC:
                raise DamagedFile(f"{self.path} is not an MCAP file")
            self._at = len(MAGIC)
        if size < self._at + _RECORD.size:
            return None
        opcode, length = _RECORD.unpack(self._read(self._at, _RECORD.size))
        end = self._at + _RECORD.size + length
        if size < end:
            return None
        content = self._read(self._at + _RECORD.size, length)
        self._at = end
        if opcode == Opcode.DATA_END:
            self.ended = True
        return Record(opcode, content)

    def _read(self, at: int, n: int) -> bytes:
        self._file.seek(at)
        data = self._file.read(n)
        if len(data) != n:
            raise DamagedFile(f"{self.path} shrank while it was read")
        return data

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
