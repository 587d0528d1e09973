"""Benchmark: the full derivative of a nine-engine first stage in the atmosphere.

Target: at most 30 us per evaluation (gravity, air table, axial + crossflow
aero over 20 segments, four grid fins, nine gimballed engines, mass properties),
so a 20 ms step stays under about 130 us. Printed, all measured in this run
(the thread's CPU time, steadier than wall time on a shared machine, with the
load): that derivative, the foundation's coasting rigid-body derivative and
their ratio; the per-part breakdown (each part called alone in a compiled
loop); and a whole RK4 step against a coasting one, and their ratio. Run with
``pytest -s tests/benchmarks``. Nothing here asserts a time; the check is that
the derivative's aerodynamic share equals the sum of its parts.
"""

import math
import time

import numba
import numpy as np

from rocketsim.atmosphere.table import air_in
from rocketsim.constants import EARTH_J2, EARTH_MU, EARTH_OMEGA, EARTH_RADIUS_EQ, EARTH_RADIUS_POLAR
from rocketsim.dynamics.derivative import body_air_velocity, derivative, radial_height
from rocketsim.dynamics.rk4 import advance
from rocketsim.layout import P_SPIN, V, make_params
from rocketsim.vehicle.engines import command_gimbal, engine_forces, ignite
from rocketsim.vehicle.grid_fins import command, grid_fin_forces
from rocketsim.vehicle.aero import body_aero
from rocketsim.vehicle.build import build
from tests.benchmarks.derivative_loops import coasting_derivative_calls, powered_derivative_calls
from rocketsim.vehicle.mass_properties import vehicle_mass_properties
from tests.aero_vehicles import corotating, earth_params, pitch_quaternion, shipped
from tests.benchmarks.timing import best_of, load_text


@numba.njit
def _mass(n, y, veh):
    total = 0.0
    for i in range(n):
        total += vehicle_mass_properties(veh, y)[1]
    return total


@numba.njit
def _air(n, y, p, veh):
    total = 0.0
    for i in range(n):
        total += air_in(veh.air, radial_height(y, p) + 1e-9 * i)[0]
    return total


@numba.njit
def _engines(n, y, dy, veh):
    total = 0.0
    for i in range(n):
        total += engine_forces(1e-6 * i, y, dy, veh.first_tank, veh.first_clock, veh.eng, veh.cmd, veh.stage,
                                 veh.tank_share, 26_000.0, 20.0)[0]
    return total


@numba.njit
def _body(n, y, veh):
    a = veh.aero
    total = 0.0
    for i in range(n):
        u, v, w = body_air_velocity(y, a.wind, EARTH_OMEGA)
        total += body_aero(u, v, w, y[10], y[11], y[12], 0.41, 299.5, 7e6, 20.0 + 1e-9 * i, a.ref, a.seg,
                           a.fin, a.ca_nf, a.ca_tf)[2]
    return total


@numba.njit
def _grid(n, y, veh):
    a = veh.aero
    total = 0.0
    for i in range(n):
        u, v, w = body_air_velocity(y, a.wind, EARTH_OMEGA)
        total += grid_fin_forces(1e-6 * i, u, v, w, y[10], y[11], y[12], 0.41, 299.5, 20.0, a.grid,
                                   a.grid_cmd)[2]
    return total


