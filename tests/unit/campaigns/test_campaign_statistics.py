"""The campaign report's statistics (rocketsim.campaigns.statistics) against independent
references: published Clopper-Pearson intervals and the beta/binomial definitions, the
analytic t and chi-square intervals of a normal sample, and the known SRCs and Spearman
correlations of synthetic models (closed forms and quadrature)."""

import math
import warnings

import numpy as np
import pytest
from scipy import integrate, stats

from rocketsim.campaigns.statistics import BOOTSTRAPPED, N_RESAMPLES, describe, proportion, sensitivity

# Newcombe (1998), "Two-sided confidence intervals for the single proportion: comparison of
# seven methods", Statistics in Medicine 17, 857-872, Table I, method 5 (Clopper-Pearson
# "exact"), 95 %, printed to 4 decimals
NEWCOMBE = [((81, 263), (0.2527, 0.3676)), ((15, 148), (0.0578, 0.1617)),
            ((0, 20), (0.0, 0.1684)), ((1, 29), (0.0009, 0.1776))]


@pytest.mark.parametrize(("kn", "published"), NEWCOMBE)
def test_clopper_pearson_matches_newcombes_table(kn, published):
    """Against Newcombe's Table I (4 decimals: within half a unit of the last)."""
    p, low, high = proportion(*kn)
    assert p == kn[0] / kn[1]
    assert low == pytest.approx(published[0], abs=5e-5)
    assert high == pytest.approx(published[1], abs=5e-5)


@pytest.mark.parametrize("n", [1, 10, 50, 400])
def test_clopper_pearson_at_none_and_all_is_the_closed_form(n):
    """k = 0: [0, 1 - (alpha/2)^(1/n)]; k = n: [(alpha/2)^(1/n), 1] (Clopper & Pearson 1934;
    n = 10 gives the textbook 0.3085). Analytic."""
    half_alpha = 0.025
    assert proportion(0, n)[1:] == pytest.approx((0.0, 1.0 - half_alpha ** (1.0 / n)), abs=1e-12)
    assert proportion(n, n)[1:] == pytest.approx((half_alpha ** (1.0 / n), 1.0), abs=1e-12)
    assert 1.0 - half_alpha ** 0.1 == pytest.approx(0.3085, abs=5e-5)


@pytest.mark.parametrize(("k", "n"), [(1, 7), (13, 40), (95, 100), (500, 1000)])
def test_clopper_pearson_ends_leave_half_alpha_in_each_binomial_tail(k, n):
    """The definition: at the lower end P(X >= k) = alpha/2, at the upper P(X <= k) = alpha/2
    (scipy.stats.binom, not the beta quantiles the code uses)."""
    _, low, high = proportion(k, n)
    assert stats.binom.sf(k - 1, n, low) == pytest.approx(0.025, rel=1e-6)
    assert stats.binom.cdf(k, n, high) == pytest.approx(0.025, rel=1e-6)


def test_no_runs_give_no_interval():
    """n = 0 has no proportion (NaN), not an error."""
    assert all(math.isnan(v) for v in proportion(0, 0))


def test_bootstrap_interval_of_a_normal_mean_and_std_matches_the_analytic_ones():
    """A seeded N(10, 3^2) sample of 400: the 95 % bootstrap (percentile) interval of the
    mean against Student's ``mean +- t(0.975, n-1) s / sqrt(n)``, of the standard deviation
    against the chi-square interval ``s sqrt((n-1) / chi2(0.975 | 0.025, n-1))``. The mean's
    ends agree within 10 % of the half-width (999 resamples put about 5 % of Monte Carlo
    noise on an end); the standard deviation's within 25 %: its bootstrap interval leans on
    the sample's own fourth moment, whose sampling error at n = 400 moves the ends by up to
    20 % of the half-width (measured over seeds 0-7)."""
    n = 400
    x = np.random.default_rng(20260101).normal(10.0, 3.0, n)
    out = describe(x, seed=5)
    s = x.std(ddof=1)
    half = stats.t.ppf(0.975, n - 1) * s / math.sqrt(n)
    assert out["mean"] == pytest.approx(x.mean(), rel=1e-14)
    assert out["mean_low"] == pytest.approx(x.mean() - half, abs=0.1 * half)
    assert out["mean_high"] == pytest.approx(x.mean() + half, abs=0.1 * half)
    low = s * math.sqrt((n - 1) / stats.chi2.ppf(0.975, n - 1))
    high = s * math.sqrt((n - 1) / stats.chi2.ppf(0.025, n - 1))
    assert out["std_low"] == pytest.approx(low, abs=0.25 * (high - low) / 2)
    assert out["std_high"] == pytest.approx(high, abs=0.25 * (high - low) / 2)
    # the percentiles are numpy's linear ones, the extremes the sample's
    assert out["p95"] == np.percentile(x, 95) and out["min"] == x.min() and out["max"] == x.max()


def test_bootstrap_median_interval_matches_the_order_statistic_interval():
    """The bootstrap (percentile) interval of the median against the distribution-free one
    from the binomial: order statistics ``j, k`` with ``P(j <= B(n, 1/2) < k) >= 95 %``
    (Conover, *Practical Nonparametric Statistics*, 3.2): within two order-statistic gaps."""
    n = 401
    x = np.sort(np.random.default_rng(7).exponential(2.0, n))
    out = describe(x, seed=11)
    j = int(stats.binom.ppf(0.025, n, 0.5))
    k = int(stats.binom.ppf(0.975, n, 0.5)) + 1
    gap = np.diff(x[j - 3:k + 3]).max()
    assert out["p50_low"] == pytest.approx(x[j - 1], abs=2 * gap)
    assert out["p50_high"] == pytest.approx(x[k - 1], abs=2 * gap)


