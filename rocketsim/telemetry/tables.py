"""A run's state messages as tables: flat rows, columns, CSV and Parquet files.

A state message becomes one row: vectors by component (``position_x``,
``attitude_w``...), the orbit as ``orbit_*``, other values as they are. Columns
keep every digit of the floats (``repr``); a value absent from a message is
empty (CSV) or null (Parquet).
"""

from __future__ import annotations

import json
from pathlib import Path

from rocketsim.extras import needs
from rocketsim.telemetry.reader import read_run, states

# components of the vector fields of a state message, in their order
_AXES = {"position": "xyz", "velocity": "xyz", "body_rates": "xyz", "attitude": "wxyz"}


def flat_row(message: dict, vectors: set | None = None) -> dict:
    """A state message as one flat row: vectors by component (``position_x``,
    ``attitude_w``...), the orbit as ``orbit_*``, other values as they are.
    ``vectors``: a set the vectors' component columns are added to."""
    row = {}
    for key, value in message.items():
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


def export(path: str | Path, out_dir: str | Path, kind: str = "csv") -> list[Path]:
    """Write one table per body (``<body>.csv`` or ``.parquet``) and ``events.csv``
    into ``out_dir``; return the files written. Floats keep every digit."""
    out_dir = Path(out_dir)
    if kind == "parquet":
        needs("parquet", "the Parquet export", "pyarrow")
        import pyarrow
        import pyarrow.parquet
    out_dir.mkdir(parents=True, exist_ok=True)
    run = read_run(path)
    written = []
    for body in run.bodies:
        columns = table(path, body)
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
    _write_csv(events, {"t": [e["t"] for e in run.events], "body": [e["body"] for e in run.events],
                        "name": [e["name"] for e in run.events],
                        "figures": [json.dumps(e["figures"]) for e in run.events]})
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
