"""A campaign's runs on Dask: an embedded cluster or the user's, warmed, fed, watched.

* The cluster: an embedded :class:`distributed.LocalCluster` of ``workers`` (default:
  one per core) single-threaded worker processes (:func:`local_cluster`), or an
  existing cluster's scheduler (``scheduler="tcp://host:8786"`` or
  ``scheduler_file``: :func:`connect`), whose workers must see the scenario's files
  and the campaign directory at the same paths.
* Warm-up: the nominal run is flown whole once in this process first, so the
  compiled kernels it needs are in the disk cache (:mod:`rocketsim.jit`), compiled
  once; then each worker flies its first :data:`WORKER_WARM_S` seconds, importing the
  flight's modules and loading the kernels of the flight's steps from the cache
  before its first run (the kernels of later events, a staging, a landing, load in
  its first run, a few milliseconds each).
* The runs: each a task (:func:`rocketsim.campaigns.run_task.fly_case`) handed to the
  scheduler :data:`IN_FLIGHT_PER_WORKER` per worker at a time; a run whose workers
  are lost while flying it is flown again up to the campaign's ``retries`` times;
  the campaign stops, every finished run saved, after :data:`NO_WORKER_S` without a
  worker.
"""

from __future__ import annotations

import hashlib
import itertools
import os
import time
from pathlib import Path

from rocketsim.campaigns.run_task import fly_case, forget_starts, kept, lost_row, task_starts, warm
from rocketsim.errors import ArgumentError

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
# s a campaign waits with no worker in its cluster (at its start, or after the last one
# was lost) before it stops, saying so every WORKER_NOTICE_S
NO_WORKER_S = 120.0
WORKER_NOTICE_S = 10.0
IN_FLIGHT_PER_WORKER = 4    # runs handed to the scheduler per worker (more as they finish)


def on_dask(text, todo, spec, finished, log, started, workers, scheduler, scheduler_file) -> None:
    """Fly the runs ``todo`` of the campaign ``text`` on Dask (the user's scheduler, or an
    embedded cluster of ``workers``), each row to ``finished(row, telemetry)``;
    ``started()`` once the workers are warm, ``log(message)`` with the warm-up's costs."""
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
            cluster = local_cluster(workers)
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
        return client.submit(fly_case, text, k, kept(spec.telemetry, k), spec.timeout, spec.retries, lost,
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
                    lost += client.run_on_scheduler(task_starts, future.key, 0)
                    if lost <= spec.retries:
                        pending[submit(k, lost)] = (k, lost)
                        continue
                    row, telemetry = lost_row(k, lost, spec.retries), None
                except Exception as error:      # noqa: BLE001 - a task that cannot run: a row
                    row, telemetry = lost_row(k, lost, spec.retries, error), None
                finished(row, telemetry)
                future.release()
            refill()
    finally:
        client.cancel(list(pending), force=True)
        client.run_on_scheduler(forget_starts, f"rocketsim-run-{token}-")


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


def local_cluster(workers: int | None):
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
