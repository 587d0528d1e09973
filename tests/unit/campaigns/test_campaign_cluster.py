"""A campaign on a user's Dask cluster does what the campaign file asks: its ``retries``
(a run whose worker is killed is flown again, or not), its ``timeout`` (a run
blocked in a sleep is stopped by the worker) and, with no worker, it says so and
stops.

The cluster is real and small: a ``dask scheduler`` and a ``dask worker`` of two
single-threaded worker processes under nannies (a killed worker process is
restarted), subprocesses listening on 127.0.0.1 at ports the system picks,
always shut down. The scheduler keeps Dask's default allowance of three lost
workers per task, which the campaign's ``retries: 0`` must not inherit.

The killed run: the first run past T+1.5 s (beyond the workers' one-second
warm-up flights; the warm-up in this process is left alone) creates a file
(exclusively) holding its worker's process id and sleeps; the test kills that
process with SIGKILL. A run flown again finds the file and flies on.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pandas as pd
import pytest

import rocketsim
from rocketsim.api import run_campaign
from rocketsim.campaigns import cluster as cluster_module
from rocketsim.errors import InputError
from tests.campaign_files import write_arc

pytest.importorskip("distributed")

VICTIM = """\
import os
import time
from pathlib import Path


def main(fc):
    fc.sleep(1.5)
    if os.getpid() == {client}:
        return
    try:
        with open({victim!r}, "x") as first:
            first.write(str(os.getpid()))
    except FileExistsError:
        return
    time.sleep(600)
"""

CAMPAIGN = """\
name: killed
scenario: arc.yaml
runs: 4
seed: 3
retries: {retries}
overrides: {{program_time_limit: 3600 s}}
dispersions:
  v_north: {{path: "mission.start.site.velocity[1]", kind: normal, sigma: 1 %}}
"""


def _dask(*args: str, log: Path) -> subprocess.Popen:
    return subprocess.Popen([str(Path(sys.executable).with_name("dask")), *args], stdout=log.open("w"),
                            stderr=subprocess.STDOUT, start_new_session=True)


@pytest.fixture(scope="module")
def cluster(tmp_path_factory):
    """(scheduler file, a function starting the workers once) of a scheduler on 127.0.0.1."""
    folder = tmp_path_factory.mktemp("cluster")
    file = folder / "scheduler.json"
    processes = [_dask("scheduler", "--host", "127.0.0.1", "--port", "0", "--no-dashboard",
                       "--scheduler-file", str(file), log=folder / "scheduler.log")]

    def start_workers() -> None:
        if len(processes) > 1:
            return
        processes.append(_dask("worker", "--scheduler-file", str(file), "--nworkers", "2", "--nthreads", "1",
                               "--host", "127.0.0.1", "--no-dashboard", log=folder / "workers.log"))

    try:
        for _ in range(600):                # a hang guard: the scheduler writes its file in seconds
            if file.is_file() and file.stat().st_size:
                break
            time.sleep(0.1)
        yield file, start_workers
    finally:
        for process in reversed(processes):
            os.killpg(process.pid, signal.SIGTERM)
        for process in reversed(processes):
            try:
                process.wait(30)
            except subprocess.TimeoutExpired:
                os.killpg(process.pid, signal.SIGKILL)
                process.wait()


def test_with_no_worker_the_campaign_says_so_and_stops(cluster, tmp_path, monkeypatch):
    file, _ = cluster
    monkeypatch.setattr(cluster_module, "NO_WORKER_S", 2.0)
    monkeypatch.setattr(cluster_module, "WORKER_NOTICE_S", 1.0)
    said = []
    campaign = write_arc(tmp_path, CAMPAIGN.format(retries=0))
    with pytest.raises(InputError, match="no worker"):
        run_campaign(campaign, tmp_path / "out", scheduler_file=file, log=said.append)
    assert any("waiting for a Dask worker" in line for line in said)


def _kill_the_victim(victim: Path) -> None:
    for _ in range(1200):                   # a hang guard: the first run starts in seconds
        if victim.is_file() and victim.read_text():
            os.kill(int(victim.read_text()), signal.SIGKILL)
            return
        time.sleep(0.05)
    raise AssertionError("no run started")


@pytest.mark.parametrize("retries", [0, 2])
def test_retries_are_what_the_campaign_file_asks(cluster, tmp_path, retries):
    import threading
    file, start_workers = cluster
    start_workers()
    victim = tmp_path / "victim"
    campaign = write_arc(tmp_path, CAMPAIGN.format(retries=retries),
                         program=VICTIM.format(victim=str(victim), client=os.getpid()))
    killer = threading.Thread(target=_kill_the_victim, args=(victim,))
    killer.start()
    results = rocketsim.campaign(campaign, tmp_path / "out", scheduler_file=file)
    killer.join()
    assert list(results["run"]) == [0, 1, 2, 3]
    lost = results[results["status"] != "ok"]
    if retries == 0:
        assert len(lost) == 1 and lost["outcome"].item() == "lost"
        assert "lost 1 time (retries: 0)" in lost["error"].item()
    else:
        assert lost.empty and results["slug.impact.t_s"].notna().all()
    stored = pd.read_parquet(tmp_path / "out" / "results.parquet")
    assert list(stored["status"]) == list(results["status"])


SLOW = """\
import os
import time


