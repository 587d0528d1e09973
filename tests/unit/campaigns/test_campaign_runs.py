"""Campaigns fly the same runs however they are flown, re-fly a case alone, and survive
failed runs.

Reference for the determinism: the campaign flown in this process
(``workers=1``); the same campaign on a two-worker Dask LocalCluster, and one
interrupted after five runs and resumed, give the same results.parquet, every
number bit for bit (``wall_time_s`` aside), and a case re-flown alone with
``rocketsim campaign rerun`` gives its row again, with a telemetry file
``rocketsim replay`` reads.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
from click.testing import CliRunner

import rocketsim
from rocketsim.campaigns.cluster import QUIET_WORKERS, local_cluster
from rocketsim.campaigns.execute import Interrupted, run
from rocketsim_cli.main import main
from tests.campaign_files import MIXED, write_arc


def same_results(a: pd.DataFrame, b: pd.DataFrame) -> None:
    """Same columns, dtypes and values, floats bit for bit (wall times aside)."""
    a, b = a.drop(columns="wall_time_s"), b.drop(columns="wall_time_s")
    assert list(a.columns) == list(b.columns)
    for name in a.columns:
        x, y = a[name].to_numpy(), b[name].to_numpy()
        assert x.dtype == y.dtype, name
        if x.dtype.kind == "f":
            assert np.array_equal(x.view(np.int64), y.view(np.int64)), name
        else:
            assert list(x) == list(y), name


@pytest.fixture(scope="module")
def serial(tmp_path_factory):
    """The mixed campaign flown in this process: (campaign file, its directory)."""
    folder = tmp_path_factory.mktemp("serial")
    campaign = write_arc(folder, MIXED)
    rocketsim.campaign(campaign, folder / "out", workers=1)
    return campaign, folder / "out"


def test_serial_local_cluster_and_resumed_campaigns_are_identical(serial, tmp_path):
    """The cluster is the user's (a LocalCluster of two single-threaded worker processes
    given by its scheduler's address, as --scheduler does); the embedded one is
    flown by tests/unit/campaigns/test_campaign_interrupt.py."""
    from distributed import LocalCluster
    campaign, directory = serial
    reference = pd.read_parquet(directory / "results.parquet")
    assert len(reference) == 12 and (reference["status"] == "ok").all()
    assert pd.read_parquet(directory / "inputs.parquet").shape == (12, 8)
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        rocketsim.campaign(campaign, tmp_path / "cluster", scheduler=cluster.scheduler_address)
    same_results(reference, pd.read_parquet(tmp_path / "cluster" / "results.parquet"))

    def stop_after_five(done, failed, total):
        if done == 5:
            raise KeyboardInterrupt

    with pytest.raises(Interrupted):
        run(campaign, tmp_path / "resumed", workers=1, progress=stop_after_five)
    assert len(pd.read_parquet(tmp_path / "resumed" / "results.parquet")) == 5
    flown = []
    run(campaign, tmp_path / "resumed", workers=1, resume=True, progress=lambda *done: flown.append(done))
    assert flown[-1] == (7, 0, 7)           # exactly the seven missing runs
    same_results(reference, pd.read_parquet(tmp_path / "resumed" / "results.parquet"))


def test_the_embedded_clusters_workers_keep_the_gil_to_the_flight():
    """The embedded cluster's worker runs neither the dashboard's profiler nor the 20 ms
    event-loop tick (each takes the GIL from the flight thread 50-100 times a second):
    its Dask settings are those of QUIET_WORKERS, and its periodic callbacks show them."""
    import dask
    from distributed import Client

    def settings(dask_worker):
        callbacks = dask_worker.periodic_callbacks
        return ({name: dask.config.get(name) for name in QUIET_WORKERS},
                "profile-cycle" in callbacks, callbacks["tick"].callback_time)

    with local_cluster(1) as cluster, Client(cluster) as client:
        (seen,) = client.run(settings).values()
    assert seen == (QUIET_WORKERS, False, 1000.0)


def test_rows_left_in_part_files_by_a_crash_are_read_and_consolidated(serial, tmp_path):
    """A client that dies leaves rows in results/part-*.parquet that results.parquet lacks:
    read_results reads both, and resuming folds them in (and flies only what is missing)."""
    from rocketsim.campaigns.cases import Plan
    from rocketsim.campaigns.spec import read_campaign
    from rocketsim.campaigns.store import Store, read_results
    campaign, directory = serial
    reference = pd.read_parquet(directory / "results.parquet")
    store = Store(tmp_path / "crashed")
    found = read_campaign(campaign)
    store.open(found, Plan(found), resume=False)
    rows = reference.to_dict("records")
    for row in rows[:4]:
        store.add(row)
    store.consolidate()                 # results.parquet: runs 0-3
    for row in rows[4:9]:
        store.add(row)
    store.flush()                       # a part file: runs 4-8; then the client dies
    assert len(pd.read_parquet(tmp_path / "crashed" / "results.parquet")) == 4
    assert list(read_results(tmp_path / "crashed")["run"]) == list(range(9))
    flown = []
    run(campaign, tmp_path / "crashed", workers=1, resume=True, progress=lambda *done: flown.append(done))
    assert flown[-1] == (3, 0, 3)
    assert not list((tmp_path / "crashed" / "results").glob("part-*.parquet"))
    same_results(reference, pd.read_parquet(tmp_path / "crashed" / "results.parquet"))


def test_rerun_reproduces_a_row_bit_for_bit_and_writes_a_replayable_file(serial, tmp_path):
    _, directory = serial
    out = tmp_path / "run-7.mcap"
    result = CliRunner().invoke(main, ["campaign", "rerun", str(directory), "7", "-o", str(out)])
    assert result.exit_code == 0, result.output
    assert "reproduces its row" in result.output and "bit for bit" in result.output
    replay = CliRunner().invoke(main, ["replay", str(out)])
    assert replay.exit_code == 0, replay.output
    assert "impact" in replay.output
    run_file = rocketsim.open_run(out)
    row = pd.read_parquet(directory / "results.parquet").set_index("run").loc[7]
    assert run_file.bodies["slug"].final["latitude_deg"] == row["slug.final.latitude_deg"]
    inputs = pd.read_parquet(directory / "inputs.parquet").set_index("run").loc[7]
    overrides = run_file.metadata["overrides"]
    assert float(overrides["mission.start.site.velocity[1]"]) == inputs["v_north"]


# a program that fails on the runs released fast upwards, and dawdles (sleeps each
# step) on the runs released slowly, beyond the campaign's timeout
FAULTY = """\
import time


