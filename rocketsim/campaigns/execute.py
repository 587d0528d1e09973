"""Flying a campaign: its runs through the front door, in this process or on Dask.

:func:`campaign` and :func:`run` fly a campaign file into its directory
(:mod:`rocketsim.campaigns.store`): the campaign is checked whole before anything
flies (:class:`rocketsim.campaigns.cases.Plan`), then each run ``k`` it is missing is
a task (:mod:`rocketsim.campaigns.run_task`: its row, and its MCAP where the
retention keeps it), flown in this process (``workers=1``, without Dask: debugging)
or on Dask (:mod:`rocketsim.campaigns.cluster`: an embedded cluster, or the user's
scheduler). A failed run is a row with its error; the campaign goes on. :func:`rerun`
flies run ``k`` alone again, bit for bit, and :func:`same_row` compares it with its row.

* Warm-up: the nominal run (every dispersion at its centre) is flown whole once in
  this process first, so the compiled kernels it needs are in the disk cache
  (:mod:`rocketsim.jit`), compiled once.
* Ctrl-C saves every finished run and raises :class:`Interrupted`; flying the
  campaign again with ``resume`` flies exactly the runs missing.
"""

from __future__ import annotations

import math
import os
import tempfile
from pathlib import Path
from typing import Callable, Mapping

from rocketsim.argument_checks import expect, switch, whole
from rocketsim.campaigns.cases import Plan
from rocketsim.campaigns.cluster import connect, on_dask
from rocketsim.campaigns.run_task import fly_case, fly_row, kept, plan_of, warm
from rocketsim.campaigns.spec import read_campaign
from rocketsim.campaigns.store import Store, frame, read_results
from rocketsim.errors import ArgumentError
from rocketsim.extras import needs
from rocketsim.scenario.trust import approve


class Interrupted(KeyboardInterrupt):
    """Ctrl-C stopped a campaign; ``done`` runs are saved in ``directory``."""

    def __init__(self, directory: Path, done: int, runs: int):
        super().__init__(f"interrupted: {done} of {runs} runs are saved in {directory}")
        self.directory, self.done, self.runs = directory, done, runs


def run(campaign, directory: str | Path, *, workers: int | None = None, scheduler: str | None = None,
        scheduler_file: str | Path | None = None, resume: bool = False, base_dir=None,
        progress: Callable[[int, int, int], None] | None = None,
        log: Callable[[str], None] | None = None, runs: int | None = None, trust: bool = False):
    """Fly ``campaign`` (a campaign file or mapping) into ``directory``; the results table.

    ``runs``: fly that many runs in place of the file's (the first ones of the same
    campaign); with ``resume`` a larger number grows a campaign sampled at random or
    on a Sobol design (:meth:`rocketsim.campaigns.store.Store.open`).

    ``progress(done, failed, total)`` is called when the first run starts (0 done) and
    as runs finish (``total``: the runs this call flies), ``log(message)`` with the warm-up's costs. Raises
    :class:`~rocketsim.errors.InputError` for a bad campaign before anything flies,
    :class:`Interrupted` on Ctrl-C (everything finished saved). A campaign file that is
    the directory's own ``campaign.yaml`` (resuming a folder as it came) flies the
    programs it names only with ``trust`` (:func:`rocketsim.scenario.trust.approve`)."""
    workers = whole(workers, "workers", low=1)
    expect(scheduler, (str, type(None)), "scheduler", "a scheduler's address (tcp://host:8786) or None")
    expect(scheduler_file, (str, os.PathLike, type(None)), "scheduler_file", "a file's path or None")
    expect(directory, (str, os.PathLike), "directory", "a folder's path")
    resume, trust = switch(resume, "resume"), switch(trust, "trust")
    in_process = workers == 1 and scheduler is None and scheduler_file is None
    needs("campaign", "a campaign", "pyarrow", *(() if in_process else ("distributed",)))
    import yaml
    log = log or (lambda message: None)
    found = read_campaign(campaign, base_dir).with_runs(runs)
    Plan(found)         # every problem reported at its line of the campaign file, before anything else
    # what flies is the resolved campaign: the text every worker reads, campaign.yaml of the directory
    text = yaml.safe_dump(found.resolved(), sort_keys=False)
    plan = plan_of(text)
    if found.path is not None and _same_file(found.path, Path(directory) / "campaign.yaml"):
        approve(plan.variants(), trust, f"the campaign folder {directory}")
    if scheduler is not None or scheduler_file is not None:
        connect(scheduler, scheduler_file).close()     # reachable, before the directory is written
    store = Store(directory)
    done = store.open(found, plan, resume)
    for line in store.set_aside:
        log(line)
    total = found.spec.runs - sum(1 for k in done if k < found.spec.runs)
    todo = (k for k in range(found.spec.runs) if k not in done)      # drawn as runs are handed out
    counts = [0, 0]

    def finished(row: dict, telemetry: bytes | None) -> None:
        store.add(row, telemetry)
        counts[0] += 1
        counts[1] += row["status"] != "ok"
        if progress is not None:
            progress(counts[0], counts[1], total)

    def started() -> None:
        if progress is not None:
            progress(0, 0, total)

    try:
        if total and in_process:
            _in_process(text, todo, found.spec, finished, log, started)
        elif total:
            on_dask(text, todo, found.spec, finished, log, started, workers, scheduler, scheduler_file)
    except KeyboardInterrupt:
        store.inputs_written(complete=False)
        store.consolidate()
        raise Interrupted(store.dir, len(done) + counts[0], found.spec.runs) from None
    except BaseException:
        store.inputs_written(complete=False)
        raise
    finally:
        store.consolidate()
    store.inputs_written()
    return read_results(store.dir)


