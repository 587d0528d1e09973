"""Sampled inputs meet their distributions, for pseudo-random, Sobol and LHS designs.

Nothing flies: the inputs come from :class:`rocketsim.campaigns.cases.Plan` at a
fixed seed. The bounds are the sampling errors of ``N`` independent draws at
about 4 standard errors (a false alarm about once in 15 000 per check; the draws
are fixed by the seed, so a test that passes keeps passing): a mean within
``4 sigma / sqrt(N)``; a standard deviation within the two-sided 99.99 %
chi-square interval, ``s^2 (N - 1) / sigma^2`` in ``[chi2(0.00005), chi2(0.99995)]``
with ``N - 1`` degrees of freedom; a correlation within ``4 / sqrt(N - 3)`` in
Fisher's ``atanh(r)``; a choice's frequency within 4 binomial standard errors.
Sobol and LHS designs fill the space more evenly than independent draws, so
the same bounds hold for them with room to spare; LHS's margins are also
exactly stratified (every 1/N bin of each ``u`` holds one run).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import stats

from rocketsim.campaigns.cases import Plan
from rocketsim.campaigns.spec import read_campaign
from tests.campaign_files import ELEVATION, SPEED, write_arc

N = 2048
V_NORTH = SPEED * math.cos(ELEVATION)

CAMPAIGN = """\
name: sampling
scenario: arc.yaml
runs: {runs}
seed: 5
sampling: {sampling}
overrides:
  mission.initial_rates: [0, 0, 0]      # written, so that its items can be set
dispersions:
  v_north: {{path: "mission.start.site.velocity[1]", kind: normal, sigma: 2 %}}
  v_up: {{path: "mission.start.site.velocity[2]", kind: normal, mean: 90 m/s, sigma: 3 m/s}}
  mass: {{path: vehicle.rigid_body.mass, kind: normal, sigma: 10 kg, min: 290 kg, max: 320 kg}}
  elevation: {{path: mission.start.site.elevation, kind: uniform, low: 55 deg, high: 65 deg}}
  step: {{path: step, kind: choice, values: [0.05, 0.04, 0.02], weights: [2, 1, 1]}}
  noise: {{path: seed, kind: seed, low: 10, high: 20}}
  slip: {{kind: slip, low: -30 min, high: 90 min}}
  rate_x: {{path: "mission.initial_rates[0]", kind: normal, mean: 0}}
  rate_y: {{path: "mission.initial_rates[1]", kind: normal, mean: 0}}
correlations:
  - {{names: [v_north, v_up], correlation: [[1, 0.6], [0.6, 1]]}}
  - {{names: [rate_x, rate_y], covariance: [[1.0e-4, -1.2e-4], [-1.2e-4, 4.0e-4]]}}
