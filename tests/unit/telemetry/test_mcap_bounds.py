"""A small crafted MCAP cannot demand large work: a 17 KB file whose one chunk inflates
to 512 MiB of zeros (zstd packs zeros 32 000 : 1) is refused or summarised
within the fuzz harness's hang watchdog, its resident memory rising by less
than half the inflated size (matplotlib's first import for the plot included),
by every command and call that reads a run.

Three bombs: the chunk declaring its 512 MiB honestly (beyond the reader's
1000 : 1 and 256 MiB), declaring 1000 bytes while its zstd frame claims
512 MiB, and the same cut short inside the chunk (read record by record).
A Hypothesis property checks that any chunk the reader accepts decompresses to
no more than it declares, within the ratio.
"""

from __future__ import annotations

import io
import struct
import zlib

import pytest
import zstandard
from hypothesis import given, settings, strategies as st

from mcap.data_stream import RecordBuilder
from mcap.records import Chunk
from mcap.stream_reader import get_chunk_data_stream

import rocketsim
from rocketsim.telemetry.mcap_stream import McapStream
from rocketsim.telemetry.reader import MAX_CHUNK, MAX_RATIO, chunk_problem, read_run
from tests.fuzz.harness import PEAKS, bounded, examples, invoke

INFLATED = 512 << 20


@pytest.fixture(scope="module")
def frame() -> bytes:
    """512 MiB of zeros as one zstd frame (16 KB)."""
    compressor = zstandard.ZstdCompressor(level=3).compressobj(size=INFLATED)
    zeros = bytes(1 << 20)
    return b"".join(compressor.compress(zeros) for _ in range(INFLATED >> 20)) + compressor.flush()


class _Frame:
    """Stands for the writer's compressor: every chunk's data is ``frame``."""

    def __init__(self, frame: bytes):
        self.frame = frame

    def compress(self, data) -> bytes:
        return self.frame


def _records(data: bytes):
    at = 8
    while at + 9 <= len(data):
        opcode, length = struct.unpack_from("<BQ", data, at)
        yield opcode, at, length
        at += 9 + length


def bomb(frame: bytes, declared: int) -> bytes:
    """A run file of one state message whose chunk's data is ``frame``, declaring
    ``declared`` uncompressed bytes (in the chunk and in its index; the summary's CRC
    made good)."""
    buffer = io.BytesIO()
    mcap = McapStream(buffer)
    mcap._compressor = _Frame(frame)
    channel = mcap.channel("/probe/state", "json", mcap.schema("state", "jsonschema", b"{}"))
    mcap.message(channel, 0, 0, b'{"t": 0}')
    mcap.metadata("rocketsim", {"scenario": "bomb"})
    mcap.finish()
    data = bytearray(buffer.getvalue())
    footer = None
    for opcode, at, length in _records(bytes(data)):
        if opcode == 0x06:
            struct.pack_into("<Q", data, at + 9 + 16, declared)
        elif opcode == 0x08:
            struct.pack_into("<Q", data, at + 9 + length - 8, declared)
        elif opcode == 0x02:
            footer = at
    summary_start = struct.unpack_from("<Q", data, footer + 9)[0]
    struct.pack_into("<I", data, footer + 9 + 16, zlib.crc32(data[summary_start:footer + 9 + 16]))
    return bytes(data)


def _files(frame: bytes, folder) -> dict:
    honest, lying = bomb(frame, INFLATED), bomb(frame, 1000)
    files = {"declared": honest, "lying": lying, "cut": lying[:len(lying) * 2 // 3]}
    paths = {}
    for name, data in files.items():
        paths[name] = folder / f"{name}.mcap"
        paths[name].write_bytes(data)
    return paths


@pytest.mark.parametrize("kind", ["declared", "lying", "cut"])
def test_a_17_kb_bomb_is_refused_or_summarised_in_bounded_memory(kind, frame, tmp_path):
    path = _files(frame, tmp_path)[kind]
    assert path.stat().st_size < 18_000
    with bounded("bomb"):
        status, output = invoke("replay", path)
        run = read_run(path)
        rocketsim.open_run(path)
        export, _ = invoke("replay", path, "--export", "csv", tmp_path / "tables", "--plot", tmp_path / "p.png")
    assert status == 2 and "damaged" in output, output
    assert "claims" in run.problem or "cut short" in run.problem, run.problem
    assert export == 2
    if PEAKS.get("bomb") is not None:       # where /proc lets the harness measure it
        assert PEAKS["bomb"] < INFLATED // 2, PEAKS["bomb"]     # the plot's first imports included


@settings(max_examples=examples(0.3), deadline=None, derandomize=True)
@given(size=st.integers(0, 1 << 22), ratio=st.sampled_from([1, 10, 999, 1000, 1001, 40_000]),
       content_size=st.booleans(), shrink=st.integers(0, 2))
def test_an_accepted_chunk_inflates_no_more_than_it_declares(size, ratio, content_size, shrink):
    """A frame of ``size`` zero bytes, declared as ``size >> shrink`` (a lie when shrunk),
    followed by zero bytes up to ``size / ratio`` compressed bytes, written as a chunk
    record by the mcap library: if the reader accepts the chunk, the mcap library's
    own decompression of it yields no more than the declared size, which is within
    the ratio and :data:`MAX_CHUNK`."""
    frame = zstandard.ZstdCompressor(level=1, write_content_size=content_size).compress(bytes(size))
    declared = size >> shrink
    chunk = Chunk(compression="zstd", data=frame + bytes(max(0, size // ratio - len(frame))),
                  message_start_time=0, message_end_time=0, uncompressed_crc=0,
                  uncompressed_size=declared)
    builder = RecordBuilder()
    chunk.write(builder)
    record = builder.end()
    if chunk_problem(record[9:9 + 64], len(record) - 9) is not None:
        return
    assert declared <= min(MAX_RATIO * max(len(chunk.data), 1), MAX_CHUNK)
    try:
        stream, length = get_chunk_data_stream(chunk)
    except zstandard.ZstdError:
        return                              # refused by zstd itself: no work done
    assert length <= declared
