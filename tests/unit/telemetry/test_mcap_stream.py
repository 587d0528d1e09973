"""The streaming MCAP writer against the ``mcap`` package's readers (the reference).

The file must read back through the indexed reader (summary, chunk and
message indexes, attachment and metadata indexes) and through the streaming
reader with CRC validation (what a truncated file falls back to), message for
message, in log-time order.
"""

import collections
import io
import random
import signal
import subprocess
import sys
from pathlib import Path

from mcap.reader import make_reader
from mcap.records import Attachment, Channel, Chunk, DataEnd, Message, Metadata
from mcap.stream_reader import StreamReader

from rocketsim.telemetry import mcap_stream
from rocketsim.telemetry.mcap_stream import McapStream

ROOT = Path(__file__).resolve().parents[3]


def _write(chunk_size):
    out = io.BytesIO()
    writer = McapStream(out, "", "test", chunk_size=chunk_size)
    schema = writer.schema("demo", "jsonschema", b'{"type": "object"}')
    a = writer.channel("/a", "json", schema)
    writer.attachment("scenario.yaml", "application/yaml", b"name: x\n", log_time=5)
    sent = []
    b = None
    for k in range(500):
        if k == 3:
            b = writer.channel("/b", "json", schema)        # registered mid-file
        channel = b if k % 3 == 0 and b is not None else a
        data = b'{"k": %d}' % k
        writer.message(channel, 1_000 + 10 * k, 1_000 + 10 * k, data, sequence=k)
        sent.append((channel, 1_000 + 10 * k, data))
    writer.metadata("rocketsim", {"seed": "7"})
    writer.finish()
    return out.getvalue(), sent


def test_indexed_reading_matches_what_was_written():
    data, sent = _write(chunk_size=2_000)            # many chunks
    reader = make_reader(io.BytesIO(data))
    summary = reader.get_summary()
    assert summary.statistics.message_count == len(sent)
    assert summary.statistics.chunk_count == len(summary.chunk_indexes) > 5
    assert summary.statistics.message_start_time == 1_000
    assert summary.statistics.message_end_time == 1_000 + 10 * 499
    assert {c.topic for c in summary.channels.values()} == {"/a", "/b"}
    got = [(c.id, m.log_time, m.data) for _, c, m in reader.iter_messages()]
    assert got == sent
    only_b = [m.data for _, _, m in reader.iter_messages(topics=["/b"])]
    assert only_b == [d for c, _, d in sent if c == 2] != []
    attachment, = reader.iter_attachments()
    assert (attachment.name, attachment.data, attachment.log_time) == ("scenario.yaml", b"name: x\n", 5)
    metadata, = reader.iter_metadata()
    assert metadata.metadata == {"seed": "7"}


def test_streaming_reading_validates_every_crc():
    data, sent = _write(chunk_size=1_000_000)        # one chunk
    records = list(StreamReader(io.BytesIO(data), validate_crcs=True).records)
    names = [type(r).__name__ for r in records]
    assert names[0] == "Header" and names[-1] == "Footer"
    messages = [(r.channel_id, r.log_time, r.data) for r in records if type(r).__name__ == "Message"]
    assert messages == sent


# --- a Ctrl-C at any moment -------------------------------------------------------
def _session(out, tracer=None):
    """A short writing session (schemas, channels, messages over several chunks, an
    attachment, metadata), traced by ``tracer`` once the writer is made; returns the
    messages it sent as (channel, log time, data), the one being sent when a
    KeyboardInterrupt came included."""
    writer = McapStream(out, "", "test", chunk_size=600)
    sent = []
    sys.settrace(tracer)
    try:
        schema = writer.schema("demo", "jsonschema", b'{"type": "object"}')
        a = writer.channel("/a", "json", schema)
        writer.attachment("scenario.yaml", "application/yaml", b"name: x\n", log_time=5)
        b = None
        for k in range(60):
            if k == 20:
                b = writer.channel("/b", "json", schema)
            channel = b if k % 3 == 0 and b is not None else a
            data = b'{"k": %d, "text": "%s"}' % (k, b"x" * (k % 7))
            sent.append((channel, 1_000 + 10 * k, data))
            writer.message(channel, 1_000 + 10 * k, 1_000 + 10 * k, data, sequence=k)
        writer.metadata("rocketsim", {"seed": "7"})
    except KeyboardInterrupt:
        pass
    finally:
        try:
            writer.finish()          # as TelemetryWriter.close does, on the way out
        finally:
            sys.settrace(None)
    return sent