"""


def plan_of(tmp_path, sampling: str, runs: int = N) -> Plan:
    return Plan(read_campaign(write_arc(tmp_path, CAMPAIGN.format(runs=runs, sampling=sampling))))


def chi2_bounds(n: int) -> tuple[float, float]:
    """The 99.99 % interval of s / sigma for n independent normal draws."""
    lo, hi = stats.chi2.ppf([0.00005, 0.99995], n - 1)
    return math.sqrt(lo / (n - 1)), math.sqrt(hi / (n - 1))


@pytest.fixture(scope="module", params=["random", "sobol", "lhs"])
def drawn(request, tmp_path_factory):
    plan = plan_of(tmp_path_factory.mktemp(request.param), request.param)
    return request.param, plan, plan.inputs_table()


def check_normal(x, mean, sigma):
    n = len(x)
    assert abs(x.mean() - mean) < 4 * sigma / math.sqrt(n)
    lo, hi = chi2_bounds(n)
    assert lo < x.std(ddof=1) / sigma < hi


def test_normals_meet_their_mean_and_sigma(drawn):
    _, _, table = drawn
    check_normal(table["v_north"], V_NORTH, 0.02 * V_NORTH)     # 2 % of the scenario's value
    check_normal(table["v_up"], 90.0, 3.0)
    check_normal(table["rate_x"], 0.0, 0.01)                     # sigmas of the covariance
    check_normal(table["rate_y"], 0.0, 0.02)


def test_correlations_are_met(drawn):
    _, _, table = drawn
    n = len(table)
    for a, b, rho in (("v_north", "v_up", 0.6), ("rate_x", "rate_y", -1.2e-4 / (0.01 * 0.02))):
        r = np.corrcoef(table[a], table[b])[0, 1]
        assert abs(math.atanh(r) - math.atanh(rho)) < 4 / math.sqrt(n - 3)
    # the independent ones are not correlated
    r = np.corrcoef(table["v_north"], table["mass"])[0, 1]
    assert abs(math.atanh(r)) < 4 / math.sqrt(n - 3)


def test_truncated_normal_stays_within_its_bounds_and_has_the_truncated_law(drawn):
    _, _, table = drawn
    x = table["mass"].to_numpy()
    assert x.min() >= 290.0 and x.max() <= 320.0
    law = stats.truncnorm((290 - 300) / 10, (320 - 300) / 10, loc=300, scale=10)
    assert abs(x.mean() - law.mean()) < 4 * law.std() / math.sqrt(len(x))
    assert stats.kstest(x, law.cdf).pvalue > 1e-4


def test_uniforms_choices_seeds_and_slips(drawn):
    sampling, _, table = drawn
    n = len(table)
    low, high = math.radians(55), math.radians(65)
    e = table["elevation"].to_numpy()
    assert e.min() >= low and e.max() <= high
    assert stats.kstest(e, stats.uniform(low, high - low).cdf).pvalue > 1e-4
    slip = table["slip"].to_numpy()
    assert slip.min() >= -1800 and slip.max() <= 5400
    assert abs(slip.mean() - 1800) < 4 * 7200 / math.sqrt(12 * n)
    for value, p in ((0.05, 0.5), (0.04, 0.25), (0.02, 0.25)):
        assert abs((table["step"] == value).mean() - p) < 4 * math.sqrt(p * (1 - p) / n)
    seeds = table["noise"].to_numpy()
    assert seeds.dtype == np.int64 and set(seeds) == set(range(10, 21))
    if sampling == "lhs":       # one run in every 1/N bin of each margin
        u = (e - low) / (high - low)
        assert sorted(np.floor(u * n).astype(int)) == list(range(n))


def test_overrides_carry_the_inputs_in_the_fields_units(tmp_path):
    plan = plan_of(tmp_path, "random", runs=4)
    inputs, overrides = plan.inputs(3), plan.overrides(3)
    assert overrides["mission.start.site.velocity[1]"] == inputs["v_north"]
    # an angle is written in rad, reading back to the same bits
    assert overrides["mission.start.site.elevation"] == f"{inputs['elevation']!r} rad"
    loaded = plan.scenario(3)
    assert loaded.scenario.mission.start.site.elevation == inputs["elevation"]
    assert loaded.scenario.vehicle.rigid_body.mass == inputs["mass"]
    assert loaded.scenario.seed == inputs["noise"]
    epoch = loaded.scenario.mission.epoch
    assert (epoch - plan.base.scenario.mission.epoch).total_seconds() == pytest.approx(inputs["slip"], abs=1e-6)


def test_a_run_draws_from_the_seed_and_its_number_alone(tmp_path):
    """Random and Sobol: run k's inputs do not depend on the number of runs; random:
    adding a dispersion changes no other's draws; LHS: the design is the seed's and
    the number of runs' (documented in rocketsim.campaigns.sampling)."""
    for sampling in ("random", "sobol"):
        few = plan_of(tmp_path / f"{sampling}-few", sampling, runs=5)
        many = plan_of(tmp_path / f"{sampling}-many", sampling, runs=300)
        assert [few.inputs(k) for k in range(5)] == [many.inputs(k) for k in range(5)]
    few = plan_of(tmp_path / "lhs-few", "lhs", runs=5)
    assert few.inputs(2) == plan_of(tmp_path / "lhs-again", "lhs", runs=5).inputs(2)
    base = plan_of(tmp_path / "base", "random", runs=5)
    extra = "dispersions:\n  extra: {path: mission.dut1, kind: uniform, low: -0.1, high: 0.1}\n"
    more = Plan(read_campaign(write_arc(tmp_path / "more", CAMPAIGN.format(runs=5, sampling="random")
                                        .replace("dispersions:\n", extra))))
    for k in range(5):
        before, after = base.inputs(k), more.inputs(k)
        assert {name: after[name] for name in before} == before
