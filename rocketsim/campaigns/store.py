"""The campaign directory: what a campaign wrote, as it went.

::

    DIR/campaign.yaml      the campaign, its scenario an absolute path
    DIR/meta.json          name, seed, runs, scenario, dispersions, target, outputs, version,
                           insertion (tolerances)
    DIR/inputs.parquet     every run's inputs, drawn and written in blocks of
                           :data:`INPUTS_BLOCK` runs by a thread of its own
                           (:class:`InputsWriter`) while the first runs fly
    DIR/results.parquet    a row per finished run (ok, error or timeout), sorted by run
    DIR/results/part-*.parquet   rows not yet consolidated into results.parquet
    DIR/runs/run-000042.mcap     telemetry kept by the campaign's retention

Rows are written as runs finish: the rows that arrived are written as a new
part file at least every :data:`FLUSH_S` seconds (each file is written to a
temporary name and renamed, so a file is whole or absent), and the parts are
consolidated into ``results.parquet`` (again written whole and renamed, then
the parts it holds removed) every :data:`CONSOLIDATE_S` seconds, at the end, on
Ctrl-C and when a campaign is resumed. A crash of the client loses the runs in
flight and the rows of the last second; ``results.parquet`` then lacks at most
the rows of the last :data:`CONSOLIDATE_S` seconds, which the parts hold until
``--resume`` consolidates them (:func:`read_results` reads both).

``inputs.parquet`` too is whole or absent (renamed when its last block is
written): a campaign of millions of runs starts flying within seconds and its
inputs take the memory of one block, whatever the number of runs (a campaign of
one block writes it before anything flies). A campaign stopped before its
inputs were all written has none, and ``--resume`` writes them again (they
derive from the campaign alone).
"""

from __future__ import annotations

import json
import math
import os
import threading
import time
from pathlib import Path

import numpy as np

from rocketsim.errors import ArgumentError, InputError
from rocketsim.scenario.yaml_source import read_yaml

FLUSH_S = 1.0           # s between part files (rows waiting)
CONSOLIDATE_S = 10.0    # s between rewrites of results.parquet
LEADING = ["run", "status", "error", "wall_time_s", "outcome"]
STRINGS = {"status", "error", "outcome"}
INPUTS_BLOCK = 4096     # runs of inputs drawn and written at a time


def frame(tables):
    """One results table from row tables (DataFrames) or rows (dicts): one row per run (a
    later row of a run replaces an earlier one), sorted by run, the leading columns first
    and the others in name order; ``run`` int64, a column holding any string a string
    column (None where missing), every other float64 (NaN where missing)."""
    import pandas as pd
    tables = [t if isinstance(t, pd.DataFrame) else pd.DataFrame(t) for t in tables]
    tables = [t for t in tables if len(t)]
    if not tables:
        return pd.DataFrame({name: pd.Series(dtype=np.int64 if name == "run" else
                                             object if name in STRINGS else np.float64)
                             for name in LEADING})
    strings = set(STRINGS)
    for table in tables:
        strings |= {name for name, dtype in table.dtypes.items()
                    if dtype == object or pd.api.types.is_string_dtype(dtype)}
    combined = pd.concat(tables, ignore_index=True, sort=False) if len(tables) > 1 else tables[0]
    combined = combined.drop_duplicates("run", keep="last").sort_values("run", kind="stable")
    found = dict(combined.items())
    names = [n for n in LEADING if n in found] + sorted(set(found) - set(LEADING))
    columns = {}
    for name in names:
        values = found[name]
        if name == "run":
            columns[name] = values.to_numpy(dtype=np.int64)
        elif name in strings:
            columns[name] = pd.array([None if v is None or (isinstance(v, float) and math.isnan(v))
                                      else str(v) for v in values], dtype=object)
        else:
            columns[name] = values.to_numpy(dtype=np.float64)
    return pd.DataFrame(columns)


def _write(table, path: Path) -> None:
    """``table`` to the Parquet file ``path``, whole or not at all (a temporary name, renamed)."""
    partial = path.with_name(f".{path.name}.partial")
    table.to_parquet(partial, index=False)
    os.replace(partial, path)


