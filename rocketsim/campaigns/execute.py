"""Flying a campaign: every run through the front door, in this process or on Dask.

Each run ``k`` is the base scenario with run ``k``'s overrides
(:meth:`rocketsim.campaigns.cases.Plan.overrides`), loaded and flown in memory by
:func:`rocketsim.api.flying.fly`; a worker is handed the campaign (its
resolved text, a few kilobytes) and ``k``, never a scenario or a run, and hands
back one row (:mod:`rocketsim.campaigns.outputs`) and, when the retention keeps
it, the run's MCAP file. So run ``k`` flies bit for bit the same alone
(:func:`rerun`), serially, in a local pool or on a cluster, first time or resumed.

* ``status`` ``ok``: the flight flew to its end (a crash or a break-up is its
  ``outcome``, not an error); ``error``: the program raised, a state went
  non-finite, a dispersed value was refused, or the worker flying it was lost
  more than ``retries`` times; ``timeout``: it flew longer than the campaign's
  ``timeout`` (wall time) and was stopped from outside the flight, wherever it was
  (:func:`bounded`: a program blocked in a sleep or a lock included).
  A failed run is a row with its error; the campaign goes on.
* Executors: ``workers=1`` flies in this process, without Dask (debugging);
  otherwise an embedded :class:`distributed.LocalCluster` of ``workers`` (default:
  one per core) single-threaded worker processes, or an existing cluster's
  scheduler (``scheduler="tcp://host:8786"`` or ``scheduler_file``), whose workers
  must see the scenario's files and the campaign directory at the same paths.
* Warm-up: the nominal run (every dispersion at its centre) is flown whole once
  in this process first, so the compiled kernels it needs are in the disk cache
  (:mod:`rocketsim.jit`), compiled once; then each worker flies its first
  :data:`WORKER_WARM_S` seconds, importing the flight's modules and loading the
  kernels of the flight's steps from the cache before its first run (the
  kernels of later events, a staging, a landing, load in its first run, a few
  milliseconds each).
* Ctrl-C saves every finished run and raises :class:`Interrupted`; flying the
  campaign again with ``resume`` flies exactly the runs missing.
"""

from __future__ import annotations

import hashlib
import itertools
import math
import os
import tempfile
import threading
import time
from pathlib import Path
from typing import Callable, Mapping

from rocketsim.api.arguments import expect, switch, whole
from rocketsim.jit import beside
from rocketsim.campaigns.cases import Plan
from rocketsim.campaigns.insertion import insertion_columns
from rocketsim.campaigns.outputs import run_columns
from rocketsim.campaigns.spec import read_campaign
from rocketsim.campaigns.store import Store, frame, read_results
from rocketsim.errors import ArgumentError, InputError
from rocketsim.extras import needs
from rocketsim.flight.leash import Leash, Stop
from rocketsim.scenario.trust import approve

WORKER_WARM_S = 1.0      # s of the nominal run a worker flies before its first run
# Dask settings of the embedded cluster's workers. A worker flies a run in a thread
# beside its event loop, and each time another thread takes the GIL the flight
# thread hands it over and takes it back (two futex calls, a sleep and a wake-up on
# another core), a cost of both system and user time. By default a worker's
# statistical profiler samples every 10 ms and its event loop ticks every 20 ms, both
# for the dashboard this cluster does not serve; with these settings a run on a worker
# costs about what it costs in a plain process (the campaign benchmark prints both).
# The memory monitor still pauses or restarts a worker over its memory limit, every
# 2 s rather than every 100 ms: a flight's memory grows slowly.
QUIET_WORKERS = {
    "distributed.worker.profile.enabled": False,
    "distributed.admin.tick.interval": "1s",
    "distributed.admin.system-monitor.interval": "5s",
    "distributed.worker.memory.monitor-interval": "2s",
}
_PLANS: dict[str, Plan] = {}     # a worker's plans, by campaign text (read once per worker)


class Interrupted(KeyboardInterrupt):
    """Ctrl-C stopped a campaign; ``done`` runs are saved in ``directory``."""

    def __init__(self, directory: Path, done: int, runs: int):
        super().__init__(f"interrupted: {done} of {runs} runs are saved in {directory}")
        self.directory, self.done, self.runs = directory, done, runs


class _Timeout(Stop):
    """A run flew longer than the campaign's timeout (raised in the flight from outside it)."""


# s a run's thread is given to stop after its timeout before it is left behind (a worker's
# flight blocked in a call that only returns by itself: a sleep, a lock)
TIMEOUT_GRACE = 2.0


