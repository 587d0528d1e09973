"""A run's state messages as tables: flat rows, columns, CSV and Parquet files.

A state message becomes one row: vectors by component (``position_x``,
``attitude_w``...), the orbit as ``orbit_*``, other values as they are
(:func:`flat_row`). The files name each column with its unit
(:func:`rocketsim.telemetry.names.column_name`: ``t_s``, ``altitude_m``,
``velocity_x_m_s``), the mission time rounded to the microsecond
(:func:`rocketsim.telemetry.names.mission_time`: ``2.3``, not
``2.3000000000000003``); the other floats keep every digit (``repr``); a value
absent from a message is empty (CSV) or null (Parquet). ``events.csv`` has a row
per event: ``t_s``, ``body``, ``name`` and a column per figure (a vector figure by
component, ``delta_v_m_s[0]``), empty where an event has no such figure.
"""

from __future__ import annotations

from pathlib import Path

from rocketsim.argument_checks import file_path, one_of
from rocketsim.extras import needs
from rocketsim.telemetry.names import FORMER_FIELDS, column_name, mission_time
from rocketsim.telemetry.reader import read_run, states

# components of the vector fields of a state message, in their order
_AXES = {"position": "xyz", "velocity": "xyz", "body_rates": "xyz", "attitude": "wxyz"}


def flat_row(message: dict, vectors: set | None = None) -> dict:
    """A state message as one flat row: vectors by component (``position_x``,
    ``attitude_w``...), the orbit as ``orbit_*``, other values as they are.
    ``vectors``: a set the vectors' component columns are added to. A field a file
    written before a rename holds is read under today's name
    (:data:`rocketsim.telemetry.names.FORMER_FIELDS`)."""
    row = {}
    for key, value in message.items():
        key = FORMER_FIELDS.get(key, key)
        if isinstance(value, list):
            axes = _AXES.get(key) or [str(i) for i in range(len(value))]
            row.update({f"{key}_{a}": v for a, v in zip(axes, value)})
            if vectors is not None:
                vectors.update(f"{key}_{a}" for a in axes[:len(value)])
        elif isinstance(value, dict):
            row.update({f"{key}_{k}": v for k, v in value.items() if not isinstance(v, (dict, list))})
        else:
            row[key] = value
    return row


def table(path: str | Path, body: str) -> dict[str, list]:
    """Columns of ``body``'s state messages, flattened by :func:`flat_row`."""
    columns: dict[str, list] = {}
    n = 0
    for message in states(path, body):
        row = flat_row(message)
        for key in row:
            if key not in columns:
                columns[key] = [None] * n
        for key, column in columns.items():
            column.append(row.get(key))
        n += 1
    return columns


def with_units(columns: dict[str, list]) -> dict[str, list]:
    """:func:`table`'s columns as the files name them, the mission time rounded
    (see the module)."""
    return {column_name(key): ([mission_time(v) for v in values] if key == "t" else values)
            for key, values in columns.items()}


def event_rows(events: list[dict]) -> dict[str, list]:
    """The columns of ``events`` (``t``, ``body``, ``name``, ``figures`` each, as a run's
    file holds them): ``t_s`` (rounded, see the module), ``body``, ``name`` and one per
    figure, in the order they first appear (a list by component, ``name[i]``), None
    where an event has no such figure."""
    rows = []
    for event in events:
        row = {"t_s": mission_time(event["t"]), "body": event["body"], "name": event["name"]}
        for key, value in (event.get("figures") or {}).items():
            if isinstance(value, list):
                row.update({f"{key}[{i}]": v for i, v in enumerate(value)})
            else:
                row[key] = value
        rows.append(row)
    names = list(dict.fromkeys(["t_s", "body", "name", *(k for r in rows for k in r)]))
    return {name: [r.get(name) for r in rows] for name in names}


def export(path: str | Path, out_dir: str | Path, kind: str = "csv") -> list[Path]:
    """Write one table per body (``<body>.csv`` or ``.parquet``) and ``events.csv``
    into ``out_dir``; return the files written (see the module)."""
    file_path(path, "path")
    file_path(out_dir, "out_dir")
    one_of(kind, ("csv", "parquet"), "kind")
    out_dir = Path(out_dir)
    if kind == "parquet":
        needs("parquet", "the Parquet export", "pyarrow")
        import pyarrow
        import pyarrow.parquet
    out_dir.mkdir(parents=True, exist_ok=True)
    run = read_run(path)
    written = []
    for body in run.bodies:
        columns = with_units(table(path, body))
        target = out_dir / f"{body}.{kind}"
        if kind == "csv":
            _write_csv(target, columns)
        else:
            # a column with no value in this run (e.g. the throttle of an engine group
            # that never ran) is float, not parquet's null type
            pyarrow.parquet.write_table(pyarrow.table({
                key: pyarrow.array(values, type=pyarrow.float64()) if all(v is None for v in values)
                else values for key, values in columns.items()}), target)
        written.append(target)
    events = out_dir / "events.csv"
    _write_csv(events, event_rows(run.events))
    written.append(events)
    return written


def _write_csv(target: Path, columns: dict[str, list]) -> None:
    import csv
    names = list(columns)
    with open(target, "w", newline="") as stream:
        out = csv.writer(stream)
        out.writerow(names)
        for row in zip(*(columns[k] for k in names)):
            out.writerow(["" if v is None else repr(v) if isinstance(v, float) else v for v in row])