def read_results(directory: str | Path):
    """The results of a campaign directory: ``results.parquet`` and any part files not yet
    consolidated into it (after a crash), as one table (:func:`frame`); :class:`InputError`
    naming a file that is not such a table (:func:`_rows`)."""
    return frame([_rows(path) for path in _result_files(Path(directory))])


def _result_files(directory: Path) -> list[Path]:
    whole = directory / "results.parquet"
    return ([whole] if whole.exists() else []) + sorted((directory / "results").glob("part-*.parquet"))


def _rows(path: Path):
    """The rows of the results file ``path``; :class:`InputError` naming it when it is not
    a Parquet table with whole ``run`` numbers and a ``status``."""
    import pandas as pd
    try:
        table = pd.read_parquet(path)
    except Exception as error:          # noqa: BLE001 - pyarrow's errors have no common base
        raise InputError(f"not a readable Parquet file ({type(error).__name__}: {str(error)[:160]})",
                         file=path) from None
    for column in ("run", "status"):
        if column not in table.columns:
            raise InputError("missing column", file=path, field=column)
    if not pd.api.types.is_integer_dtype(table["run"].dtype):
        raise InputError(f"expected whole run numbers, not {table['run'].dtype}", file=path, field="run")
    return table


def set_aside_damaged(directory: Path) -> list[str]:
    """Rename each results file of ``directory`` that :func:`_rows` refuses to
    ``<name>.damaged`` (kept, not read again: its runs are flown again); what was done, a
    line each."""
    said = []
    for path in _result_files(directory):
        try:
            _rows(path)
        except InputError as error:
            aside = path.with_name(path.name + ".damaged")
            os.replace(path, aside)
            said.append(f"{error}: set aside as {aside.name}, its runs are flown again")
    return said


class InputsWriter:
    """Writes every run's inputs (:meth:`rocketsim.campaigns.cases.Plan.inputs_table`) to
    ``path`` in a thread of its own, a Parquet row group per :data:`INPUTS_BLOCK` runs, to
    a temporary name renamed when the last block is written."""

    def __init__(self, plan, path: Path):
        self.plan, self.path = plan, path
        self._partial = path.with_name(f".{path.name}.partial")
        self._stop = threading.Event()
        self._error: BaseException | None = None
        self._thread = threading.Thread(target=self._write, name="rocketsim-inputs", daemon=True)
        self._thread.start()

    def _write(self) -> None:
        import pyarrow as pa
        import pyarrow.parquet as pq
        runs = self.plan.campaign.spec.runs
        try:
            writer = None
            try:
                for first in range(0, runs, INPUTS_BLOCK):
                    if self._stop.is_set():
                        return
                    table = pa.Table.from_pandas(self.plan.inputs_table(first, min(first + INPUTS_BLOCK, runs)),
                                                 preserve_index=False)
                    if writer is None:
                        writer = pq.ParquetWriter(self._partial, table.schema)
                    writer.write_table(table.cast(writer.schema))
            finally:
                if writer is not None:
                    writer.close()
            os.replace(self._partial, self.path)
        except BaseException as error:      # noqa: BLE001 - handed to the thread that waits for it
            self._error = error
        finally:
            if self._partial.exists():
                self._partial.unlink()

    def finish(self) -> None:
        """Wait for the last block; raise what stopped the writing."""
        self._thread.join()
        if self._error is not None:
            error = self._error
            self._error = None
            if isinstance(error, OSError):
                raise InputError(f"cannot write the campaign's inputs: {error.strerror or error}",
                                 file=self.path) from None
            raise error

    def cancel(self) -> None:
        """Stop after the block being written; the inputs file is then absent."""
        self._stop.set()
        self._thread.join()