def main(fc):
    slow = fc.vertical_speed < 91.3          # released slowly upwards
    fc.sleep(1.5)
    if slow and os.getpid() != {client}:
        time.sleep(600)
"""


def _released_upwards(timeout: str) -> str:
    """The campaign dispersing the upward release speed, with ``timeout``."""
    return (CAMPAIGN.format(retries=0).replace("v_north: {path: \"mission.start.site.velocity[1]\"",
                                               "v_up: {path: \"mission.start.site.velocity[2]\"")
            + f"timeout: {timeout}\n")


def test_a_worker_stops_a_run_blocked_past_its_timeout(cluster, tmp_path):
    """The runs released slowest upwards sleep in their program at T+1.5 s, in a worker's
    thread where nothing interrupts a sleep: each is stopped at the campaign's timeout
    and its thread left behind; the others fly. The timeout, 6 s, leaves a loaded machine
    (load 20 on 2 cores) time to fly every run to T+1.5 s: at 3 s a slow run was
    sometimes stopped before it reached its sleep."""
    file, start_workers = cluster
    start_workers()
    campaign = write_arc(tmp_path, _released_upwards("6 s"), program=SLOW.format(client=os.getpid()))
    results = rocketsim.campaign(campaign, tmp_path / "out", scheduler_file=file)
    inputs = pd.read_parquet(tmp_path / "out" / "inputs.parquet")
    slow = set(inputs.loc[inputs["v_up"] < 91.3, "run"])
    assert slow and slow < set(range(4))
    assert set(results.loc[results["status"] == "timeout", "run"]) == slow
    assert (results.loc[~results["run"].isin(slow), "status"] == "ok").all()
    for error in results.loc[results["status"] == "timeout", "error"]:
        assert "stopped after 6 s of wall time" in error and "left behind" in error


def test_in_this_process_a_run_blocked_past_its_timeout_is_stopped(tmp_path):
    """--workers 1 flies in the main thread, where the timeout interrupts the sleep itself."""
    campaign = write_arc(tmp_path, _released_upwards("1 s"), program=SLOW.format(client=-1))
    results = rocketsim.campaign(campaign, tmp_path / "out", workers=1)
    inputs = pd.read_parquet(tmp_path / "out" / "inputs.parquet")
    slow = set(inputs.loc[inputs["v_up"] < 91.3, "run"])
    assert set(results.loc[results["status"] == "timeout", "run"]) == slow
    for error in results.loc[results["status"] == "timeout", "error"]:
        assert "stopped after 1 s of wall time, at T+1.5 s" in error and "left behind" not in error