def test_first_stage_derivative_in_the_atmosphere():
    booster = build(shipped("falcon9-block5.yaml"), last=0)
    a = booster.arrays
    assert a.aero.seg.shape[0] >= 10 and a.aero.grid.shape[0] == 4 and booster.n_engines == 9
    r = np.array([EARTH_RADIUS_EQ + 10e3, 0.0, 0.0])
    y = booster.state(r, corotating(r) + np.array([300.0, 20.0, 0.0]), q=pitch_quaternion(math.radians(4.0)),
                      w=(0.01, 0.02, -0.01))
    for e in range(9):
        ignite(y, a.eng, a.cmd, a.stage, e, a.first_clock)
        command_gimbal(a.eng, a.cmd, e, 0.0, 0.01, -0.004)    # steering, as the autopilot does
    y[booster.clocks] = 10.0
    command(a.aero.grid, a.aero.grid_cmd, 0.0, math.radians(3.0), math.radians(-2.0), math.radians(1.0))
    p = earth_params()
    rigid = make_params(5e5, (2e5, 1e8, 1e8), EARTH_MU, EARTH_RADIUS_EQ, EARTH_J2, EARTH_RADIUS_POLAR)
    y13 = np.ascontiguousarray(y[:13])
    dy, dy13 = np.zeros_like(y), np.zeros(13)
    for f, args in ((powered_derivative_calls, (y, p, dy, a)), (coasting_derivative_calls, (y13, rigid, dy13)), (_mass, (y, a)), (_air, (y, p, a)),
                    (_engines, (y, dy, a)), (_body, (y, a)), (_grid, (y, a))):
        f(10, *args)

    n = 100_000
    per = lambda f, *args: best_of(3, lambda: f(n, *args), time.thread_time)[0] / n * 1e6
    t_full = per(powered_derivative_calls, y, p, dy, a)
    t_coast = per(coasting_derivative_calls, y13, rigid, dy13)
    parts = {"mass properties": per(_mass, y, a), "air table": per(_air, y, p, a),
             "9 engines": per(_engines, y, dy, a), "body aero (20 segments)": per(_body, y, a),
             "4 grid fins": per(_grid, y, a)}
    print(f"\n[aero] full first-stage derivative in the air: {t_full:.2f} us (target <= 30 us); "
          f"coasting derivative {t_coast:.3f} us; ratio {t_full / t_coast:.1f}x; {load_text()}")
    print("[aero] parts: " + "; ".join(f"{k} {v:.2f} us" for k, v in parts.items())
          + f"; rest (gravity, quaternion, rotations) {t_full - sum(parts.values()):.2f} us")

    steps = 500
    t_step = best_of(3, lambda: advance(y, 0, 0.02, steps, p, a), time.thread_time)[0] / steps * 1e6
    t_coast_step = best_of(3, lambda: advance(y13, 0, 0.02, steps, rigid), time.thread_time)[0] / steps * 1e6
    print(f"[aero] RK4 step (20 ms) of the burning stage in the air: {t_step:.1f} us "
          f"(target ~130 us); coasting step {t_coast_step:.2f} us; ratio {t_step / t_coast_step:.1f}x; {load_text()}")

    # correctness: the aerodynamic share of the derivative is the sum of the parts (body axes)
    bare = a._replace(aero=a.aero._replace(ref=a.aero.ref * 0.0))
    dy0 = np.zeros_like(y)
    derivative(0.0, y, p, dy, a)
    derivative(0.0, y, p, dy0, bare)
    mass, x_cm = booster.mass_properties(y)[:2]
    rho, _, _, sound = air_in(a.air, radial_height(y, p))[:4]
    thrust = engine_forces(0.0, y, np.zeros_like(y), a.first_tank, a.first_clock, a.eng, a.cmd, a.stage,
                             a.tank_share, air_in(a.air, radial_height(y, p))[1], x_cm)[0]
    u, v, w = body_air_velocity(y, a.aero.wind, p[P_SPIN])
    f1 = body_aero(u, v, w, y[10], y[11], y[12], rho, sound, thrust, x_cm, a.aero.ref, a.aero.seg, a.aero.fin,
                   a.aero.ca_nf, a.aero.ca_tf)
    f2 = grid_fin_forces(0.0, u, v, w, y[10], y[11], y[12], rho, sound, x_cm, a.aero.grid, a.aero.grid_cmd)
    force_body = np.array(f1[:3]) + np.array(f2[:3])
    from rocketsim.frames.quaternion import quat_rotate
    expected = quat_rotate(y[6:10], force_body) / mass
    assert np.allclose(dy[V:V + 3] - dy0[V:V + 3], expected, rtol=1e-9, atol=1e-12)
