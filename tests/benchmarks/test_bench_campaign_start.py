"""Benchmark: how soon a large campaign flies its first run, and the memory its inputs take.

A campaign's inputs are drawn lazily (:mod:`rocketsim.campaigns.sampling`,
:class:`rocketsim.campaigns.store.InputsWriter`): the first run flies while the
inputs file is written block by block, and no table of every run is held.
Target: the first run of a campaign of a million runs starts within seconds,
and the peak memory does not grow with the runs.

Printed (``pytest -s``), with the machine's load, for the sampling tests'
nine-dispersion campaign of the vacuum arc (:mod:`tests.unit.campaigns.test_campaign_sampling`),
sampled at random and on a Sobol design, each in a fresh process:

* the campaign flown in that process (``workers=1``) and stopped after its
  first run: the seconds from the call to the first run's start (reading the
  campaign, the nominal run's warm-up flight) and the process's peak resident
  memory;
* the baseline, measured in the same run: drawing every run's inputs as one
  table (:meth:`rocketsim.campaigns.cases.Plan.inputs_table`), the work a
  campaign did before its first run when its inputs were not lazy; its
  seconds, the ratio to the lazy start, and its process's peak memory;
* the same lazy start for a campaign of 100 runs: the memory of the flight alone.

In the suite the campaign has 5 000 runs; with ``ROCKETSIM_BENCH_FULL=1`` a
million (the baseline then takes about a minute).
"""

from __future__ import annotations

import os
import subprocess
import sys

import pytest

from tests.benchmarks.timing import load_text
from tests.conftest import ROOT

FULL = os.environ.get("ROCKETSIM_BENCH_FULL") == "1"
RUNS = 1_000_000 if FULL else 5_000

_SETUP = """
import resource, sys, time
from pathlib import Path
from tests.campaign_files import write_arc
from tests.unit.campaigns.test_campaign_sampling import CAMPAIGN
folder = Path(sys.argv[1]); runs = int(sys.argv[2]); sampling = sys.argv[3]
path = write_arc(folder, CAMPAIGN.format(runs=runs, sampling=sampling))
def peak():
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
"""
LAZY = _SETUP + """
from rocketsim.campaigns.execute import Interrupted, run
start, first = time.perf_counter(), []
def progress(done, failed, total):
    if not first:
        first.append(time.perf_counter() - start)
    if done:
        raise KeyboardInterrupt
try:
    run(path, folder / "out", workers=1, progress=progress)
except Interrupted:
    pass
print(first[0], peak())
"""
TABLE = _SETUP + """
from rocketsim.campaigns.cases import Plan
from rocketsim.campaigns.spec import read_campaign
plan = Plan(read_campaign(path))
start = time.perf_counter()
table = plan.inputs_table()
assert len(table) == runs
print(time.perf_counter() - start, peak())
"""


def _measure(code: str, folder, runs: int, sampling: str) -> tuple[float, float]:
    done = subprocess.run([sys.executable, "-c", code, str(folder), str(runs), sampling], cwd=ROOT,
                          capture_output=True, text=True, timeout=3600)
    assert done.returncode == 0, done.stderr[-2000:]
    seconds, megabytes = done.stdout.split()
    return float(seconds), float(megabytes)


@pytest.mark.parametrize("sampling", ["random", "sobol"])
def test_a_large_campaign_flies_its_first_run_without_drawing_every_input(sampling, tmp_path):
    lazy, lazy_mb = _measure(LAZY, tmp_path / "lazy", RUNS, sampling)
    small, small_mb = _measure(LAZY, tmp_path / "small", 100, sampling)
    table, table_mb = _measure(TABLE, tmp_path / "table", RUNS, sampling)
    print(f"\n[campaign start] {load_text()}; {RUNS:,} runs ({sampling}): first run after {lazy:.2f} s, "
          f"peak {lazy_mb:.0f} MB (100 runs: {small:.2f} s, {small_mb:.0f} MB); every input drawn up front "
          f"(the baseline): {table:.2f} s, {table / lazy:.1f}x the lazy start, peak {table_mb:.0f} MB")
