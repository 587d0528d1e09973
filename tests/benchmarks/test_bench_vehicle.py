"""Benchmark: mass properties plus nine engines per RK4 derivative stage.

Target: at most 10 us per stage for the vehicle's share. Printed: the powered
derivative of the Falcon 9-class booster (nine Merlin 1D, two tanks, US 1976
pressure lookup) and the coasting rigid-body derivative, both called in a
compiled loop in the same run, their ratio and the difference (the vehicle's
own cost); and a whole powered RK4 step against a coasting one. Times are the
thread's CPU time (steadier than wall time on a shared machine), with the load. Run with
``pytest -s tests/benchmarks``. Nothing here asserts a time; the check is that
the burn does what the rocket equation says.
"""

import math
import time
from pathlib import Path

import numpy as np

from rocketsim.atmosphere.day import standard_table
from rocketsim.constants import EARTH_J2, EARTH_MU, EARTH_RADIUS_EQ, EARTH_RADIUS_POLAR, G0
from rocketsim.dynamics.derivative import derivative
from rocketsim.dynamics.rk4 import advance
from rocketsim.layout import V, make_params
from rocketsim.scenario.load import validate
from rocketsim.scenario.models import VehicleSpec
from rocketsim.scenario.yaml_source import read_yaml
from rocketsim.vehicle.engines import S_DRY, ignite
from rocketsim.vehicle.build import build
from tests.benchmarks.derivative_loops import coasting_derivative_calls, powered_derivative_calls
from tests.benchmarks.timing import best_of, load_text

ROOT = Path(__file__).resolve().parents[2]


def test_mass_properties_and_nine_engines_per_stage():
    booster = build(validate(read_yaml(ROOT / "vehicles" / "falcon9-block5.yaml"), VehicleSpec), last=0)
    a = booster.arrays
    assert booster.n_engines == 9
    y = booster.state([EARTH_RADIUS_EQ + 5e3, 0.0, 0.0], [0.0, 465.0, 0.0])
    for e in range(9):
        ignite(y, a.eng, a.cmd, a.stage, e, a.first_clock)
    y[booster.clocks] = 10.0
    p = make_params(1.0, (1.0, 1.0, 1.0), EARTH_MU, EARTH_RADIUS_EQ, EARTH_J2, EARTH_RADIUS_POLAR)
    rigid = make_params(5e5, (2e5, 1e8, 1e8), EARTH_MU, EARTH_RADIUS_EQ, EARTH_J2, EARTH_RADIUS_POLAR)
    y13 = np.ascontiguousarray(y[:13])
    dy, dy13 = np.zeros_like(y), np.zeros(13)
    powered_derivative_calls(10, y, p, dy, a)
    coasting_derivative_calls(10, y13, rigid, dy13)

    n = 200_000
    t_powered = best_of(3, lambda: powered_derivative_calls(n, y, p, dy, a), time.thread_time)[0] / n
    t_coast = best_of(3, lambda: coasting_derivative_calls(n, y13, rigid, dy13), time.thread_time)[0] / n
    print(f"\n[vehicle] derivative with mass properties + 9 engines: {t_powered * 1e6:.3f} us/stage; "
          f"coasting derivative {t_coast * 1e6:.3f} us/stage; ratio {t_powered / t_coast:.1f}x; "
          f"the vehicle's own share {(t_powered - t_coast) * 1e6:.3f} us (target <= 10 us); {load_text()}")

    # whole steps, in orbit (no impact ends the batch), 40 s of a 150 s burn
    steps = 2_000
    y_orbit = y.copy()
    y_orbit[:6] = (EARTH_RADIUS_EQ + 300e3, 0.0, 0.0, 0.0, 7_700.0, 0.0)
    y13_orbit = np.ascontiguousarray(y_orbit[:13])
    t_step = best_of(3, lambda: advance(y_orbit, 0, 0.02, steps, p, a), time.thread_time)[0] / steps
    t_coast_step = best_of(3, lambda: advance(y13_orbit, 0, 0.02, steps, rigid), time.thread_time)[0] / steps
    assert advance(y_orbit, 0, 0.02, steps, p, a)[1] == steps and a.stage[0, S_DRY] == 0.0
    print(f"[vehicle] powered RK4 step (20 ms): {t_step * 1e6:.2f} us = {0.02 / t_step:,.0f}x real "
          f"time; coasting step {t_coast_step * 1e6:.2f} us; ratio {t_step / t_coast_step:.1f}x; {load_text()}")

    # correctness: at 5 km over the equator, body x up: a = 9 (T_vac - p_a A_e) / m - g(J2)
    derivative(0.0, y, p, dy, a)
    mass = booster.mass_properties(y)[0]
    p_a = standard_table().at(5e3)[1][0]
    r = EARTH_RADIUS_EQ + 5e3
    gravity = EARTH_MU / r ** 2 * (1 + 1.5 * EARTH_J2 * (EARTH_RADIUS_EQ / r) ** 2)
    expected = 9 * (914.1e3 - p_a * 0.680) / mass - gravity
    assert math.isclose(dy[V], expected, rel_tol=1e-12)
    assert math.isclose(-dy[booster.tanks].sum(), 9 * 914.1e3 / (G0 * 311), rel_tol=1e-12)
