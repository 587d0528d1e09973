"""A campaign's task: run ``k`` flown into its row, in this process or on a Dask worker.

A task is handed the campaign (its resolved text, a few kilobytes) and ``k``, never a
scenario or a run: run ``k`` is the base scenario with run ``k``'s overrides
(:meth:`rocketsim.campaigns.cases.Plan.overrides`), loaded and flown in memory by
:func:`rocketsim.api.flying.fly`, and the task hands back one row
(:mod:`rocketsim.campaigns.outputs`) and, when the retention keeps it, the run's MCAP
file. So run ``k`` flies bit for bit the same alone, serially, in a local pool or on a
cluster, first time or resumed.

* ``status`` ``ok``: the flight flew to its end (a crash or a break-up is its
  ``outcome``, not an error); ``error``: the program raised, a state went
  non-finite, a dispersed value was refused, or the worker flying it was lost
  more than ``retries`` times (counted on the scheduler: :func:`task_starts`);
  ``timeout``: it flew longer than the campaign's ``timeout`` (wall time) and was
  stopped from outside the flight, wherever it was (:func:`bounded`: a program
  blocked in a sleep or a lock included). A failed run is a row with its error.
* :func:`warm` flies the nominal run (every dispersion at its centre) so the
  compiled kernels it needs load, or compile into the disk cache
  (:mod:`rocketsim.jit`), before the first run.
"""

from __future__ import annotations

import math
import sys
import tempfile
import threading
import time
from pathlib import Path
from typing import Callable

from rocketsim.jit import beside
from rocketsim.campaigns.cases import Plan
from rocketsim.campaigns.insertion import insertion_columns
from rocketsim.campaigns.outputs import run_columns
from rocketsim.campaigns.spec import read_campaign
from rocketsim.errors import InputError
from rocketsim.flight.leash import Leash, Stop

_PLANS: dict[str, Plan] = {}     # a worker's plans, by campaign text (read once per worker)

# s a run's thread is given to stop after its timeout before it is left behind (a worker's
# flight blocked in a call that only returns by itself: a sleep, a lock)
TIMEOUT_GRACE = 2.0

# the scheduler's count of each campaign task's starts (an attribute of the scheduler)
_STARTS = "rocketsim_task_starts"


class _Timeout(Stop):
    """A run flew longer than the campaign's timeout (raised in the flight from outside it)."""


def plan_of(text: str) -> Plan:
    """The :class:`Plan` of a resolved campaign's YAML text (read once per process)."""
    plan = _PLANS.get(text)
    if plan is None:
        import yaml
        plan = Plan(read_campaign(yaml.safe_load(text)))
        _PLANS.clear()
        _PLANS[text] = plan
    return plan


def fly_row(plan: Plan, k: int, telemetry: Path | None, timeout: float | None):
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
        return lost_row(k, lost, retries), None
    beside.COMPILE_BESIDE = False     # the workers fill the cores: each compiles what its runs need itself
    plan = plan_of(text)
    with tempfile.TemporaryDirectory(prefix="rocketsim-run-") as folder:
        path = Path(folder) / f"run-{k:06d}.mcap"
        row = fly_row(plan, k, path if keep == "all" else None, timeout)
        if keep == "failed" and row["status"] == "error":
            fly_row(plan, k, path, timeout)       # the same flight, bit for bit, into a file
        return row, (path.read_bytes() if path.is_file() else None)


def _times_lost() -> int:
    """How many times the Dask task running now started before (each start that never
    returned was lost with its worker: a task queued on a lost worker but never started
    is not counted), counting this start; 0 outside a Dask worker (a process that has not
    imported Dask's distributed is none: it is not imported for the question)."""
    if "distributed" not in sys.modules:
        return 0
    try:
        from distributed import get_client, get_worker
        key = get_worker().get_current_task()
    except (ImportError, ValueError):
        return 0
    return get_client().run_on_scheduler(task_starts, key, 1)


def task_starts(key, add: int, dask_scheduler=None) -> int:
    """On the scheduler: the times the task ``key`` started before, counting ``add`` more."""
    starts = dask_scheduler.__dict__.setdefault(_STARTS, {})
    before = starts.get(key, 0)
    starts[key] = before + add
    return before


def forget_starts(prefix: str, dask_scheduler=None) -> None:
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


def kept(retention, k: int) -> str:
    """What of run ``k``'s telemetry the campaign's ``retention`` keeps (``keep`` of
    :func:`fly_case`): a list of runs keeps theirs whole."""
    if isinstance(retention, list):
        return "all" if k in retention else "none"
    return retention


def lost_row(k: int, times: int, retries: int, error: BaseException | None = None) -> dict:
    """The row of run ``k``, not flown again: its workers were lost ``times`` times (or the
    task could not run: ``error``)."""
    text = (f"the worker flying it was lost {times} time{'s' if times != 1 else ''} (retries: {retries})"
            + (f": {type(error).__name__}: {error}" if error is not None else ""))
    return {"run": k, "status": "error", "error": text, "outcome": "lost", "wall_time_s": math.nan}
