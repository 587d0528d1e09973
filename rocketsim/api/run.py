"""A flown run, in memory or read from its MCAP file: summary, events, tables, plot.

:class:`Run` is what :func:`rocketsim.fly` returns and :func:`open_run` reads back
from a file (executing nothing: the program a file carries is an attachment like
any other). The two are the same run and compare equal: the same metadata,
summary, events, log lines and, for every body, the same table, every number
bit for bit.

A body's :meth:`BodyRun.table` is a pandas DataFrame indexed by mission time
(``t_s``, rounded to the microsecond: ``table.loc[23.9]`` finds the sample at
23.9 s), a row per state sample, with the columns of the CSV export
(:mod:`rocketsim.telemetry.tables`), named with their SI unit (``altitude_m``,
``velocity_x_m_s``, ``dynamic_pressure_Pa``; angles end in ``_deg``, ratios and
counts carry none: :data:`rocketsim.telemetry.names.COLUMNS` says what each is);
``table(units=False)`` names them as the state message's fields, flattened.
A value JSON cannot hold (NaN, an infinity: a throttle with no engine running,
an unbound orbit's period) is NaN.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from rocketsim.api.samples import Samples
from rocketsim.argument_checks import file_path
from rocketsim.telemetry.names import column_name, mission_time
from rocketsim.telemetry.reader import RunFile, read_run, states
from rocketsim.telemetry.tables import event_rows

class BodyRun:
    """One body of a run: its samples, and its part of the summary."""

    def __init__(self, run: "Run", name: str, samples: Samples):
        self.run = run
        self.name = name
        self.samples = samples

    def table(self, units: bool = True):
        """The body's samples as a pandas DataFrame indexed by mission time (see the module)."""
        import pandas as pd
        columns = self.samples.columns()
        t = mission_time(columns.pop("t", np.empty(0)))
        return pd.DataFrame({column_name(k) if units else k: v for k, v in columns.items()},
                            index=pd.Index(t, name="t_s" if units else "t"))

    @property
    def _summary(self) -> dict:
        return ((self.run.summary or {}).get("bodies") or {}).get(self.name, {})

    @property
    def final(self) -> dict | None:
        """The final state of the summary (``time_s``, ``altitude_m``, ``inertial_speed_m_s``,
        ``surface_speed_m_s``...)."""
        return self._summary.get("final")

    @property
    def orbit(self) -> dict | None:
        """The osculating orbit of the final state, with its ``central_body`` (None: the body
        is not in orbit: its periapsis is below the central body's surface, or it landed)."""
        return self._summary.get("orbit")

    @property
    def flight(self) -> dict | None:
        """A body not in orbit: its apogee above the ground, largest speed over the ground,
        Mach, q and g, rail exit and landing (:mod:`rocketsim.sim.summary`; None: in orbit)."""
        return self._summary.get("flight")

    @property
    def touchdown(self) -> dict | None:
        """The first ground contact's figures (None: the body did not touch down)."""
        return self._summary.get("touchdown")

    @property
    def events(self):
        """The body's events (a slice of :attr:`Run.events`)."""
        events = self.run.events
        return events[events["body"] == self.name].reset_index(drop=True)

    def __repr__(self) -> str:
        return f"<body {self.name!r} of {self.run!r}: {len(self.samples)} samples>"


class Run:
    """One flight: :attr:`summary`, :attr:`events`, :attr:`bodies` (by name), :meth:`plot`.

    ``file`` is what a reader of the run's file gets (:class:`~rocketsim.telemetry.reader.RunFile`;
    for a flight in memory, the same made without a file) and ``samples`` each
    body's samples."""

    def __init__(self, file: RunFile, samples: dict[str, Samples]):
        self.file = file
        self.bodies = {name: BodyRun(self, name, samples[name]) for name in samples}

    @property
    def path(self) -> Path | None:
        """The MCAP file (None: a run kept in memory)."""
        return None if self.file.path.name == "<memory>" else self.file.path

    @property
    def summary(self) -> dict | None:
        """The flight summary (None: the flight ended in an error before it)."""
        return self.file.summary

    @property
    def metadata(self) -> dict[str, dict[str, str]]:
        return self.file.metadata

    @property
    def logs(self) -> list[dict]:
        """The program's log lines (foxglove.Log messages with ``t`` and ``body``)."""
        return self.file.logs

    @property
    def events(self):
        """Every event as a pandas DataFrame: ``t_s`` (rounded, as a table's), ``body``,
        ``name`` and a column per figure (SI, as the summary names them; a vector by
        component; NaN or None where an event has no such figure): ``events.csv``'s columns
        (:func:`rocketsim.telemetry.tables.event_rows`)."""
        import pandas as pd
        return pd.DataFrame(event_rows(self.file.events))

    @property
    def outcome(self) -> str:
        """``ok``, or the error that ended the flight."""
        outcome = self.file.metadata.get("outcome", {})
        return outcome.get("error", outcome.get("status", "unknown"))

    def plot(self, path: str | Path | None = None):
        """Draw the run (altitude, speed, q, acceleration, throttle, Mach, attitude, ground
        track: :func:`rocketsim.plots.run`) to the PNG ``path`` and return the path;
        without one, return the picture, which a notebook shows inline."""
        from rocketsim.plots import run as plot_run
        return plot_run(self, path)

    def __eq__(self, other) -> bool:
        if not isinstance(other, Run):
            return NotImplemented
        def record(file: RunFile) -> tuple:
            return (file.metadata, file.attachments, json.dumps(file.summary), file.events, file.logs,
                    file.errors, json.dumps(file.final), file.problem)

        if record(self.file) != record(other.file) or list(self.bodies) != list(other.bodies):
            return False
        return all(same_table(self.bodies[b].table(), other.bodies[b].table()) for b in self.bodies)

    __hash__ = None

    def __repr__(self) -> str:
        info = self.file.metadata.get("rocketsim", {})
        end = (self.file.end_ns - self.file.start_ns) / 1e9 if self.file.start_ns is not None else 0.0
        where = f"file {self.path}" if self.path else "in memory"
        return (f"<Run {info.get('scenario', '?')!r}: {len(self.bodies)} bodies, {len(self.file.events)} events, "
                f"T+0 .. {end:.1f} s, {self.outcome}, {where}>")


def same_table(a, b) -> bool:
    """Whether two tables hold the same columns, index and values, floats bit for bit
    (every NaN the same)."""
    if list(a.columns) != list(b.columns) or len(a) != len(b):
        return False
    pairs = [(a.index.to_numpy(), b.index.to_numpy())] + [(a[c].to_numpy(), b[c].to_numpy()) for c in a.columns]
    for x, y in pairs:
        if x.dtype != y.dtype:
            return False
        if x.dtype.kind == "f":
            if not np.array_equal(x.view(np.int64), y.view(np.int64)):
                return False
        elif not np.array_equal(x, y):
            return False
    return True


def open_run(path: str | Path) -> Run:
    """The run in the MCAP file ``path``, read without executing anything (a file cut
    short gives what precedes the break: ``run.file.problem`` says why)."""
    file_path(path, "path")
    file = read_run(path)
    samples = {}
    for body in file.bodies:
        samples[body] = Samples()
        for message in states(path, body):
            samples[body].add_message(message)
    return Run(file, samples)
