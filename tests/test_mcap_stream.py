"""The streaming MCAP writer against the ``mcap`` package's readers (the reference).

The file must read back through the indexed reader (summary, chunk and
message indexes, attachment and metadata indexes) and through the streaming
reader with CRC validation (what a truncated file falls back to), message for
message, in log-time order.
"""

import io

from mcap.reader import make_reader
from mcap.stream_reader import StreamReader

from rocketsim.telemetry.mcap_stream import McapStream


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