def plan_of(text: str) -> Plan:
    """The :class:`Plan` of a resolved campaign's YAML text (read once per process)."""
    plan = _PLANS.get(text)
    if plan is None:
        import yaml
        plan = Plan(read_campaign(yaml.safe_load(text)))
        _PLANS.clear()
        _PLANS[text] = plan
    return plan


def _fly(plan: Plan, k: int, telemetry: Path | None, timeout: float | None):
    """Fly run ``k`` (into the MCAP ``telemetry``, or in memory): its row."""
    from rocketsim.api.flying import fly
    from rocketsim.api.run import open_run
    start = time.perf_counter()
    reached = [0.0]

    def watch(t: float, phase: str) -> None:
        reached[0] = t

    paths, tolerance = plan.campaign.spec.outputs, plan.campaign.spec.insertion
    row = {"run": k, "status": "ok", "error": None}
    try:
        scenario = plan.scenario(k)
        run = bounded(lambda: fly(scenario, telemetry, progress=watch), timeout)
        row.update(run_columns(run, paths))
        if tolerance is not None:
            row.update(insertion_columns(run, scenario.scenario.mission.target.orbit, tolerance))
    except _Timeout as error:
        text = f"stopped after {timeout:g} s of wall time, at T+{reached[0]:.1f} s or later"
        if str(error):
            text += f" ({error})"
        row.update(status="timeout", error=text, outcome="timeout")
    except Exception as error:              # noqa: BLE001 - a failed run is a row, the campaign goes on
        text = str(error) if isinstance(error, InputError) else f"{type(error).__name__}: {error}"
        row.update(status="error", error=text, outcome=text)
        partial = getattr(error, "run", None)
        if partial is None and telemetry is not None and telemetry.is_file():
            partial = open_run(telemetry)
        if partial is not None:         # what flew before the error
            row.update({**run_columns(partial, paths), "outcome": partial.outcome})
    row["wall_time_s"] = time.perf_counter() - start
    return row


def bounded(call: Callable, timeout: float | None):
    """``call()``, stopped by :class:`_Timeout` after ``timeout`` s of wall time (None: no
    bound) whatever it is doing: in the main thread a :class:`~rocketsim.flight.leash.Leash`
    interrupts it (a sleep or a lock included); in another (a Dask worker's) it flies in a
    thread of its own under the leash, which stops Python code, and one still blocked
    :data:`TIMEOUT_GRACE` s later (in a call only its own return ends) is left behind."""
    if timeout is None:
        return call()
    if threading.current_thread() is threading.main_thread():
        with Leash(timeout, _Timeout):
            return call()
    outcome: list = []

    def leashed() -> None:
        try:
            with Leash(timeout, _Timeout):
                outcome.append((True, call()))
        except BaseException as error:      # noqa: BLE001 - handed to the caller's thread
            outcome.append((False, error))

    thread = threading.Thread(target=leashed, name="rocketsim-run", daemon=True)
    thread.start()
    thread.join(timeout + TIMEOUT_GRACE)
    if not outcome:
        raise _Timeout("blocked in a call that could not be interrupted: its thread was left behind")
    done, value = outcome[0]
    if not done:
        raise value
    return value


def fly_case(text: str, k: int, keep: str, timeout: float | None, retries: int = 0,
             lost: int = 0) -> tuple[dict, bytes | None]:
    """A worker's task: run ``k`` of the campaign ``text``; ``keep`` its telemetry
    (``all``: flown into an MCAP file; ``failed``: flown again into one if it failed;
    ``none``). Returns ``(row, MCAP bytes or None)``. A run whose workers were lost more
    than ``retries`` times (``lost`` before this task, and those the scheduler counts
    for it: :func:`_times_lost`) is not flown again: its row says so."""
    lost += _times_lost()
    if lost > retries:
        return _lost(k, lost, retries), None
    beside.COMPILE_BESIDE = False     # the workers fill the cores: each compiles what its runs need itself
    plan = plan_of(text)
    with tempfile.TemporaryDirectory(prefix="rocketsim-run-") as folder:
        path = Path(folder) / f"run-{k:06d}.mcap"
        row = _fly(plan, k, path if keep == "all" else None, timeout)
        if keep == "failed" and row["status"] == "error":
            _fly(plan, k, path, timeout)       # the same flight, bit for bit, into a file
        return row, (path.read_bytes() if path.is_file() else None)


def _times_lost() -> int:
    """How many times the Dask task running now started before (each start that never
    returned was lost with its worker: a task queued on a lost worker but never started
    is not counted), counting this start; 0 outside a Dask worker."""
    try:
        from distributed import get_client, get_worker
        key = get_worker().get_current_task()
    except (ImportError, ValueError):
        return 0
    return get_client().run_on_scheduler(_starts, key, 1)