def main(fc):
    if fc.vertical_speed > 94.0:
        raise RuntimeError(f"released too fast: {fc.vertical_speed:.2f} m/s")
    slow = fc.vertical_speed < 90.5
    while True:
        fc.step()
        if slow:
            time.sleep(0.01)
"""


def test_failed_runs_are_rows_and_the_others_fly(tmp_path):
    campaign = write_arc(tmp_path, """\
        name: faults
        scenario: arc.yaml
        runs: 16
        seed: 4
        dispersions:
          v_up: {path: "mission.start.site.velocity[2]", kind: normal, sigma: 2 m/s}
        telemetry: failed
        timeout: 0.3 s
        """, program=FAULTY)
    result = CliRunner().invoke(main, ["campaign", "run", str(campaign), "-o", str(tmp_path / "out"),
                                       "--workers", "1"])
    inputs = pd.read_parquet(tmp_path / "out" / "inputs.parquet")
    results = pd.read_parquet(tmp_path / "out" / "results.parquet")
    fast = set(inputs.loc[inputs["v_up"] > 94.0, "run"])
    slow = set(inputs.loc[inputs["v_up"] < 90.5, "run"])
    assert fast and slow and len(fast | slow) < 16          # some of each, and some flew
    assert list(results["run"]) == list(range(16))
    assert set(results.loc[results["status"] == "error", "run"]) == fast
    assert set(results.loc[results["status"] == "timeout", "run"]) == slow
    ok = results[results["status"] == "ok"]
    assert set(ok["run"]) == set(range(16)) - fast - slow and ok["slug.impact.t_s"].notna().all()
    for k in fast:
        assert "released too fast" in results.loc[results["run"] == k, "error"].item()
    # the failures are listed, and the exit status says some runs failed
    assert result.exit_code == 1, result.output
    for k in fast | slow:
        assert f"run {k}: " in result.output
    # the retention keeps the failed runs' telemetry, nothing else
    kept = {int(p.stem.split("-")[1]) for p in (tmp_path / "out" / "runs").glob("run-*.mcap")}
    assert kept == fast
    assert "released too fast" in rocketsim.open_run(tmp_path / "out" / "runs" / f"run-{min(fast):06d}.mcap").outcome
