"""Benchmark: Earth-fixed -> geodetic conversion (prints figures; asserts only correctness).

Run with ``python -m pytest tests/benchmarks/test_bench_geodetic.py -s``.
Figures: nanoseconds per point of the compiled core looped in numba (what a
kernel pays), of the same through the vectorised Python entry point, and
the ratio against pymap3d's numpy-vectorised ``ecef2geodetic`` on the same
points measured in the same run (the baseline).
"""


import numpy as np
import pymap3d

from tests.benchmarks.timing import best_of
from rocketsim.frames.geodetic import _ecef_to_geodetic_rows, ecef_to_geodetic, geodetic_to_ecef

N = 200_000


def test_bench_ecef_to_geodetic():
    rng = np.random.default_rng(7)
    lat = np.arcsin(rng.uniform(-1.0, 1.0, N))
    lon = rng.uniform(-np.pi, np.pi, N)
    h = rng.uniform(-1000.0, 1e6, N)
    r = np.ascontiguousarray(geodetic_to_ecef(lat, lon, h))
    _ecef_to_geodetic_rows(r[:10])            # compile (or load from cache) outside the timing

    t_core, rows = best_of(5, lambda: _ecef_to_geodetic_rows(r))
    t_api, (_, _, h_api) = best_of(5, lambda: ecef_to_geodetic(r))
    t_ref, (_, _, h_ref) = best_of(5, lambda: pymap3d.ecef2geodetic(r[:, 0], r[:, 1], r[:, 2], deg=False))

    assert np.max(np.abs(rows[:, 2] - h)) < 1e-3
    assert np.max(np.abs(h_api - h_ref)) < 1e-3
    print(f"\necef_to_geodetic over {N} points (-1 km .. 1000 km):"
          f"\n  compiled core loop    {t_core / N * 1e9:8.1f} ns/point"
          f"\n  vectorised entry      {t_api / N * 1e9:8.1f} ns/point"
          f"\n  pymap3d (baseline)    {t_ref / N * 1e9:8.1f} ns/point"
          f"\n  speed-up vs baseline  {t_ref / t_api:8.1f}x")
