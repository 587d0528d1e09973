"""Benchmark: how often the Falcon 9-class booster lands upright on LZ-1 through random days.

The shipped campaign ``campaigns/falcon9-landing.yaml``: the mission of
``scenarios/falcon9-leo.yaml`` flown until the booster is down, on realistic
sensors (both programs read the navigation estimate), each run through a seeded
random day (a jet stream of 10 to 60 m/s), with the booster's engine thrust and
specific impulse and its dry mass dispersed. Target: upright within 10 m of the pad
in at least 99 % of 500 runs, the median miss within 3 m, touchdown within 2 m/s down
and 0.5 m/s sideways; the propellant kept at touchdown printed (its mean and 1st
percentile: the margin).

In the suite the campaign's first SUITE_RUNS runs are flown in this process
(``workers=1``): a run of the whole mission on realistic sensors is a long flight,
so one keeps the suite inside its budget: it must fly, and its booster land
upright within 10 m of the pad. With ``ROCKETSIM_BENCH_FULL=1`` all 500 are flown on
two workers and the share upright within 10 m is asserted against the target.
Nothing asserts a time.

Printed (``pytest -s``), with the machine's load: the report's landing lines (the
outcomes with their exact Clopper-Pearson intervals, the miss, the touchdown speeds,
the propellant kept: mean and 1st percentile), the runs' wall times.

``ROCKETSIM_BENCH_LANDING_DIR`` names the campaign's folder (else a temporary one):
it survives the run, ``rocketsim campaign report`` reads it, and a benchmark started
again on it flies only the runs missing (a campaign resumed).
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import pytest
import yaml

from rocketsim.campaigns.execute import run
from rocketsim.campaigns.landing import OUTCOMES
from rocketsim.campaigns.report import report
from tests.benchmarks.timing import load_text

ROOT = Path(__file__).resolve().parents[2]
CAMPAIGN = ROOT / "campaigns" / "falcon9-landing.yaml"
FULL = os.environ.get("ROCKETSIM_BENCH_FULL") == "1"
SUITE_RUNS = 1
BOOSTER = "booster"                 # the booster's body after separation


@pytest.fixture(scope="module")
def campaign(tmp_path_factory):
    """The shipped campaign flown (SUITE_RUNS runs, or all of them with ROCKETSIM_BENCH_FULL=1):
    its results table, with the report's landing lines printed."""
    campaign = yaml.safe_load(CAMPAIGN.read_text())
    if not FULL:
        campaign["runs"] = SUITE_RUNS
    named = os.environ.get("ROCKETSIM_BENCH_LANDING_DIR")
    directory = Path(named) if named else tmp_path_factory.mktemp("landing") / "campaign"
    resume = (directory / "campaign.yaml").exists()
    results = run(campaign, directory, workers=2 if FULL else 1, base_dir=CAMPAIGN.parent, resume=resume)
    print(f"\nlanding campaign ({load_text()}): {len(results)} runs, "
          f"{int((results['status'] == 'ok').sum())} ok; run wall time median "
          f"{np.median(results['wall_time_s']):.1f} s (min {results['wall_time_s'].min():.1f}, "
          f"max {results['wall_time_s'].max():.1f})")
    text = report(directory).text
    print(next((block for block in text.split("\n\n") if block.startswith("landing of ")), text))
    return results


def test_every_run_flies_and_the_booster_comes_down_with_a_named_outcome(campaign):
    ok = (campaign["status"] == "ok").to_numpy()
    assert ok.all(), campaign.loc[~ok, ["run", "error"]]
    assert set(campaign[f"{BOOSTER}.landing.outcome"]) <= set(OUTCOMES)


def test_the_booster_lands_upright_on_the_pad(campaign):
    outcome = campaign[f"{BOOSTER}.landing.outcome"].to_numpy(object)
    if FULL:
        assert len(campaign) >= 500 and np.mean(outcome == "upright on target") >= 0.99
    else:
        assert (outcome == "upright on target").all(), outcome
