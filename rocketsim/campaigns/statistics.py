"""The statistics of a campaign's outputs: pure functions of arrays, no files, no plots.

- :func:`describe`: the mean, the standard deviation (``ddof=1``), the 1/5/50/95/99th
  percentiles (numpy's default, linear interpolation between order statistics: Hyndman &
  Fan 1996 definition 7), the minimum and the maximum of a sample, with bootstrap
  confidence intervals (``scipy.stats.bootstrap``, **percentile method**, 999 resamples,
  95 %) for all but the minimum and the maximum (a bootstrap interval of an extreme is
  degenerate: no resample goes beyond the sample), from 10 values up. Seeded, so the same
  sample and seed give the same interval bit for bit. The percentile method rather than
  BCa: BCa's jackknife costs one evaluation per run and its acceleration is unstable for
  the tail percentiles of small samples; the percentile interval is what Efron &
  Tibshirani (1993, ch. 13) give for a statistic whose bootstrap distribution is
  near-symmetric, as these are for the sample sizes of a campaign.
- :func:`proportion`: the share of runs with an outcome with its exact binomial
  (Clopper-Pearson 1934) interval, ``scipy.stats.binomtest(k, n).proportion_ci(method="exact")``:
  the beta quantiles ``B(alpha/2; k, n-k+1)`` and ``B(1-alpha/2; k+1, n-k)``, which
  never undercover (conservative).
- :func:`sensitivity`: how each dispersed input drives an output: Spearman's rank
  correlation (Pearson's on average ranks: any monotone relation, linear or not) and the
  standardized regression coefficients (SRC: the least-squares slopes of the output on the
  inputs, all scaled to zero mean and unit standard deviation) with the fit's R². For
  independent inputs and a linear output, ``SRC_i = a_i sigma_i / sigma_y`` and the squared
  SRCs sum to R² (Saltelli et al. 2008, *Global Sensitivity Analysis: The Primer*, ch. 1);
  an R² well below 1 says the output is not linear in the inputs and Spearman is the
  measure to read.

docs/physics.md#campaign-statistics gives the formulas and the tests that check them.
"""

from __future__ import annotations

import numpy as np

CONFIDENCE = 0.95                       # of every interval the report gives
PERCENTILES = (1.0, 5.0, 50.0, 95.0, 99.0)
N_RESAMPLES = 999                       # bootstrap resamples: a 95 % percentile interval's
                                        # ends are the 25th and 975th of 999 sorted values
BOOTSTRAP_METHOD = "percentile"
MIN_BOOTSTRAP = 10                      # values below which no interval is given: a resample of
                                        # a few values is no picture of the sampling distribution
_BATCH = 100                            # resamples evaluated at a time (bounded memory)

# the statistics with a bootstrap interval, in the order of _statistics' rows
BOOTSTRAPPED = ("mean", "std", *(f"p{p:g}" for p in PERCENTILES))


def _statistics(x, axis=-1):
    """The rows of :data:`BOOTSTRAPPED` of ``x`` along ``axis``."""
    return np.stack([np.mean(x, axis=axis), np.std(x, axis=axis, ddof=1),
                     *np.percentile(x, PERCENTILES, axis=axis)])