# the scheduler's count of each campaign task's starts (an attribute of the scheduler)
_STARTS = "rocketsim_task_starts"


def _starts(key, add: int, dask_scheduler=None) -> int:
    """On the scheduler: the times the task ``key`` started before, counting ``add`` more."""
    starts = dask_scheduler.__dict__.setdefault(_STARTS, {})
    before = starts.get(key, 0)
    starts[key] = before + add
    return before


def _forget(prefix: str, dask_scheduler=None) -> None:
    """On the scheduler: drop the counts of the tasks whose keys start with ``prefix``."""
    starts = dask_scheduler.__dict__.get(_STARTS, {})
    for key in [key for key in starts if str(key).startswith(prefix)]:
        del starts[key]


def warm(text: str, duration: float | None = 0.0) -> float:
    """Fly the campaign's nominal run (every dispersion at its centre) for ``duration``
    seconds (None: to its end), in memory: the flight's modules and compiled kernels
    load (or compile into the cache). Returns the seconds it took."""
    from rocketsim.api.flying import fly
    start = time.perf_counter()
    plan = plan_of(text)
    try:
        fly(plan.nominal(), duration=duration)
    except Exception:       # noqa: BLE001 - a nominal run that fails warms as far as it flew
        pass
    return time.perf_counter() - start


def _keep(retention, k: int) -> str:
    if isinstance(retention, list):
        return "all" if k in retention else "none"
    return retention


def _lost(k: int, times: int, retries: int, error: BaseException | None = None) -> dict:
    text = (f"the worker flying it was lost {times} time{'s' if times != 1 else ''} (retries: {retries})"
            + (f": {type(error).__name__}: {error}" if error is not None else ""))
    return {"run": k, "status": "error", "error": text, "outcome": "lost", "wall_time_s": math.nan}


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
            _on_dask(text, todo, found.spec, finished, log, started, workers, scheduler, scheduler_file)
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
        finished(*fly_case(text, k, _keep(spec.telemetry, k), spec.timeout))


def _on_dask(text, todo, spec, finished, log, started, workers, scheduler, scheduler_file) -> None:
    import dask
    from distributed import Client
    token = hashlib.sha256(text.encode()).hexdigest()[:12]
    with dask.config.set({"distributed.scheduler.allowed-failures": spec.retries}):
        if scheduler is not None or scheduler_file is not None:
            cluster = None
            client = connect(scheduler, scheduler_file)
            log(f"warm-up: the nominal run flown in this process in {warm(text, None):.2f} s")
        else:
            log(f"warm-up: the nominal run flown in this process in {warm(text, None):.2f} s")
            cluster = _local_cluster(workers)
            client = Client(cluster)
        try:
            start = time.perf_counter()
            addresses = _workers(client, log)
            warming = [client.submit(warm, text, WORKER_WARM_S, key=f"rocketsim-warm-{token}-{n}",
                                     workers=[address], allow_other_workers=False, pure=False)
                       for n, address in enumerate(addresses)]
            costs = client.gather(warming)
            log(f"warm-up: {len(addresses)} workers flew the nominal run's first {WORKER_WARM_S:g} s in "
                f"{time.perf_counter() - start:.2f} s (each {min(costs):.2f} .. {max(costs):.2f} s)")
            started()
            _fly_all(client, text, token, todo, spec, finished, log)
        finally:
            client.close()
            if cluster is not None:
                cluster.close()


# s a campaign waits with no worker in its cluster (at its start, or after the last one
# was lost) before it stops, saying so every WORKER_NOTICE_S
NO_WORKER_S = 120.0
WORKER_NOTICE_S = 10.0
IN_FLIGHT_PER_WORKER = 4    # runs handed to the scheduler per worker (more as they finish)


def _workers(client, log) -> list[str]:
    """The cluster's workers' addresses, waiting (visibly) up to :data:`NO_WORKER_S` for one."""
    waited = 0.0
    while True:
        addresses = list(client.scheduler_info()["workers"])
        if addresses:
            return addresses
        if waited >= NO_WORKER_S:
            raise ArgumentError(f"the Dask scheduler has no worker: none joined in {NO_WORKER_S:g} s; "
                                "nothing was flown", "scheduler")
        log(f"waiting for a Dask worker to join the scheduler ({waited:.0f} of {NO_WORKER_S:g} s)")
        time.sleep(WORKER_NOTICE_S)
        waited += WORKER_NOTICE_S


