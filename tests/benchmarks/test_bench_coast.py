"""Benchmark: one coasting rigid body with J2 at 20 ms.

Target: at least 1 000x real time (<= 20 us per step) on one core. Printed:
the compiled kernel's cost per step and its real-time factor, the ratio
against a plain-numpy RK4 of the same equations measured in the same run,
and the whole `fly` loop with 10 Hz telemetry (a fresh process's start-up, cold
and warm: test_bench_startup.py). Run with ``pytest -s tests/benchmarks`` to see
the figures.
Nothing here asserts a time; the checks are that both integrators agree.
"""

import math
import time
from pathlib import Path

import numpy as np

from rocketsim.constants import EARTH_J2, EARTH_MU, EARTH_RADIUS_EQ, EARTH_RADIUS_POLAR
from rocketsim.dynamics.rk4 import advance
from rocketsim.layout import make_params, make_state
from rocketsim.frames.elements import elements_to_state
from tests.benchmarks.timing import best_of

H = 0.02
ROOT = Path(__file__).resolve().parents[2]


def numpy_derivative(y, inertia):
    """The same equations as rocketsim.dynamics.derivative, in plain numpy."""
    r, v, q, w = y[0:3], y[3:6], y[6:10], y[10:13]
    rn = np.linalg.norm(r)
    z2 = r[2] ** 2 / rn ** 2
    k = 1.5 * EARTH_J2 * EARTH_MU * EARTH_RADIUS_EQ ** 2 / rn ** 5
    a = -EARTH_MU * r / rn ** 3 - k * r * np.array([1 - 5 * z2, 1 - 5 * z2, 3 - 5 * z2])
    qw, qv = q[0], q[1:]
    dq = 0.5 * np.concatenate(([-qv @ w], qw * w + np.cross(qv, w)))
    dw = -np.cross(w, inertia * w) / inertia
    return np.concatenate((v, a, dq, dw))


def numpy_rk4(y, h, n, inertia):
    for _ in range(n):
        k1 = numpy_derivative(y, inertia)
        k2 = numpy_derivative(y + 0.5 * h * k1, inertia)
        k3 = numpy_derivative(y + 0.5 * h * k2, inertia)
        k4 = numpy_derivative(y + h * k3, inertia)
        y = y + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        y[6:10] /= np.linalg.norm(y[6:10])
    return y


def test_coasting_body_speed():
    inertia = np.array([0.15, 0.12, 0.05])
    r, v = elements_to_state(EARTH_RADIUS_EQ + 415e3, 0.0005, math.radians(51.6), 1.0, 0.2, 0.3, EARTH_MU)
    y0 = make_state(r, v, w=(0.01, 0.002, -0.003))
    p = make_params(10.0, inertia, EARTH_MU, EARTH_RADIUS_EQ, EARTH_J2, EARTH_RADIUS_POLAR)
    advance(y0, 0, H, 10, p)                                    # compile or load from cache

    n_kernel, n_numpy = 100_000, 2_000
    t_kernel, (y_kernel, _) = best_of(3, lambda: advance(y0, 0, H, n_kernel, p))
    t_numpy, y_numpy = best_of(2, lambda: numpy_rk4(y0.copy(), H, n_numpy, inertia))
    y_check, _ = advance(y0, 0, H, n_numpy, p)
    assert np.allclose(y_check[:6], y_numpy[:6], rtol=1e-12, atol=1e-6)   # same equations

    per_step_kernel = t_kernel / n_kernel
    per_step_numpy = t_numpy / n_numpy
    print(f"\n[coast] compiled RK4 + J2: {per_step_kernel * 1e6:.2f} us/step = "
          f"{H / per_step_kernel:,.0f}x real time (target >= 1 000x, <= 20 us/step)")
    print(f"[coast] plain numpy RK4 of the same equations: {per_step_numpy * 1e6:.1f} us/step; "
          f"compiled is {per_step_numpy / per_step_kernel:.0f}x faster")


def test_fly_loop_with_telemetry_speed(tmp_path):
    from rocketsim.scenario.load import load
    from rocketsim.api.telemetry_flight import fly_to_file as fly
    loaded = load(ROOT / "scenarios" / "iss-coast.yaml")
    fly(loaded, tmp_path / "warm.mcap", duration=1.0)
    duration = 600.0
    start = time.perf_counter()
    fly(loaded, tmp_path / "run.mcap", duration=duration)
    wall = time.perf_counter() - start
    print(f"\n[coast] rocketsim fly iss-coast, 10 Hz telemetry: {duration / wall:,.0f}x real time "
          f"({wall / (duration / H) * 1e6:.1f} us per 20 ms step, telemetry included)")
