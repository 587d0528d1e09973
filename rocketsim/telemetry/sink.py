"""What a flight writes its telemetry through: :class:`TelemetrySink`.

The world (:class:`rocketsim.sim.world.World` and the modules it drives) and the
flight around it (:func:`rocketsim.api.telemetry_flight.fly_into`) write a run through
these calls alone, so a run can go to an MCAP file
(:class:`rocketsim.telemetry.writer.TelemetryWriter`) or stay in memory
(:class:`rocketsim.api.recorder.Recorder`) with the same flight. Both declare the
protocol as a base; ``tests/unit/telemetry/test_telemetry_sink.py`` checks that each defines
every call with the protocol's parameters, and that the world calls nothing else.

Times ``t`` are mission times (s); figures are SI. A sample is the numbers of a
body's state message, ``fields(values, int)`` the message they fill
(:func:`rocketsim.sim.sampling.figures`).
"""

from __future__ import annotations

from typing import Protocol, runtime_checkable

import numpy as np


@runtime_checkable
class TelemetrySink(Protocol):
    """The calls a flight writes its telemetry through (a context manager: ``close`` on
    leaving it, on success and on an error alike)."""

    def add_body(self, name: str) -> None:
        """A body that flies from now on: its samples follow."""
        ...

    def sample(self, body: str, values: np.ndarray, fields, leaving: bool = False) -> None:
        """A body's sample (``values`` float64, not changed afterwards); ``leaving``: its last
        in a frame it leaves at this instant (a handover)."""
        ...

    def sample_rows(self, body: str, rows: np.ndarray, fields) -> None:
        """:meth:`sample` of each row of ``rows``, in order (a compiled run's samples)."""
        ...

    def sample_interleaved(self, blocks: list[tuple]) -> None:
        """The samples of several bodies' blocks ``(body, rows, fields, first, every, rank)``,
        row ``j`` of a block at step ``first + j every``, in order of step and then rank."""
        ...

    def event(self, t: float, body: str, name: str, figures: dict) -> None:
        """An event of ``body`` with its figures."""
        ...

    def log(self, t: float, body: str, message: str) -> None:
        """A line a program logged."""
        ...

    def error(self, t: float, message: str) -> None:
        """The error that ended the flight."""
        ...

    def attach(self, name: str, data: bytes, media_type: str = "text/plain") -> None:
        """A file the run carries (the scenario, the files it references, the program)."""
        ...

    def metadata(self, name: str, values: dict[str, str]) -> None:
        """A named map of strings (the run's settings, outcome, summary)."""
        ...

    def close(self) -> None:
        """Finish the run: everything written is kept and readable."""
        ...

    def __enter__(self) -> "TelemetrySink":
        ...

    def __exit__(self, exc_type, exc, traceback) -> None:
        ...
