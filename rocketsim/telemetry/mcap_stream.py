"""A streaming MCAP writer with a cheap message path (the MCAP format, version 0).

Telemetry writes tens of thousands of small messages per flight; the ``mcap``
package's writer builds a record object, statistics and index objects and makes
five stream writes for each. This writer packs a message record in one
``struct`` call into the open chunk, a reused byte array, and keeps the chunk's
message index as an array of (channel, log time, offset); a caller that frames
records itself writes them straight into both (:meth:`McapStream.reserve`,
:meth:`McapStream.added`: a telemetry sample's records in one compiled call,
:mod:`rocketsim.telemetry.splice`). Everything else follows the MCAP
specification (mcap.dev/spec) and is read back by the ``mcap`` package's reader:

* data section: magic, Header, then Schema and Channel records as they are
  registered, Chunks (zstd-compressed records, each followed by one Message
  Index record per channel in it), Attachments and Metadata as they come,
  Data End;
* summary section: every Schema and Channel, the Statistics, one Chunk Index
  per chunk, the Attachment and Metadata Indexes, then a Summary Offset per
  group, the Footer (with the summary's CRC-32) and the closing magic.

Chunks carry the CRC-32 of their uncompressed records; attachments carry
their CRC-32. Memory held while writing is one chunk. Times are integers
(ns); nothing reads the clock, so the same calls write the same bytes.

Every call is whole or not begun: Ctrl-C and SIGTERM are held while it runs
(:mod:`rocketsim.telemetry.held_signals`), so the summary :meth:`McapStream.finish`
writes indexes exactly the records on disk, however the writing was stopped.
"""

from __future__ import annotations

import struct
import zlib
from typing import BinaryIO

import numpy as np
import zstandard

from rocketsim.telemetry.held_signals import holding

MAGIC = b"\x89MCAP0\r\n"

HEADER, FOOTER, SCHEMA, CHANNEL, MESSAGE, CHUNK, MESSAGE_INDEX, CHUNK_INDEX = 1, 2, 3, 4, 5, 6, 7, 8
ATTACHMENT, ATTACHMENT_INDEX, STATISTICS, METADATA, METADATA_INDEX = 9, 10, 11, 12, 13
SUMMARY_OFFSET, DATA_END = 14, 15

_RECORD = struct.Struct("<BQ")               # opcode, content length
_MESSAGE = struct.Struct("<BQHIQQ")          # record prefix, channel, sequence, log and publish time
_MESSAGE_FIXED = 2 + 4 + 8 + 8               # content bytes before the data
# zstd level of the chunks: on telemetry chunks level 1 compresses about twice as fast as
# the default level 3 and packs them no worse (tests/benchmarks measure both)
ZSTD_LEVEL = 1
# bytes a chunk holds beyond its size (the records that take it there): grown when short
_SLACK = 16 * 1024


def _string(text: str) -> bytes:
    data = text.encode("utf-8")
    return struct.pack("<I", len(data)) + data


def _string_map(values: dict[str, str]) -> bytes:
    body = b"".join(_string(k) + _string(v) for k, v in values.items())
    return struct.pack("<I", len(body)) + body


def _record(opcode: int, content: bytes) -> bytes:
    return _RECORD.pack(opcode, len(content)) + content