def describe(values, seed, *, confidence: float = CONFIDENCE, n_resamples: int = N_RESAMPLES) -> dict:
    """Statistics of the finite entries of ``values`` (NaN and infinities are left out and
    not counted): ``n``, then each of :data:`BOOTSTRAPPED` with ``<name>_low`` and
    ``<name>_high`` (the bootstrap interval at ``confidence``), ``min`` and ``max``.

    ``seed`` is anything :func:`numpy.random.default_rng` takes (an int, a sequence of
    ints): the resampling draws from that stream alone. One value has no standard
    deviation; fewer than :data:`MIN_BOOTSTRAP` values have no intervals (NaN); a sample of
    one repeated value has a spread of exactly 0 and that value as its own interval (every
    resample is the same).
    """
    x = np.asarray(values, dtype=float)
    x = x[np.isfinite(x)]
    out: dict = {"n": int(x.size)}
    if x.size == 0:
        return out | {k: np.nan for name in BOOTSTRAPPED for k in (name, f"{name}_low", f"{name}_high")} \
            | {"min": np.nan, "max": np.nan}
    constant = bool(np.all(x == x[0]))
    if x.size < 2:
        point = np.array([x[0], np.nan, *[x[0]] * len(PERCENTILES)])
    elif constant:                          # every statistic the value, the spread exactly 0
        point = np.array([x[0], 0.0, *[x[0]] * len(PERCENTILES)])
    else:
        point = _statistics(x)
    if x.size < MIN_BOOTSTRAP:
        low = high = np.full(len(BOOTSTRAPPED), np.nan)
    elif constant:
        low = high = point
    else:
        from scipy import stats     # here: scipy.stats is slow to import
        result = stats.bootstrap((x,), _statistics, n_resamples=n_resamples, batch=_BATCH,
                                 vectorized=True, confidence_level=confidence,
                                 method=BOOTSTRAP_METHOD, random_state=np.random.default_rng(seed))
        low, high = result.confidence_interval
    for name, value, lo, hi in zip(BOOTSTRAPPED, point, low, high):
        out[name] = float(value)
        out[f"{name}_low"] = float(lo)
        out[f"{name}_high"] = float(hi)
    out["min"] = float(x.min())
    out["max"] = float(x.max())
    return out


def proportion(k: int, n: int, confidence: float = CONFIDENCE) -> tuple[float, float, float]:
    """``(k / n, low, high)``: the share of ``n`` runs with an outcome seen in ``k`` of them
    and its exact Clopper-Pearson interval at ``confidence`` (NaN for ``n = 0``). At
    ``k = 0`` the interval is ``[0, 1 - (alpha/2)^(1/n)]``, at ``k = n``
    ``[(alpha/2)^(1/n), 1]``, ``alpha = 1 - confidence``."""
    if n == 0:
        return np.nan, np.nan, np.nan
    from scipy import stats
    interval = stats.binomtest(int(k), int(n)).proportion_ci(confidence_level=confidence, method="exact")
    return k / n, float(interval.low), float(interval.high)


def sensitivity(inputs, output) -> dict:
    """How the columns of ``inputs`` (array (n, m): one row per run, one column per input)
    drive ``output`` (n,): ``spearman`` (m,) Spearman's rho of each input with the output
    (``scipy.stats.spearmanr``, ties given their average rank), ``spearman_p`` (m,) its
    two-sided p-value (the t approximation with n - 2 degrees of freedom: a rho of 0.1 is
    not told from 0 below about 400 runs), ``src`` (m,) the standardized regression
    coefficients and ``r2`` the fit's coefficient of determination.

    Rows with a non-finite entry are left out, and ``n`` says how many were used. An input
    or an output that does not vary has NaN coefficients (and is left out of the fit); the
    fit needs more runs than inputs plus one, or its SRCs and R² are NaN.
    """
    x = np.asarray(inputs, dtype=float)
    y = np.asarray(output, dtype=float)
    keep = np.isfinite(y) & np.all(np.isfinite(x), axis=1)
    x, y = x[keep], y[keep]
    n, m = x.shape
    out = {"n": int(n), "spearman": np.full(m, np.nan), "spearman_p": np.full(m, np.nan),
           "src": np.full(m, np.nan), "r2": np.nan}
    if n < 3:
        return out
    varied = np.ptp(x, axis=0) > 0.0      # (not std > 0: the std of equal values can be 1e-17)
    if np.ptp(y) == 0.0 or not varied.any():
        return out
    sx = x.std(axis=0, ddof=1)
    sy = y.std(ddof=1)
    from scipy import stats
    for j in np.flatnonzero(varied):
        result = stats.spearmanr(x[:, j], y)
        out["spearman"][j] = result.statistic
        out["spearman_p"][j] = result.pvalue
    used = np.flatnonzero(varied)
    if n > used.size + 1:
        z = (x[:, used] - x[:, used].mean(axis=0)) / sx[used]
        w = (y - y.mean()) / sy
        coefficients, *_ = np.linalg.lstsq(z, w, rcond=None)
        residual = w - z @ coefficients
        out["src"][used] = coefficients
        out["r2"] = float(1.0 - residual @ residual / (w @ w))
    return out