class Store:
    """A campaign directory being written (see the module)."""

    def __init__(self, directory: str | Path):
        self.dir = Path(directory)
        self.parts = self.dir / "results"
        self.runs = self.dir / "runs"
        self._waiting: list[dict] = []
        self._written: dict[Path, object] = {}     # the part files written, not yet consolidated: their tables
        self._flushed = self._consolidated = time.monotonic()
        self._count = 0
        self.set_aside: list[str] = []      # the damaged results files a resume set aside
        self.inputs: InputsWriter | None = None     # writing inputs.parquet, if it is being written

    # --- starting ----------------------------------------------------------------

    def open(self, campaign, plan, resume: bool) -> set[int]:
        """Start the campaign here (a new or empty directory) or, with ``resume``, go on
        with the same campaign; the runs already finished."""
        import yaml
        resolved = campaign.resolved()
        held = self.dir / "campaign.yaml"
        if held.is_file():
            if not resume:
                raise ArgumentError(f"{self.dir} already holds a campaign: resume it to fly its missing "
                                    "runs, or write to another directory", "resume")
            before = read_yaml(held).data
            now = json.loads(json.dumps(resolved))
            changed = (sorted(k for k in set(before) | set(now) if before.get(k) != now.get(k))
                       if isinstance(before, dict) else ["everything: it is not a mapping"])
            if changed == ["runs"] and now["runs"] > before["runs"] and now["sampling"] != "lhs":
                self._grow(plan, campaign, now)     # the same runs, and more of them
            elif changed:
                why = (f"it has {before['runs']} runs; --runs may only add to a campaign sampled at random "
                       "or on a Sobol design" if changed == ["runs"] else
                       "resume it with its own file, " + str(held))
                raise ArgumentError(f"{self.dir} holds another campaign (its campaign.yaml differs in "
                                    f"{', '.join(changed)}): {why}", "resume")
            self.set_aside = set_aside_damaged(self.dir) + self._rewrite_damaged_plan(campaign, plan)
            self.consolidate()
            return set(read_results(self.dir)["run"].tolist())
        if resume:
            raise ArgumentError(f"{self.dir} holds no campaign to resume", "resume")
        if self.dir.exists() and not self.dir.is_dir():
            raise ArgumentError(f"{self.dir} is a file, not a directory", "directory")
        try:
            self.dir.mkdir(parents=True, exist_ok=True)
            self.parts.mkdir(exist_ok=True)
        except OSError as error:
            raise ArgumentError(f"cannot create {self.dir}: {error.strerror or error}", "directory") from None
        self._write_plan(campaign, plan, ("inputs.parquet", "meta.json"))
        # the campaign file last: a directory holding it holds the rest
        (self.dir / ".campaign.yaml.partial").write_text(yaml.safe_dump(json.loads(json.dumps(resolved)),
                                                                        sort_keys=False))
        os.replace(self.dir / ".campaign.yaml.partial", held)
        return set()

    def _grow(self, plan, campaign, resolved: dict) -> None:
        """Rewrite the directory's campaign, meta.json and inputs for ``campaign``'s larger
        number of runs (the inputs of the runs already there are unchanged: random and
        Sobol draws of run k depend on the seed and k alone)."""
        import yaml
        self._write_plan(campaign, plan, ("inputs.parquet", "meta.json"))
        (self.dir / ".campaign.yaml.partial").write_text(yaml.safe_dump(resolved, sort_keys=False))
        os.replace(self.dir / ".campaign.yaml.partial", self.dir / "campaign.yaml")

    def _write_plan(self, campaign, plan, names) -> None:
        """Write the files ``names`` (``inputs.parquet``, ``meta.json``) that the campaign and
        its plan determine."""
        from rocketsim.version import __version__
        if "inputs.parquet" in names:
            if self.inputs is not None:
                self.inputs.cancel()
            self.inputs = InputsWriter(plan, self.dir / "inputs.parquet")
            if campaign.spec.runs <= INPUTS_BLOCK:      # one block: written before anything flies
                self.inputs_written()
        if "meta.json" in names:
            spec = campaign.spec
            meta = {"name": spec.name, "seed": spec.seed, "runs": spec.runs, "scenario": str(campaign.scenario),
                    "dispersions": [{"name": name, **given.model_dump(mode="json", exclude_none=True)}
                                    for name, given in spec.dispersions.items()],
                    "target": plan.target(), "outputs": list(spec.outputs), "version": __version__,
                    "insertion": None if spec.insertion is None else {
                        "periapsis_m": spec.insertion.periapsis, "apoapsis_m": spec.insertion.apoapsis,
                        "inclination_deg": math.degrees(spec.insertion.inclination)}}
            (self.dir / "meta.json").write_text(json.dumps(meta, indent=1) + "\n")

    def _rewrite_damaged_plan(self, campaign, plan) -> list[str]:
        """On resume: ``inputs.parquet`` or ``meta.json`` missing or unreadable (the campaign
        determines both) set aside as ``<name>.damaged`` and written again; a line each."""
        import pyarrow.parquet as pq
        said = []
        runs = campaign.spec.runs

        def rows(path: Path) -> int:
            return pq.ParquetFile(path).metadata.num_rows

        for name, read, whole in (("inputs.parquet", rows, lambda found: found == runs),
                                  ("meta.json", lambda p: json.loads(p.read_text()),
                                   lambda found: isinstance(found, dict))):
            path = self.dir / name
            if name == "inputs.parquet" and self.inputs is not None:
                continue        # being written for a grown campaign
            try:
                if not whole(read(path)):
                    raise ValueError("not the campaign's table or mapping")
                continue
            except FileNotFoundError:
                said.append(f"{path}: missing, written again from the campaign")
            except Exception as error:      # noqa: BLE001 - pyarrow's and json's errors alike
                os.replace(path, path.with_name(name + ".damaged"))
                said.append(f"{path}: unreadable ({type(error).__name__}), set aside as {name}.damaged "
                            "and written again from the campaign")
            self._write_plan(campaign, plan, (name,))
        return said

    def inputs_written(self, complete: bool = True) -> None:
        """Wait until ``inputs.parquet`` is written (``complete``) or stop writing it; raise
        what stopped the writing."""
        writer, self.inputs = self.inputs, None
        if writer is not None:
            writer.finish() if complete else writer.cancel()

    # --- rows -------------------------------------------------------------------

    def add(self, row: dict, telemetry: bytes | None = None) -> None:
        """One finished run's row (and the MCAP kept of it); written within :data:`FLUSH_S`."""
        if telemetry is not None:
            self.runs.mkdir(exist_ok=True)
            path = self.runs / f"run-{row['run']:06d}.mcap"
            partial = path.with_name(f".{path.name}.partial")
            partial.write_bytes(telemetry)
            os.replace(partial, path)
        self._waiting.append(row)
        now = time.monotonic()
        if now - self._flushed >= FLUSH_S:
            self.flush()
        if now - self._consolidated >= CONSOLIDATE_S:
            self.consolidate()

    def flush(self) -> None:
        """Write the waiting rows as a new part file."""
        self._flushed = time.monotonic()
        if not self._waiting:
            return
        self.parts.mkdir(exist_ok=True)
        existing = [int(p.stem.split("-")[1]) for p in self.parts.glob("part-*.parquet")]
        self._count = max([self._count] + existing) + 1
        path, table = self.parts / f"part-{self._count:06d}.parquet", frame([self._waiting])
        _write(table, path)
        self._written[path] = table
        self._waiting = []

    def consolidate(self) -> None:
        """Fold the part files (and the rows waiting) into ``results.parquet``: those this
        store wrote from the table it wrote them from (the same numbers and text), the
        others read."""
        self.flush()
        self._consolidated = time.monotonic()
        parts = sorted(self.parts.glob("part-*.parquet"))
        whole = self.dir / "results.parquet"
        if not parts and whole.is_file():
            return
        tables = [_rows(whole)] if whole.exists() else []
        tables += [self._written[part] if part in self._written else _rows(part) for part in parts]
        _write(frame(tables), whole)
        for part in parts:
            part.unlink()
        self._written.clear()