def _fly_all(client, text, token, todo, spec, finished, log) -> None:
    """Every run of ``todo`` on the cluster, each row to ``finished`` as it comes. A run
    whose workers are lost while flying it is flown again up to ``spec.retries``
    times, whatever the scheduler's own allowance (its ``allowed-failures``, which
    also counts a task merely queued on a lost worker: a task past it comes back as
    KilledWorker and is submitted again, counting only its starts); the campaign stops
    (every finished run saved) after :data:`NO_WORKER_S` without a worker. Runs are
    handed to the scheduler :data:`IN_FLIGHT_PER_WORKER` per worker at a time, more as
    they finish: the client's and the scheduler's memory do not grow with the runs."""
    from distributed import wait
    from distributed.scheduler import KilledWorker

    def submit(k: int, lost: int):
        return client.submit(fly_case, text, k, _keep(spec.telemetry, k), spec.timeout, spec.retries, lost,
                             key=f"rocketsim-run-{token}-{k}-{lost}", priority=-k, pure=False)

    pending: dict = {}

    def refill() -> None:
        window = IN_FLIGHT_PER_WORKER * max(len(client.scheduler_info()["workers"]), 1)
        for k in itertools.islice(todo, max(window - len(pending), 0)):
            pending[submit(k, 0)] = (k, 0)

    refill()
    idle = 0.0
    try:
        while pending:
            try:
                done = wait(list(pending), timeout=WORKER_NOTICE_S, return_when="FIRST_COMPLETED").done
            except TimeoutError:
                done = ()
            if not done:
                idle = idle + WORKER_NOTICE_S if not client.scheduler_info()["workers"] else 0.0
                if idle >= NO_WORKER_S:
                    raise ArgumentError(f"the Dask cluster has had no worker for {NO_WORKER_S:g} s; every "
                                        "finished run is saved: resuming flies the rest", "scheduler")
                if idle:
                    log(f"no Dask worker in the cluster for {idle:.0f} s: waiting up to {NO_WORKER_S:g} s")
                continue
            idle = 0.0
            for future in done:
                k, lost = pending.pop(future)
                try:
                    row, telemetry = future.result()
                except KilledWorker:      # the scheduler's allowance is spent: count the starts
                    lost += client.run_on_scheduler(_starts, future.key, 0)
                    if lost <= spec.retries:
                        pending[submit(k, lost)] = (k, lost)
                        continue
                    row, telemetry = _lost(k, lost, spec.retries), None
                except Exception as error:      # noqa: BLE001 - a task that cannot run: a row
                    row, telemetry = _lost(k, lost, spec.retries, error), None
                finished(row, telemetry)
                future.release()
            refill()
    finally:
        client.cancel(list(pending), force=True)
        client.run_on_scheduler(_forget, f"rocketsim-run-{token}-")


def connect(scheduler: str | None, scheduler_file: str | Path | None):
    """A Dask client of the scheduler at ``scheduler`` (an address) or named by
    ``scheduler_file``; :class:`InputError` when it cannot be reached within 10 s."""
    from distributed import Client
    given = scheduler if scheduler is not None else f"the scheduler file {scheduler_file}"
    try:
        return Client(scheduler, scheduler_file=None if scheduler_file is None else str(scheduler_file),
                      timeout="10s")
    except Exception as error:      # noqa: BLE001 - unreachable, a bad address, a file that is no scheduler's
        raise ArgumentError(f"cannot reach the Dask scheduler at {given}: {type(error).__name__}: {error}",
                            "scheduler" if scheduler is not None else "scheduler_file") from None


def _local_cluster(workers: int | None):
    """A LocalCluster of ``workers`` (default: one per core) single-threaded worker processes,
    no dashboard. Its workers ignore SIGINT (started while this process ignores it, which a
    new process inherits): Ctrl-C at a terminal reaches the whole process group, and this
    process, not each worker, stops the campaign and shuts them down. The workers run
    with :data:`QUIET_WORKERS` (their nanny hands them this process's Dask settings)."""
    import logging
    import signal
    import threading
    import dask
    from distributed import LocalCluster
    main = threading.current_thread() is threading.main_thread()
    previous = signal.signal(signal.SIGINT, signal.SIG_IGN) if main else None
    try:
        with dask.config.set(QUIET_WORKERS):
            return LocalCluster(n_workers=workers or os.cpu_count() or 1, threads_per_worker=1, processes=True,
                                dashboard_address=None, silence_logs=logging.ERROR)
    finally:
        if main:
            signal.signal(signal.SIGINT, previous)


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
    row = _fly(plan, k, Path(telemetry), plan.campaign.spec.timeout)
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
