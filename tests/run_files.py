"""A scenario folder written once per test module (for module-scoped flights), and run
files copied with edits (damaged or crafted runs)."""

import textwrap
from pathlib import Path

from mcap.reader import make_reader
from mcap.writer import CompressionType, Writer

from tests.conftest import MISSION, VEHICLE


def write_scenario(folder: Path, program: str, duration: str) -> Path:
    """The conftest coasting probe with ``program``, in ``folder``; returns the scenario path."""
    (folder / "vehicle.yaml").write_text(VEHICLE)
    (folder / "mission.yaml").write_text(MISSION.format(duration=duration))
    (folder / "program.py").write_text(textwrap.dedent(program))
    path = folder / "scenario.yaml"
    path.write_text("name: test\nvehicle: vehicle.yaml\nmission: mission.yaml\nprogram: program.py\n")
    return path


def rewrite_run(source: Path, target: Path, change=None, attachments: dict[str, bytes] | None = None,
                metadata: dict[str, dict] | None = None) -> Path:
    """Copy an MCAP record for record into ``target``: ``change(index, topic, data)`` may
    edit a message's bytes, ``attachments`` (if given) replace the attachments, and
    ``metadata`` updates the metadata records by name."""
    with open(source, "rb") as stream, open(target, "wb") as sink:
        reader = make_reader(stream)
        writer = Writer(sink, compression=CompressionType.ZSTD)
        writer.start()
        summary = reader.get_summary()
        schemas = {i: writer.register_schema(s.name, s.encoding, s.data) for i, s in summary.schemas.items()}
        channels = {i: writer.register_channel(c.topic, c.message_encoding, schemas[c.schema_id])
                    for i, c in summary.channels.items()}
        for index, (_, channel, message) in enumerate(reader.iter_messages(log_time_order=False)):
            data = bytes(message.data)
            writer.add_message(channels[message.channel_id], message.log_time,
                               data if change is None else change(index, channel.topic, data),
                               message.publish_time)
        if attachments is None:
            attachments = {a.name: a.data for a in reader.iter_attachments()}
        for name, data in attachments.items():
            writer.add_attachment(0, 0, name, "application/octet-stream", data)
        records = {m.name: dict(m.metadata) for m in reader.iter_metadata()}
        for name, values in (metadata or {}).items():
            records[name] = {**records.get(name, {}), **values}
        for name, values in records.items():
            writer.add_metadata(name, values)
        writer.finish()
    return target
