"""A flight's telemetry kept in memory: what the MCAP writer writes, without a file.

:class:`Recorder` is a :class:`~rocketsim.telemetry.sink.TelemetrySink`, as the MCAP
writer is (:class:`rocketsim.telemetry.writer.TelemetryWriter`), and keeps what
a reader of the file gets back (:class:`rocketsim.telemetry.reader.RunFile`):
events, log lines and errors as the file's JSON decodes them (each message is
encoded as the writer encodes it and decoded again: NaN becomes None, tuples
lists), metadata and attachments as written, and each body's samples as numbers
in columns (:class:`rocketsim.api.samples.Samples`), not one dictionary per
sample. The Foxglove messages drawn from a state (transforms, location fixes,
the Earth's turn) are not kept: they carry nothing the state does not.
"""

from __future__ import annotations

from pathlib import Path

import orjson

from rocketsim.api.samples import Samples
from rocketsim.telemetry import foxglove
from rocketsim.telemetry.reader import RunFile
from rocketsim.telemetry.sink import TelemetrySink
from rocketsim.telemetry.encoding import encode

MEMORY = Path("<memory>")       # the path of a run that has no file


class Recorder(TelemetrySink):
    """The telemetry of one flight, in memory (``program_file`` names the program in
    the log lines, as the writer's does)."""

    def __init__(self, epoch_ns: int, program_file: str = ""):
        self.run = RunFile(MEMORY)
        self.samples: dict[str, Samples] = {}
        self._epoch_ns = epoch_ns
        self._program_file = program_file
        self._finals: dict[str, tuple] = {}      # body -> its last sample (values, fields)

    def _stamp(self, t: float) -> int:
        return self._epoch_ns + round(t * 1e9)

    def add_body(self, name: str) -> None:
        self.samples.setdefault(name, Samples())
        self.run.counts.setdefault(f"/{name}/state", 0)

    def sample(self, body: str, values, fields, leaving: bool = False) -> None:
        """A body's sample: the numbers of its state message (see the writer's;
        ``leaving`` only decides the file's frames, which a run in memory has not)."""
        self.sample_rows(body, values.reshape(1, -1), fields)

    def sample_rows(self, body: str, rows, fields) -> None:
        """:meth:`sample` of each row of ``rows``, in order (of time)."""
        n = len(rows)
        if not n:
            return
        self.samples[body].add_rows(rows, fields)
        self.run.counts[f"/{body}/state"] += n
        # the state's t (rocketsim.stepping.sample_figures), rising from row to row
        first, last = self._stamp(rows.item(0, -2)), self._stamp(rows.item(n - 1, -2))
        self.run.start_ns = first if self.run.start_ns is None else min(self.run.start_ns, first)
        self.run.end_ns = last if self.run.end_ns is None else max(self.run.end_ns, last)
        self._finals[body] = (rows[-1], fields)

    def sample_interleaved(self, blocks: list[tuple]) -> None:
        """:meth:`sample` of each sample of interleaved blocks, in order (see the writer's):
        each body's blocks by step (what a body keeps is in its own order; the run's first
        and last stamps are in no order)."""
        for body, rows, fields, *_ in sorted(blocks, key=lambda block: block[3]):
            self.sample_rows(body, rows, fields)

    def event(self, t: float, body: str, name: str, figures: dict) -> None:
        self.run.events.append(_as_read({"t": t, "body": body, "name": name, "figures": figures}))

    def log(self, t: float, body: str, message: str) -> None:
        stamp = self._stamp(t)
        self.run.logs.append(_as_read(foxglove.log_line(stamp, foxglove.INFO, message, body,
                                                        self._program_file, t, body)))

    def error(self, t: float, message: str) -> None:
        stamp = self._stamp(t)
        self.run.errors.append(_as_read(foxglove.log_line(stamp, foxglove.ERROR, message, "rocketsim",
                                                          "", t, "")))

    def attach(self, name: str, data: bytes, media_type: str = "text/plain") -> None:
        self.run.attachments[name] = data

    def metadata(self, name: str, values: dict[str, str]) -> None:
        self.run.metadata[name] = {k: str(v) for k, v in values.items()}

    def close(self) -> None:
        """Set each body's last state message, as a reader of the file finds it."""
        for body, (values, fields) in self._finals.items():
            self.run.final[body] = _as_read(fields(values.tolist(), int))

    def __enter__(self) -> "Recorder":
        return self

    def __exit__(self, exc_type, exc, traceback) -> None:
        self.close()


def _as_read(message: dict) -> dict:
    """``message`` as a reader of the file decodes it."""
    return orjson.loads(encode(message))