def _in_process(text, todo, spec, finished, log, started) -> None:
    log(f"warm-up: the nominal run flown in this process in {warm(text, None):.2f} s")
    started()
    for k in todo:
        finished(*fly_case(text, k, kept(spec.telemetry, k), spec.timeout))


def _same_file(a: Path, b: Path) -> bool:
    try:
        return a.samefile(b)
    except OSError:
        return False


def rerun(directory: str | Path, k: int, telemetry: str | Path, trust: bool = False):
    """Fly run ``k`` of the campaign in ``directory`` alone into the MCAP file
    ``telemetry``; ``(row, recorded)``: its row, and its row in the results (None if
    it has none), both as one-row tables with the same columns. The folder may come
    from someone else: the programs run ``k`` flies run only with ``trust``
    (:func:`rocketsim.scenario.trust.approve` raises
    :class:`~rocketsim.scenario.trust.UntrustedProgram` naming them)."""
    needs("campaign", "a campaign's rerun", "pyarrow")
    expect(directory, (str, os.PathLike), "directory", "a campaign folder's path")
    expect(telemetry, (str, os.PathLike), "telemetry", "a file's path")
    k, trust = whole(k, "k", optional=False), switch(trust, "trust")
    directory = Path(directory)
    if not (directory / "campaign.yaml").is_file():
        raise ArgumentError(f"{directory} holds no campaign (no campaign.yaml)", "directory")
    plan = Plan(read_campaign(directory / "campaign.yaml"))
    runs = plan.campaign.spec.runs
    if not 0 <= k < runs:
        raise ArgumentError(f"the campaign has runs 0 .. {runs - 1}, not {k}", "k")
    approve(plan.scenario(k), trust, f"the campaign folder {directory}")
    row = fly_row(plan, k, Path(telemetry), plan.campaign.spec.timeout)
    results = read_results(directory)
    recorded = results[results["run"] == k]
    mine = frame([[row]])
    if recorded.empty:
        return mine, None
    names = list(dict.fromkeys(list(recorded.columns) + list(mine.columns)))
    return mine.reindex(columns=names), recorded.reset_index(drop=True).reindex(columns=names)


def same_row(a, b, ignore=("wall_time_s",)) -> list[str]:
    """The columns where two one-row results tables differ: floats bit for bit, a
    missing value (NaN, None) only where the other is missing too."""
    import numpy as np

    def missing(value) -> bool:
        return value is None or (isinstance(value, float) and math.isnan(value))

    differ = []
    for name in a.columns:
        x, y = a[name].iloc[0], b[name].iloc[0]
        if name in ignore or (missing(x) and missing(y)):
            continue
        if isinstance(x, float) and isinstance(y, float):
            same = np.float64(x).view(np.int64) == np.float64(y).view(np.int64)
        else:
            same = x == y
        if not same:
            differ.append(name)
    return differ


def campaign(campaign: str | Path | Mapping, directory: str | Path | None = None, *,
             workers: int | None = None, scheduler: str | None = None,
             scheduler_file: str | Path | None = None, resume: bool = False,
             base_dir: str | Path | None = None, runs: int | None = None, trust: bool = False):
    """Fly a Monte Carlo campaign and return its results as a pandas DataFrame (a row
    per run: ``run``, ``status``, ``error``, ``wall_time_s``, ``outcome`` and the
    output columns of :mod:`rocketsim.campaigns.outputs`).

    ``campaign``: a campaign file or mapping (its scenario relative to ``base_dir``);
    ``directory``: where the campaign is written (:mod:`rocketsim.campaigns.store`;
    default a temporary folder, removed); ``workers``: 1 flies in this process,
    otherwise a local Dask cluster of that many processes (default one per core);
    ``scheduler`` / ``scheduler_file``: an existing Dask cluster's; ``resume``: fly the
    runs ``directory`` is missing; ``runs``: that many runs in place of the file's. Every
    run's inputs derive from the campaign's seed and the run's number alone
    (:mod:`rocketsim.campaigns.sampling`); ``trust``: resuming ``directory`` with its own
    ``campaign.yaml`` may run its programs (see :func:`run`)."""
    if directory is None:
        with tempfile.TemporaryDirectory(prefix="rocketsim-campaign-") as folder:
            return run(campaign, Path(folder) / "campaign", workers=workers, scheduler=scheduler,
                       scheduler_file=scheduler_file, base_dir=base_dir, runs=runs)
    return run(campaign, directory, workers=workers, scheduler=scheduler, scheduler_file=scheduler_file,
               resume=resume, base_dir=base_dir, runs=runs, trust=trust)
