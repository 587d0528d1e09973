"""Landing outcomes: each run's ``<body>.landing.outcome`` from its events, and the report
that leads with the upright-on-target share and keeps wrecks out of the landings' ellipses.

The outcomes follow the rules of rocketsim/campaigns/landing.py (first that applies:
broke up, tipped over, ran dry, impact, under a parachute, hard landing, upright on or
off target), checked here event by event. The report is checked on a synthetic campaign
(tests/unit/campaigns/test_campaign_report.py's construction) whose outcomes are drawn here: the counts
written, the beta quantiles of Clopper-Pearson (scipy), the upright landings' scatter
against pymap3d's east/north of the points written.
"""

import json

import numpy as np
import pandas as pd
import pymap3d
import pytest
from scipy import stats

from rocketsim.campaigns.landing import landing_outcome
from rocketsim.campaigns.outputs import summary_columns
from rocketsim.campaigns.report import report
from tests.unit.campaigns.test_campaign_report import TARGET, synthetic, write_campaign


def touchdown(down=1.2, sideways=0.4, distance=3.0, **more):
    return (300.0, {"vertical_speed_m_s": -down, "horizontal_speed_m_s": sideways,
                    "distance_to_target_m": distance, **more})


@pytest.mark.parametrize("events, expected", [
    ({"touchdown": touchdown()}, "upright on target"),
    ({"touchdown": touchdown(distance=10.5)}, "upright off target"),
    ({"touchdown": touchdown(down=3.5)}, "hard landing"),
    ({"touchdown": touchdown(sideways=2.5)}, "hard landing"),
    ({"touchdown": touchdown(sideways=9.5), "tip-over": (301.0, {})}, "tipped over"),
    ({"impact": (300.0, {})}, "impact"),
    ({"stage_dry": (290.0, {}), "impact": (300.0, {})}, "ran dry"),
    ({"impact": (300.0, {}), "stage_dry": (301.0, {})}, "impact"),       # dry only after the crash
    ({"breakup": (200.0, {}), "impact": (300.0, {})}, "broke up"),
    ({"touchdown": touchdown(drift_time_s=40.0)}, "under a parachute"),
    ({"ignition": (2.0, {})}, None),                                   # still flying
])
def test_each_outcome_follows_its_rule(events, expected):
    assert landing_outcome(events) == expected


def test_a_run_row_names_its_bodies_outcomes():
    events = [{"t": 2.0, "body": "booster", "name": "ignition", "figures": {}},
              {"t": 300.0, "body": "booster", "name": "touchdown",
               "figures": {"vertical_speed_m_s": -1.4, "horizontal_speed_m_s": 9.0, "distance_to_target_m": 2.0,
                           "latitude_deg": 28.4858, "longitude_deg": -80.5444}},
              {"t": 301.5, "body": "booster", "name": "tip-over", "figures": {}},
              {"t": 250.0, "body": "fairing", "name": "impact", "figures": {"latitude_deg": 29.0,
                                                                              "longitude_deg": -79.0}}]
    row = summary_columns(None, events)
    assert row["booster.landing.outcome"] == "tipped over" and row["booster.landing.kind"] == "touchdown"
    assert row["fairing.landing.outcome"] == "impact"
    assert "stage2.landing.outcome" not in row


@pytest.fixture(scope="module")
def landed(tmp_path_factory):
    """The synthetic campaign with a drawn outcome per ok run and the propellant kept."""
    directory, truth = synthetic(tmp_path_factory.mktemp("outcomes") / "dir")
    results = pd.read_parquet(directory / "results.parquet")
    inputs = pd.read_parquet(directory / "inputs.parquet")
    rng = np.random.default_rng(3)
    n = len(results)
    outcome = np.where(truth["impact"], "impact",
                       rng.choice(["upright on target", "upright off target", "tipped over", "hard landing"],
                                  n, p=(0.7, 0.1, 0.1, 0.1))).astype(object)
    results["booster.landing.outcome"] = outcome
    results["booster.ignition.t_s"] = 2.0
    results["booster.final.usable_propellant_kg"] = rng.normal(4000.0, 100.0, n)
    results["booster.touchdown.distance_to_target_m"] = np.hypot(truth["east"], truth["north"])
    meta = json.loads((directory / "meta.json").read_text())
    write_campaign(directory, meta, inputs, results)
    return report(directory), truth, outcome, results


def test_the_headline_is_the_upright_on_target_share_with_its_interval(landed):
    rep, truth, outcome, _ = landed
    ok = truth["ok"]
    k, n = int(np.sum(outcome[ok] == "upright on target")), int(ok.sum())
    low, high = stats.beta.ppf(0.025, k, n - k + 1), stats.beta.ppf(0.975, k + 1, n - k)
    table = rep.tables["outcomes"].set_index("outcome")
    assert table.loc["upright on target", "k"] == k and table.loc["upright on target", "n"] == n
    assert (table.loc["upright on target", "low"], table.loc["upright on target", "high"]) == pytest.approx(
        (low, high), abs=1e-9)
    assert table.loc["tipped over", "k"] == np.sum(outcome[ok] == "tipped over")
    first = rep.text.split("landing of booster at ")[1].splitlines()
    assert first[1].startswith(f"  upright within 10 m: {k} of {n}")
    assert "usable propellant left at touchdown" in rep.text


def test_the_ellipses_keep_the_upright_landings_apart_from_the_wrecks(landed):
    rep, truth, outcome, _ = landed
    ok = truth["ok"]
    upright = ok & np.isin(outcome, ("upright on target", "upright off target", "hard landing"))
    assert set(rep.dispersions) == {"booster upright", "booster crashed", "fairing"}
    assert rep.dispersions["booster upright"].n == upright.sum()
    assert rep.dispersions["booster crashed"].n == (ok & ~upright).sum()
    east, north, _ = pymap3d.geodetic2enu(truth["lat"][upright], truth["lon"][upright], 0.0,
                                          TARGET["latitude_deg"], TARGET["longitude_deg"], 0.0)
    assert rep.dispersions["booster upright"].mean == pytest.approx([east.mean(), north.mean()], abs=1e-3)
