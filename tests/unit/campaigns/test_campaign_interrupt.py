"""A campaign survives a lost worker and Ctrl-C: `rocketsim campaign run` in a subprocess
on a two-worker Dask LocalCluster, against the same campaign flown in this process.

The runs are made slow without loading the machine: the arc's program sleeps
``ARC_SLOW`` seconds at each step when that variable is set (as it is in the
subprocess only): a run then takes about a second of wall time, so a worker is
always in the middle of one. Sleeping changes no number of the flight, so the
results must equal the serial reference's bit for bit.
"""

from __future__ import annotations

import os
import select
import signal
import subprocess
import sys
import time

import pandas as pd
import psutil
import pytest

import rocketsim
from tests.campaign_files import write_arc
from tests.unit.campaigns.test_campaign_runs import same_results

SLOW = """\
import os
import time


def main(fc):
    pause = float(os.environ.get("ARC_SLOW", "0"))
    while True:
        fc.step()
        if pause:
            time.sleep(pause)
"""

CAMPAIGN = """\
name: slow
scenario: arc.yaml
runs: 10
seed: 9
dispersions:
  v_north: {path: "mission.start.site.velocity[1]", kind: normal, sigma: 1 %}
  v_up: {path: "mission.start.site.velocity[2]", kind: normal, sigma: 1 %}
"""


@pytest.fixture(scope="module")
def reference(tmp_path_factory):
    folder = tmp_path_factory.mktemp("slow")
    campaign = write_arc(folder, CAMPAIGN, program=SLOW)
    return campaign, rocketsim.campaign(campaign, folder / "serial", workers=1)


def start(campaign, out) -> subprocess.Popen:
    env = {**os.environ, "ARC_SLOW": "0.001"}
    return subprocess.Popen([sys.executable, "-m", "rocketsim_cli.main", "campaign", "run", str(campaign),
                             "-o", str(out), "--workers", "2"], stderr=subprocess.PIPE, stdout=subprocess.PIPE,
                            text=True, env=env)


def wait_for(process: subprocess.Popen, text: str, seconds: float = 120.0) -> str:
    """The subprocess's stderr until a line containing ``text`` (or the deadline)."""
    seen, deadline = "", time.monotonic() + seconds
    while time.monotonic() < deadline:
        ready, _, _ = select.select([process.stderr], [], [], 1.0)
        if ready:
            line = process.stderr.readline()
            seen += line
            if text in line or not line:
                return seen
    return seen


def workers_of(process: subprocess.Popen) -> list[psutil.Process]:
    """The Dask worker processes the campaign's LocalCluster started (multiprocessing
    spawns them; its resource tracker is not one)."""
    found = []
    for child in psutil.Process(process.pid).children(recursive=True):
        command = " ".join(child.cmdline())
        if "spawn_main" in command and "resource_tracker" not in command:
            found.append(child)
    return found


def disturbed(campaign, out, after: str, disturb, seconds: float) -> tuple[int, str]:
    """Fly ``campaign`` in a subprocess, call ``disturb(process)`` once its stderr shows
    ``after``; (exit status, stderr)."""
    process = start(campaign, out)
    try:
        seen = wait_for(process, after)
        assert after in seen, seen
        disturb(process)
        _, err = process.communicate(timeout=seconds)
    finally:
        process.kill()                      # this test's own subprocess, if it is still there
    return process.returncode, seen + err


def kill_a_worker(process: subprocess.Popen) -> None:
    workers = workers_of(process)
    assert len(workers) == 2
    workers[0].kill()                       # SIGKILL: the run it was flying is lost with it
    workers[0].wait(10)


def test_killing_a_worker_mid_campaign_loses_no_run(reference, tmp_path):
    campaign, serial = reference
    status, err = disturbed(campaign, tmp_path / "out", "1/10 runs", kill_a_worker, 180)
    assert status == 0, err
    results = pd.read_parquet(tmp_path / "out" / "results.parquet")
    assert (results["status"] == "ok").all()
    same_results(serial, results)


def test_ctrl_c_then_resume_equals_the_uninterrupted_campaign(reference, tmp_path):
    campaign, serial = reference
    status, err = disturbed(campaign, tmp_path / "out", "3/10 runs",
                            lambda process: process.send_signal(signal.SIGINT), 60)
    assert status == 130, err
    assert "--resume" in err
    saved = pd.read_parquet(tmp_path / "out" / "results.parquet")
    assert 3 <= len(saved) < 10
    flown = []
    rocketsim.campaigns.execute.run(campaign, tmp_path / "out", workers=1, resume=True,
                                    progress=lambda *done: flown.append(done))
    assert flown[-1][0] == 10 - len(saved)
    same_results(serial, pd.read_parquet(tmp_path / "out" / "results.parquet"))
