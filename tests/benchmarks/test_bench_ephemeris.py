"""Benchmark: the solar-system state (prints figures; asserts only correctness).

Run with ``python -m pytest tests/benchmarks/test_bench_ephemeris.py -s``.
Targets: the full state of the Sun, Earth, Moon and Mars
(positions and velocities) at one instant in at most 50 us, and at least
100 000 instants per second vectorised over an array of times. Both are
printed against the baseline measured in the same run: the same kernels
evaluating the full, untruncated series (VSOP87D 2425 + 5483 terms,
ELP2000-82B main problem 2645 terms) read from ../shared/data.
"""

from __future__ import annotations

import numpy as np
import pytest

from rocketsim.ephemeris import generate, solar_system
from rocketsim.timescales import calendar_jd
from tests.benchmarks.timing import best_of

N = 20_000          # instants of the vectorised figure (a 141 x 141 porkchop grid)
N_FULL = 2_000      # the full series are ~10x slower: fewer instants, same per-instant figure
SINGLE = 2_000      # repetitions of the one-instant call


def test_bench_solar_system_state():
    if not (generate.DEFAULT_DATA / "vsop87d").is_dir():
        pytest.skip("the full series (the baseline) are not in ../shared/data")
    full = generate.prepared_full()
    jd = np.linspace(calendar_jd(2026, 1, 1.0), calendar_jd(2031, 1, 1.0), N)
    jd0 = calendar_jd(2026, 11, 26.5)
    solar_system.states(jd0)                              # compile / load outside the timing
    solar_system.heliocentric_states(jd[:2], *full)

    def one_instant():
        for _ in range(SINGLE):
            field = solar_system.states(jd0, center="earth")
        return field

    t_single, _ = best_of(5, one_instant)
    # the same entry point for both series, one instant per call
    t_kernel, _ = best_of(5, lambda: [solar_system.heliocentric_states(jd0)
                                      for _ in range(SINGLE)])
    t_single_full, _ = best_of(3, lambda: [solar_system.heliocentric_states(jd0, *full)
                                           for _ in range(SINGLE // 10)])
    t_vector, truncated = best_of(5, lambda: solar_system.heliocentric_states(jd))
    t_vector_full, reference = best_of(3, lambda: solar_system.heliocentric_states(jd[:N_FULL], *full))

    per_single = t_single / SINGLE * 1e6
    per_kernel = t_kernel / SINGLE * 1e6
    per_single_full = t_single_full / (SINGLE // 10) * 1e6
    rate = N / t_vector
    rate_full = N_FULL / t_vector_full
    # correctness only: the truncation error over these instants (km)
    error = np.linalg.norm(truncated[:N_FULL, :, :3] - reference[:, :, :3], axis=2).max(axis=0) / 1e3
    geocentric = truncated[:N_FULL, 2, :3] - truncated[:N_FULL, 1, :3]
    moon = np.linalg.norm(geocentric - (reference[:, 2, :3] - reference[:, 1, :3]), axis=1).max() / 1e3
    assert error[1] < 300.0 and error[3] < 300.0 and moon < 1.0
    print(f"\nsolar-system state (Sun, Earth, Moon, Mars; r and v), 2026-2031:"
          f"\n  one instant, states()        {per_single:8.1f} us   (target <= 50 us)"
          f"\n  one instant, heliocentric_states(), truncated {per_kernel:8.1f} us"
          f"\n  one instant, heliocentric_states(), full      {per_single_full:8.1f} us   (baseline)"
          f"\n  vectorised over {N} dates {rate:10.0f} instants/s (target >= 100 000)"
          f"\n  vectorised, full series      {rate_full:10.0f} instants/s (baseline)"
          f"\n  speed-up vs full series      {per_single_full / per_kernel:8.1f}x one instant,"
          f" {rate / rate_full:5.1f}x vectorised"
          f"\n  truncation error (max km)    Earth {error[1]:.1f}, Mars {error[3]:.1f},"
          f" Moon about the Earth {moon:.2f}")
