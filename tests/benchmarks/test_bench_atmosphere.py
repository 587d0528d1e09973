"""Benchmark: the 50 m table lookup against evaluating the 1976 standard directly.

Targets: at most 2 us per scalar lookup (as the flight loop calls it:
from compiled code) and at least 5 million heights per second vectorised,
each reported as a ratio against evaluating the 1976 model directly
(:func:`us_standard_1976`, numpy-vectorised) in the same run. Run with ``-s``
to see the figures; nothing here asserts a time, only that the lookups agree
with the direct model.
"""

import numba
import numpy as np
import pytest

from rocketsim.atmosphere.day import standard_table
from rocketsim.atmosphere.table import air_at
from rocketsim.atmosphere.ussa1976 import us_standard_1976
from tests.benchmarks.timing import best_of


@numba.njit(cache=False)
def _flight_loop_like(h0, dh, rho, p, t, a, we, wn, heights):
    """Call the scalar lookup once per height from compiled code, as the RK4 stages do."""
    total = 0.0
    for j in range(heights.shape[0]):
        r = air_at(h0, dh, rho, p, t, a, we, wn, heights[j])
        total += r[0] + r[1] + r[2] + r[3]
    return total


def _best(fn, repeat=3):
    return best_of(repeat, fn)[0]


def test_bench_atmosphere_lookup():
    table = standard_table()
    args = table.arrays()
    rng = np.random.default_rng(0)
    heights = rng.uniform(0.0, 120_000.0, 1_000_000)
    few = heights[:2_000]

    _flight_loop_like(*args, few)                      # compile
    air_at(*args, 1000.0)
    table.at(few)

    n = len(heights)
    t_compiled = _best(lambda: _flight_loop_like(*args, heights)) / n
    t_python_call = _best(lambda: [air_at(*args, h) for h in few]) / len(few)
    t_direct_scalar = _best(lambda: [us_standard_1976(h) for h in few[:300]]) / 300
    t_vector = _best(lambda: table.at(heights))
    t_direct_vector = _best(lambda: us_standard_1976(heights), repeat=1)

    print()
    print(f"scalar lookup inside a compiled loop : {t_compiled * 1e9:8.1f} ns/call "
          f"(x{t_direct_scalar / t_compiled:,.0f} faster than us_standard_1976 per scalar call, "
          f"{t_direct_scalar * 1e6:.1f} us)")
    print(f"scalar lookup called from Python     : {t_python_call * 1e6:8.2f} us/call "
          f"(x{t_direct_scalar / t_python_call:,.0f} faster than the direct scalar call)")
    print(f"vectorised lookup                    : {n / t_vector / 1e6:8.1f} M heights/s "
          f"(x{t_direct_vector / t_vector:.1f} the direct model's "
          f"{n / t_direct_vector / 1e6:.2f} M heights/s)")

    rho, p, t, a, _, _ = table.at(heights[:50_000])
    direct = us_standard_1976(heights[:50_000])
    # (3.8e-4: a row straddling the 11 km tropopause kink, see test_atmosphere_table.py)
    np.testing.assert_allclose(rho, direct.density, rtol=3.8e-4)
    np.testing.assert_allclose(a, direct.speed_of_sound, rtol=3.8e-4)
    expected = float(np.sum(rho + p + t + a))
    assert _flight_loop_like(*args, heights[:50_000]) == pytest.approx(expected, rel=1e-12)