def test_bootstrap_is_deterministic_for_a_seed():
    """The same sample and seed give the same intervals bit for bit; another seed others."""
    x = np.random.default_rng(3).gamma(2.0, size=300)
    first, again, other = describe(x, seed=[1, 2]), describe(x, seed=[1, 2]), describe(x, seed=[1, 3])
    assert first == again
    assert first["mean_low"] != other["mean_low"]
    assert N_RESAMPLES == 999


def test_describe_of_degenerate_samples():
    """NaN and infinities are not counted; one value has no spread and no interval; nor
    have fewer than 10 values an interval; a repeated value is its own interval (every
    resample is the same sample)."""
    out = describe([np.nan, 4.0, np.inf], seed=0)
    assert out["n"] == 1 and out["mean"] == 4.0 and math.isnan(out["std"]) and math.isnan(out["mean_low"])
    out = describe([2.5] * 10, seed=0)
    assert out["std"] == 0.0 and all(out[f"{s}_low"] == out[s] == out[f"{s}_high"] for s in BOOTSTRAPPED)
    assert describe([0.1] * 64, seed=0)["std"] == 0.0       # np.std gives 1.4e-17 here
    assert describe([], seed=0)["n"] == 0
    nine = describe(np.arange(9.0), seed=0)
    assert nine["mean"] == 4.0 and math.isnan(nine["mean_low"]) and math.isnan(nine["p50_high"])
    assert np.isfinite(describe(np.arange(10.0), seed=0)["mean_low"])


def test_src_of_a_linear_model_are_the_analytic_ones():
    """y = 1.5 x1 - 2 x2 + e, x1 ~ N(0, 2^2), x2 ~ U(-3, 3) (sd sqrt 3), e ~ N(0, 1):
    var y = 9 + 12 + 1 = 22, so SRC = (3, -2 sqrt 3) / sqrt 22 = (0.6396, -0.7385) and
    R^2 = 21/22 (Saltelli et al. 2008, ch. 1). 5000 runs: the SRCs' sampling error is about
    0.005, the tolerance 0.02."""
    rng = np.random.default_rng(42)
    n = 5000
    x = np.column_stack([rng.normal(0.0, 2.0, n), rng.uniform(-3.0, 3.0, n), rng.normal(0.0, 1.0, n)])
    y = 1.5 * x[:, 0] - 2.0 * x[:, 1] + rng.normal(0.0, 1.0, n)
    out = sensitivity(x, y)
    assert out["n"] == n
    assert out["src"] == pytest.approx([3.0 / math.sqrt(22), -2.0 * math.sqrt(3) / math.sqrt(22), 0.0], abs=0.02)
    assert out["r2"] == pytest.approx(21.0 / 22.0, abs=0.01)
    # the unrelated third input is not ranked as a driver
    assert abs(out["spearman"][2]) < 0.05 and out["spearman_p"][2] > 0.001


def _grade_correlation(a: float, b: float, first: bool) -> float:
    """Spearman's population rho of x1 (``first``) or x2 with S = a x1 + b x2, x1, x2
    iid U(0, 1), a >= b > 0: ``12 E[F(x) F_S(S)] - 3`` by quadrature, with the trapezoidal
    CDF of S (any monotone transform of S has the same rho)."""
    def cdf(s):
        if s <= b:
            return s * s / (2 * a * b)
        if s <= a:
            return (s - b / 2) / a
        return 1.0 - (a + b - s) ** 2 / (2 * a * b) if s < a + b else 1.0

    value, _ = integrate.dblquad(lambda u, v: (v if first else u) * cdf(a * v + b * u), 0, 1, 0, 1,
                                 epsabs=1e-10)
    return 12.0 * value - 3.0


def test_spearman_ranks_a_nonlinear_monotone_model_right():
    """y = exp(5 (2 x1 + x2)), x1, x2 iid U(0, 1): a monotone but far from linear model.
    Spearman's rho against the population values by quadrature (0.900 and 0.425: x1 first)
    within 0.02 (about 3 standard errors at 4000 runs); the linear fit explains less
    (R^2 < 0.8), so its SRCs are not the measure to read."""
    rng = np.random.default_rng(9)
    n = 4000
    x = rng.uniform(0.0, 1.0, (n, 2))
    y = np.exp(5.0 * (2.0 * x[:, 0] + x[:, 1]))
    out = sensitivity(x, y)
    expected = [_grade_correlation(2.0, 1.0, True), _grade_correlation(2.0, 1.0, False)]
    assert expected == pytest.approx([0.9, 0.425], abs=1e-8)     # 9/10 and 17/40
    assert out["spearman"] == pytest.approx(expected, abs=0.02)
    assert out["spearman"][0] > out["spearman"][1] > 0
    assert out["r2"] < 0.8


def test_sensitivity_of_constant_and_short_samples_is_nan():
    """A constant input or output has no coefficient; fewer than 3 runs, nothing."""
    x = np.column_stack([np.arange(10.0), np.ones(10)])
    out = sensitivity(x, 2.0 * np.arange(10.0))
    assert out["spearman"][0] == pytest.approx(1.0) and math.isnan(out["spearman"][1])
    assert out["src"][0] == pytest.approx(1.0) and out["r2"] == pytest.approx(1.0)
    assert math.isnan(sensitivity(x, np.ones(10))["r2"])
    assert math.isnan(sensitivity(x[:2], np.arange(2.0))["spearman"][0])
    with warnings.catch_warnings():
        warnings.simplefilter("error")          # scipy warns of a constant input: none is passed on
        wide = np.column_stack([np.arange(64.0), np.full(64, 0.1)])
        assert np.isnan(sensitivity(wide, np.full(64, 0.1))["spearman"]).all()
        assert np.isnan(sensitivity(wide, np.arange(64.0))["spearman"][1])
