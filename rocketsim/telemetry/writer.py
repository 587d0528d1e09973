"""Stream telemetry to an MCAP file as the flight goes.

The file is chunked (zstd) so memory stays bounded however long the flight;
messages are JSON with registered JSON schemas. Timestamps are the mission
epoch (UTC, ns since 1970) plus mission time, so Foxglove shows real dates and
the same run always writes the same bytes: nothing here reads the wall clock.

The scenario and every file it references travel in the file as attachments,
so a run can be shared as one file. :meth:`TelemetryWriter.close` writes the
summary and index; callers use the writer as a context manager so the file is
finished on success, on a program error and on Ctrl-C alike.
"""

from __future__ import annotations

import json
from pathlib import Path

from mcap.writer import CompressionType, Writer

from rocketsim import __version__
from rocketsim.telemetry.schemas import BODY_STATE, EVENT, LOG, schema_bytes

PROFILE = ""
LIBRARY = f"rocketsim {__version__}"


def encode(message: dict) -> bytes:
    """JSON bytes of a message: compact, keys in a fixed order, floats by repr."""
    return json.dumps(message, separators=(",", ":"), allow_nan=True).encode()


class TelemetryWriter:
    """One MCAP telemetry file: a state channel per body, events and logs."""

    def __init__(self, path: str | Path, epoch_ns: int):
        self.path = Path(path)
        self._file = open(self.path, "wb")
        self._writer = Writer(self._file, compression=CompressionType.ZSTD)
        self._writer.start(profile=PROFILE, library=LIBRARY)
        self._epoch_ns = epoch_ns
        self._schemas = {}
        self._channels: dict[str, int] = {}
        self._sequence = 0
        self._closed = False
        self._events = self._channel("/events", EVENT)
        self._logs = self._channel("/log", LOG)

    def _channel(self, topic: str, schema: dict) -> int:
        title = schema["title"]
        if title not in self._schemas:
            self._schemas[title] = self._writer.register_schema(
                name=title, encoding="jsonschema", data=schema_bytes(schema))
        channel = self._writer.register_channel(
            topic=topic, message_encoding="json", schema_id=self._schemas[title])
        self._channels[topic] = channel
        return channel

    def add_body(self, name: str) -> None:
        """Open the state channel ``/<name>/state`` for a body."""
        self._channel(f"/{name}/state", BODY_STATE)

    def _write(self, channel: int, t: float, message: dict) -> None:
        stamp = self._epoch_ns + round(t * 1e9)
        self._writer.add_message(channel_id=channel, log_time=stamp, publish_time=stamp,
                                 data=encode(message), sequence=self._sequence)
        self._sequence += 1

    def state(self, body: str, message: dict) -> None:
        self._write(self._channels[f"/{body}/state"], message["t"], message)

    def event(self, t: float, body: str, name: str, figures: dict) -> None:
        self._write(self._events, t, {"t": t, "body": body, "name": name, "figures": figures})

    def log(self, t: float, body: str, message: str) -> None:
        self._write(self._logs, t, {"t": t, "body": body, "message": message})

    def attach(self, name: str, data: bytes, media_type: str = "text/plain") -> None:
        """Attach a file (scenario, vehicle, program...) to the log."""
        self._writer.add_attachment(create_time=0, log_time=self._epoch_ns, name=name,
                                    media_type=media_type, data=data)

    def metadata(self, name: str, values: dict[str, str]) -> None:
        self._writer.add_metadata(name=name, data={k: str(v) for k, v in values.items()})

    def close(self) -> None:
        """Write the summary and index and close the file (idempotent)."""
        if self._closed:
            return
        self._closed = True
        try:
            self._writer.finish()
        finally:
            self._file.close()

    def __enter__(self) -> "TelemetryWriter":
        return self

    def __exit__(self, *exc) -> None:
        self.close()