class McapStream:
    """Write one MCAP file to ``stream`` (a binary file opened for writing).

    ``chunk_size``: uncompressed bytes of records gathered before a chunk is
    compressed and written. Call :meth:`finish` once at the end.
    """

    @holding
    def __init__(self, stream: BinaryIO, profile: str = "", library: str = "",
                 chunk_size: int = 256 * 1024):
        self._out = stream
        self._offset = 0
        self._chunk_limit = chunk_size
        self._compressor = zstandard.ZstdCompressor(level=ZSTD_LEVEL)
        self._schemas: list[bytes] = []          # records, for the summary
        self._channels: list[bytes] = []
        self._chunk_indexes: list[bytes] = []
        self._attachment_indexes: list[bytes] = []
        self._metadata_indexes: list[bytes] = []
        self._counts: dict[int, int] = {}        # channel -> messages
        self._first = self._last = None          # log times over the file
        self._attachments = self._metadata = 0
        self._new_chunk()
        self._emit(MAGIC)
        self._emit(_record(HEADER, _string(profile) + _string(library)))

    # --- the file ---------------------------------------------------------
    def _emit(self, data: bytes) -> int:
        """Write ``data`` at the end of the file; returns where it starts."""
        start = self._offset
        self._out.write(data)
        self._offset += len(data)
        return start

    @holding
    def schema(self, name: str, encoding: str, data: bytes) -> int:
        """Register a schema; returns its id (from 1)."""
        schema_id = len(self._schemas) + 1
        record = _record(SCHEMA, struct.pack("<H", schema_id) + _string(name) + _string(encoding)
                         + struct.pack("<I", len(data)) + data)
        self._schemas.append(record)
        self._emit(record)
        return schema_id

    @holding
    def channel(self, topic: str, message_encoding: str, schema_id: int,
                metadata: dict[str, str] | None = None) -> int:
        """Register a channel; returns its id (from 1)."""
        channel_id = len(self._channels) + 1
        record = _record(CHANNEL, struct.pack("<HH", channel_id, schema_id) + _string(topic)
                         + _string(message_encoding) + _string_map(metadata or {}))
        self._channels.append(record)
        self._counts[channel_id] = 0
        self._emit(record)
        return channel_id

    # --- messages, in chunks -------------------------------------------------
    def _new_chunk(self) -> None:
        self._chunk = np.empty(self._chunk_limit + _SLACK, dtype=np.uint8)
        self._view = memoryview(self._chunk)
        self._size = 0
        self._index = np.empty(3 * 1024, dtype=np.int64)   # (channel, log time, offset) per record
        self._n = 0

    @holding
    def reserve(self, size: int, records: int) -> tuple[np.ndarray, int, np.ndarray, int]:
        """Room for ``size`` more bytes of ``records`` more records in the open chunk:
        ``(chunk, its size, index, records in it)``, for a caller that writes records
        at the chunk's end and their (channel, log time, start) triples at the index's,
        then calls :meth:`added`."""
        if self._size + size > self._chunk.shape[0]:
            grown = np.empty(2 * (self._size + size), dtype=np.uint8)
            grown[:self._size] = self._chunk[:self._size]
            self._chunk, self._view = grown, memoryview(grown)
        if 3 * (self._n + records) > self._index.shape[0]:
            grown = np.empty(2 * 3 * (self._n + records), dtype=np.int64)
            grown[:3 * self._n] = self._index[:3 * self._n]
            self._index = grown
        return self._chunk, self._size, self._index, self._n

    @holding
    def added(self, size: int, records: int) -> None:
        """The open chunk now holds ``size`` bytes in ``records`` records (see
        :meth:`reserve`). A chunk ends after the first record that takes it to the
        chunk size, as when messages are added one by one."""
        first = self._n
        self._size, self._n = size, records
        while self._size >= self._chunk_limit:
            # where each record from the first added ends: where the next starts
            ends = np.append(self._index[3 * first + 5:3 * self._n:3], self._size)
            k = int(np.searchsorted(ends, self._chunk_limit))
            self._write_chunk(int(ends[k]), first + k + 1)
            first = 0

    @holding
    def message(self, channel: int, log_time: int, publish_time: int, data: bytes,
                sequence: int = 0) -> None:
        """Add a message (times in ns) to the open chunk."""
        size = 9 + _MESSAGE_FIXED + len(data)
        chunk, at, index, n = self.reserve(size, 1)
        _MESSAGE.pack_into(chunk, at, MESSAGE, _MESSAGE_FIXED + len(data), channel, sequence,
                           log_time, publish_time)
        self._view[at + 9 + _MESSAGE_FIXED:at + size] = data
        index[3 * n:3 * n + 3] = channel, log_time, at
        self.added(at + size, n + 1)

    def _write_chunk(self, size: int | None = None, records: int | None = None) -> None:
        """Compress and write the open chunk's first ``size`` bytes (all by default), its
        first ``records`` records, with their message indexes and (for the summary) its
        chunk index; what follows them starts the next chunk."""
        size = self._size if size is None else size
        records = self._n if records is None else records
        if records == 0:
            return
        data = self._view[:size]
        compressed = self._compressor.compress(data)
        entries = self._index[:3 * records].reshape(records, 3)
        channels, times = entries[:, 0], entries[:, 1]
        first, last = int(times.min()), int(times.max())
        chunk = _record(CHUNK, struct.pack("<QQQI", first, last, size, zlib.crc32(data))
                        + _string("zstd") + struct.pack("<Q", len(compressed)) + compressed)
        chunk_start = self._emit(chunk)
        index_offsets = {}
        index_start = self._offset
        by_channel = np.argsort(channels, kind="stable")       # each channel's records in order
        pairs = entries[by_channel, 1:].astype("<u8")
        present, starts, counts = np.unique(channels[by_channel], return_index=True, return_counts=True)
        for channel, start, count in zip(present.tolist(), starts.tolist(), counts.tolist()):
            self._counts[channel] += count
            index_offsets[channel] = self._emit(_record(
                MESSAGE_INDEX, struct.pack("<HI", channel, 16 * count) + pairs[start:start + count].tobytes()))
        offsets = b"".join(struct.pack("<HQ", c, o) for c, o in index_offsets.items())
        self._chunk_indexes.append(_record(CHUNK_INDEX, struct.pack(
            "<QQQQI", first, last, chunk_start, len(chunk), len(offsets)) + offsets
            + struct.pack("<Q", self._offset - index_start) + _string("zstd")
            + struct.pack("<QQ", len(compressed), size)))
        self._first = first if self._first is None else min(self._first, first)
        self._last = last if self._last is None else max(self._last, last)
        # what follows starts the next chunk, in the same arrays (fresh ones cost their
        # pages' first touch again)
        rest, rest_records = self._size - size, self._n - records
        self._chunk[:rest] = self._chunk[size:self._size]
        self._index[:3 * rest_records] = self._index[3 * records:3 * self._n]
        self._index[2:3 * rest_records:3] -= size
        self._size, self._n = rest, rest_records

    # --- attachments and metadata ---------------------------------------------
    @holding
    def attachment(self, name: str, media_type: str, data: bytes, log_time: int,
                   create_time: int = 0) -> None:
        """Attach a file (outside the chunks), with its CRC-32."""
        fields = (struct.pack("<QQ", log_time, create_time) + _string(name) + _string(media_type)
                  + struct.pack("<Q", len(data)) + data)
        record = _record(ATTACHMENT, fields + struct.pack("<I", zlib.crc32(fields)))
        start = self._emit(record)
        self._attachments += 1
        self._attachment_indexes.append(_record(ATTACHMENT_INDEX, struct.pack(
            "<QQQQQ", start, len(record), log_time, create_time, len(data))
            + _string(name) + _string(media_type)))

    @holding
    def metadata(self, name: str, values: dict[str, str]) -> None:
        """A named map of strings (outside the chunks)."""
        record = _record(METADATA, _string(name) + _string_map(values))
        start = self._emit(record)
        self._metadata += 1
        self._metadata_indexes.append(_record(METADATA_INDEX, struct.pack("<QQ", start, len(record))
                                              + _string(name)))

    # --- the end ----------------------------------------------------------------
    @holding
    def finish(self) -> None:
        """Write the last chunk, the data end, the summary section and the footer."""
        self._write_chunk()
        self._emit(_record(DATA_END, struct.pack("<I", 0)))
        summary_start = self._offset
        counts = b"".join(struct.pack("<HQ", c, n) for c, n in self._counts.items())
        statistics = _record(STATISTICS, struct.pack(
            "<QHIIIIQQI", sum(self._counts.values()), len(self._schemas), len(self._channels),
            self._attachments, self._metadata, len(self._chunk_indexes),
            self._first or 0, self._last or 0, len(counts)) + counts)
        summary = bytearray()
        groups = []
        for opcode, records in ((SCHEMA, self._schemas), (CHANNEL, self._channels),
                                (STATISTICS, [statistics]), (CHUNK_INDEX, self._chunk_indexes),
                                (ATTACHMENT_INDEX, self._attachment_indexes),
                                (METADATA_INDEX, self._metadata_indexes)):
            if records:
                data = b"".join(records)
                groups.append((opcode, summary_start + len(summary), len(data)))
                summary += data
        offsets_start = summary_start + len(summary)
        for opcode, start, length in groups:
            summary += _record(SUMMARY_OFFSET, struct.pack("<BQQ", opcode, start, length))
        summary += _RECORD.pack(FOOTER, 20) + struct.pack("<QQ", summary_start, offsets_start)
        summary += struct.pack("<I", zlib.crc32(summary)) + MAGIC
        self._emit(bytes(summary))
