"""Read rocketsim telemetry back from an MCAP file."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Iterator

from mcap.reader import make_reader


def messages(path: str | Path, topics: list[str] | None = None) -> Iterator[tuple[str, int, dict]]:
    """Yield ``(topic, log_time_ns, message)`` in log-time order."""
    with open(path, "rb") as stream:
        reader = make_reader(stream)
        for _schema, channel, message in reader.iter_messages(topics=topics):
            yield channel.topic, message.log_time, json.loads(message.data)


def raw_messages(path: str | Path) -> list[tuple[str, int, bytes]]:
    """Every message as ``(topic, log_time_ns, data bytes)``, in file order."""
    with open(path, "rb") as stream:
        reader = make_reader(stream)
        return [(channel.topic, message.log_time, bytes(message.data))
                for _schema, channel, message in reader.iter_messages(log_time_order=False)]


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
