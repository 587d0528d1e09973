"""The campaign directory: what a campaign wrote, as it went.

::

    DIR/campaign.yaml      the campaign, its scenario an absolute path
    DIR/meta.json          name, seed, runs, scenario, dispersions, target, outputs, version,
                           insertion (tolerances)
    DIR/inputs.parquet     every run's inputs, written before anything flies
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
"""

from __future__ import annotations

import json
import math
import os
import time
from pathlib import Path

import numpy as np

from rocketsim.errors import InputError
from rocketsim.scenario.yaml_source import read_yaml

FLUSH_S = 1.0           # s between part files (rows waiting)
CONSOLIDATE_S = 10.0    # s between rewrites of results.parquet
LEADING = ["run", "status", "error", "wall_time_s", "outcome"]
STRINGS = {"status", "error", "outcome"}


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
        strings |= {name for name in table.columns
                    if table[name].dtype == object or pd.api.types.is_string_dtype(table[name].dtype)}
    combined = pd.concat(tables, ignore_index=True, sort=False)
    combined = combined.drop_duplicates("run", keep="last").sort_values("run", kind="stable")
    names = [n for n in LEADING if n in combined.columns] + sorted(set(combined.columns) - set(LEADING))
    columns = {}
    for name in names:
        values = combined[name]
        if name == "run":
            columns[name] = values.astype(np.int64).to_numpy()
        elif name in strings:
            columns[name] = pd.array([None if v is None or (isinstance(v, float) and math.isnan(v))
                                      else str(v) for v in values], dtype=object)
        else:
            columns[name] = values.astype(np.float64).to_numpy()
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


class Store:
    """A campaign directory being written (see the module)."""

    def __init__(self, directory: str | Path):
        self.dir = Path(directory)
        self.parts = self.dir / "results"
        self.runs = self.dir / "runs"
        self._waiting: list[dict] = []
        self._flushed = self._consolidated = time.monotonic()
        self._count = 0
        self.set_aside: list[str] = []      # the damaged results files a resume set aside

    # --- starting ----------------------------------------------------------------

    def open(self, campaign, plan, resume: bool) -> set[int]:
        """Start the campaign here (a new or empty directory) or, with ``resume``, go on
        with the same campaign; the runs already finished."""
        import yaml
        resolved = campaign.resolved()
        held = self.dir / "campaign.yaml"
        if held.is_file():
            if not resume:
                raise InputError(f"{self.dir} already holds a campaign: add --resume to fly its missing "
                                 "runs, or write to another directory", field="--output")
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
                raise InputError(f"{self.dir} holds another campaign (its campaign.yaml differs in "
                                 f"{', '.join(changed)}): {why}", field="--resume")
            self.set_aside = set_aside_damaged(self.dir) + self._rewrite_damaged_plan(campaign, plan)
            self.consolidate()
            return set(read_results(self.dir)["run"].tolist())
        if resume:
            raise InputError(f"{self.dir} holds no campaign to resume", field="--resume")
        if self.dir.exists() and not self.dir.is_dir():
            raise InputError(f"{self.dir} is a file, not a directory", field="--output")
        try:
            self.dir.mkdir(parents=True, exist_ok=True)
            self.parts.mkdir(exist_ok=True)
        except OSError as error:
            raise InputError(f"cannot create {self.dir}: {error.strerror or error}", field="--output") from None
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
            _write(plan.inputs_table(), self.dir / "inputs.parquet")
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
        import pandas as pd
        said = []
        for name, read in (("inputs.parquet", pd.read_parquet), ("meta.json", lambda p: json.loads(p.read_text()))):
            path = self.dir / name
            try:
                if not isinstance(read(path), (pd.DataFrame, dict)):
                    raise ValueError("not a table or a mapping")
                continue
            except FileNotFoundError:
                said.append(f"{path}: missing, written again from the campaign")
            except Exception as error:      # noqa: BLE001 - pyarrow's and json's errors alike
                os.replace(path, path.with_name(name + ".damaged"))
                said.append(f"{path}: unreadable ({type(error).__name__}), set aside as {name}.damaged "
                            "and written again from the campaign")
            self._write_plan(campaign, plan, (name,))
        return said

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
        _write(frame([self._waiting]), self.parts / f"part-{self._count:06d}.parquet")
        self._waiting = []

    def consolidate(self) -> None:
        """Fold the part files (and the rows waiting) into ``results.parquet``."""
        self.flush()
        self._consolidated = time.monotonic()
        parts = sorted(self.parts.glob("part-*.parquet"))
        if not parts and (self.dir / "results.parquet").is_file():
            return
        _write(read_results(self.dir), self.dir / "results.parquet")
        for part in parts:
            part.unlink()
