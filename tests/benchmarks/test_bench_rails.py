"""Benchmark: cruise rails to Mars, and a sleeping LEO stage against an awake one.

Targets: the heliocentric leg to Mars on cruise rails in under 10 s on one
core, reported with its error against DOP853 (rtol 1e-13, the same field
summed independently); a sleeping LEO stage on rails at most a fifth of the
cost per step of an awake coasting one. Printed: the 280-day cruise's wall
time, cruise steps and error, the cost per 20 ms step of the Falcon 9-class
second stage (engine off, propellant left) awake (mass properties and engine
model at every RK4 stage) and on rails, their ratio, and the awake rigid
body's cost as a second baseline, all measured in the same run. Run with
``pytest -s tests/benchmarks``. Nothing here asserts a time; the checks are
the accuracies.
"""

import time
from pathlib import Path

import numpy as np

from rocketsim.constants import (DEG, EARTH_J2, EARTH_MU, EARTH_RADIUS_EQ, EARTH_RADIUS_POLAR,
                                 SUN_MU, SUN_RADIUS)
from rocketsim.dynamics import cruise, nbody, rails
from rocketsim.dynamics.rk4 import advance
from rocketsim.layout import make_params, make_state
from rocketsim.frames.elements import elements_to_state
from rocketsim.scenario.load import validate
from rocketsim.scenario.models import VehicleSpec
from rocketsim.scenario.yaml_source import read_yaml
from rocketsim.vehicle.build import build
from tests.benchmarks.timing import best_of
from tests.nbody_reference import reference_orbit
from tests.unit.dynamics.test_cruise import JD0, SUN_P, mars_transfer

ROOT = Path(__file__).resolve().parents[2]
H = 0.02


def test_heliocentric_leg_to_mars_on_cruise_rails():
    r0, v0 = mars_transfer()
    fp = nbody.make_field("sun", JD0)
    air = nbody.no_air()
    y0 = make_state(r0, v0)
    k_end = round(280 * 86400 / H)
    cruise.advance_cruise(y0, 0, H, 100, SUN_P, fp, air, SUN_P[1:4])       # compile
    seconds, (y, k, reason, count) = best_of(2, lambda: cruise.advance_cruise(
        y0, 0, H, k_end, SUN_P, fp, air, SUN_P[1:4]))
    start = time.perf_counter()
    r_ref, _ = reference_orbit(r0, v0, 0.0, k * H, JD0, "sun", np.eye(3),
                               ("earth", "moon", "mars"), (SUN_MU, SUN_RADIUS, 0.0))
    reference_seconds = time.perf_counter() - start
    error = np.linalg.norm(y[:3] - r_ref)
    print(f"\n[rails] 280-day Earth-Mars cruise: {seconds:.3f} s wall (target < 10 s), "
          f"{count} cruise steps, {error:.3f} m from DOP853 (target < 100 km); "
          f"DOP853 itself {reference_seconds:.2f} s, ratio {reference_seconds / seconds:.2f}")
    assert reason == cruise.DONE and error < 100e3


def _stage_costs(stage, altitude, drag):
    """Seconds per step awake and on rails, the awake rigid body's, and both final states."""
    a = stage.arrays
    r, v = elements_to_state(EARTH_RADIUS_EQ + altitude, 0.001, 28.5 * DEG, 0.0, 0.0, 0.0)
    y0 = stage.state(r, v, propellant=0.1 * stage.tank_load)
    p = make_params(1.0, (1.0, 1.0, 1.0), EARTH_MU, EARTH_RADIUS_EQ, EARTH_J2, EARTH_RADIUS_POLAR)
    mass, _, ixx, iyy, _ = stage.mass_properties(y0)
    inertia = np.array((ixx, iyy, iyy))
    rigid = p.copy()
    rigid[0:4] = (mass, ixx, iyy, iyy)
    fp = nbody.make_field("earth", JD0, bodies=(), drag=drag)
    air = a.air
    n = 50_000
    advance(y0, 0, H, 10, p, a)
    advance(y0[:13].copy(), 0, H, 10, rigid)
    rails.advance_rails(y0, 0, H, 10, p, fp, air, inertia, rails.FREE)
    t_awake, (y_awake, _) = best_of(3, lambda: advance(y0, 0, H, n, p, a))
    t_rigid, _ = best_of(3, lambda: advance(y0[:13].copy(), 0, H, n, rigid))
    t_rails, (y_rails, _) = best_of(3, lambda: rails.advance_rails(y0, 0, H, n, p, fp, air,
                                                                   inertia, rails.FREE))
    print(f"\n[rails] stage at {altitude / 1e3:.0f} km per 20 ms step: awake {t_awake / n * 1e6:.3f} us, "
          f"rails {t_rails / n * 1e6:.3f} us, ratio rails/awake {t_rails / t_awake:.3f} "
          f"(target <= 0.2); awake rigid body {t_rigid / n * 1e6:.3f} us "
          f"(rails/rigid {t_rails / t_rigid:.2f})")
    return y_awake, y_rails


def test_sleeping_leo_stage_against_an_awake_coasting_one():
    stage = build(validate(read_yaml(ROOT / "vehicles" / "falcon9-block5.yaml"), VehicleSpec),
                  first=1)
    # above the air: the same gravity, the same arithmetic, the same orbit to the bit
    y_awake, y_rails = _stage_costs(stage, 700e3, 0.0)
    np.testing.assert_array_equal(y_rails[:6], y_awake[:6])
    # in the air: the awake stage's aerodynamics against the rails' point-mass drag
    # (C_D = 2.2 on the 3.66 m section); only the cost is compared
    mass = stage.mass_properties(stage.state((7e6, 0, 0), (0, 7e3, 0),
                                             propellant=0.1 * stage.tank_load))[0]
    _stage_costs(stage, 250e3, 2.2 * np.pi * 1.83 ** 2 / mass)