class InterruptAt:
    """A tracer that sends this process SIGINT at the ``n``-th bytecode run in the
    functions of the files ``under`` a folder (default: ``mcap_stream``'s file alone):
    the handler raises at the next moment Python runs handlers, as a Ctrl-C's does."""

    def __init__(self, n, under=mcap_stream.__file__):
        self.n, self.under = n, under

    def __call__(self, frame, event, arg):
        if event == "call":
            if not frame.f_code.co_filename.startswith(self.under):
                return None
            frame.f_trace_opcodes = True
            return self
        if event == "opcode":
            self.n -= 1
            if self.n == 0:
                signal.raise_signal(signal.SIGINT)
        return self


def _opcodes_of_a_session() -> int:
    count = InterruptAt(-1)
    _session(io.BytesIO(), count)
    return -1 - count.n


def records_agreeing(data: bytes) -> list:
    """The messages of the MCAP ``data`` as (channel, sequence, log time, data), once
    checked that its summary agrees with the records on disk, read by both of the
    ``mcap`` package's readers: the same messages through the chunk indexes as in the
    stream (CRCs checked), the statistics counting them, every chunk, channel,
    attachment and metadata record indexed."""
    summary = make_reader(io.BytesIO(data)).get_summary()
    assert summary is not None
    records = list(StreamReader(io.BytesIO(data), validate_crcs=True).records)
    records = records[:[type(r) for r in records].index(DataEnd)]         # the data section
    streamed = [(r.channel_id, r.sequence, r.log_time, r.data) for r in records if isinstance(r, Message)]
    indexed = [(c.id, m.sequence, m.log_time, m.data)
               for _, c, m in make_reader(io.BytesIO(data)).iter_messages(log_time_order=False)]
    assert indexed == streamed
    statistics = summary.statistics
    assert statistics.message_count == len(streamed)
    counts = collections.Counter(c for c, _, _, _ in streamed)
    assert statistics.channel_message_counts == {c: counts[c] for c in summary.channels}
    chunks = [r for r in StreamReader(io.BytesIO(data), emit_chunks=True).records if isinstance(r, Chunk)]
    assert statistics.chunk_count == len(summary.chunk_indexes) == len(chunks)
    assert statistics.channel_count == len(summary.channels) == sum(isinstance(r, Channel) for r in records)
    if streamed:
        times = [t for _, _, t, _ in streamed]
        assert (statistics.message_start_time, statistics.message_end_time) == (min(times), max(times))
    assert len(summary.attachment_indexes) == sum(isinstance(r, Attachment) for r in records)
    assert len(summary.metadata_indexes) == sum(isinstance(r, Metadata) for r in records)
    return streamed


def in_a_fresh_process(target: str, *args: str, timeout: float = 300) -> None:
    """Call ``target`` ("module:function") with ``args`` in a fresh Python process at the
    repository's top, bounded by ``timeout`` seconds; fail with its stderr if it fails.

    The tests that trace every bytecode (:class:`InterruptAt`) run so: CPython 3.11's
    opcode tracing was seen to spin for ever on one line (a ``with`` of
    ``held_signals``, a call of the writer) in a test worker that had run hundreds of
    other tests, never in a fresh process; bounded, a hang fails the test, not the run."""
    module, function = target.split(":")
    done = subprocess.run(
        [sys.executable, "-c", "import importlib, sys; "
         f"getattr(importlib.import_module({module!r}), {function!r})(*sys.argv[1:])", *args],
        cwd=ROOT, capture_output=True, text=True, timeout=timeout)
    assert done.returncode == 0, done.stderr[-4000:]


def interrupted_sessions() -> None:
    """The sessions of the test below, each interrupted at one of 250 moments."""
    total = _opcodes_of_a_session()
    whole = _session(io.BytesIO())
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        for n in random.Random(7).sample(range(1, total + 1), 250):
            out = io.BytesIO()
            try:
                sent = _session(out, InterruptAt(n))
            except KeyboardInterrupt:
                sent = whole    # the Ctrl-C came in finish: every message was sent
            written = [(c, t, d) for c, _, t, d in records_agreeing(out.getvalue())]
            assert written == sent[:len(written)] and len(written) >= len(sent) - 1
    finally:
        signal.signal(signal.SIGINT, previous)


def test_a_ctrl_c_at_any_moment_leaves_a_file_whose_summary_agrees_with_its_records():
    """SIGINT sent at 250 moments drawn over every bytecode the writer runs in a
    session (its file operations and their bookkeeping alike): each file finishes
    with a summary that indexes exactly the records on disk, and loses at most the
    message being written (in a fresh process: :func:`in_a_fresh_process`)."""
    in_a_fresh_process("tests.unit.telemetry.test_mcap_stream:interrupted_sessions")
