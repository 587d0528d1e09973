"""fc.cruise in the world: cruise rails where no shell is near, 20 ms steps inside one.

References: DOP853 (``rocketsim.dynamics.reference``, rtol 1e-13) of the
same field the world flies awake (Earth's point mass and J2), and the awake
RK4 kernel for a body that may not cruise (inside Earth's 2 000 km shell).
"""

import numpy as np

from rocketsim.dynamics.reference import integrate_reference
from rocketsim.dynamics.rk4 import advance
from rocketsim.frames.quaternion import quat_rotate
from rocketsim.scenario.load import load
from rocketsim.sim.build import build_world
from tests.unit.sim.test_world_rails import AXISYMMETRIC

CRUISER = """
def main(fc):
    fc.cruise(72000.0)
    fc.log("after cruise", repr(fc.time))
"""


def world_for(write, scenario, position, velocity):
    path = scenario(CRUISER, duration="72000 s")
    write("vehicle.yaml", AXISYMMETRIC)
    write("mission.yaml", f"""\
        epoch: 2026-11-26T12:00:00Z
        start:
          state:
            position: {list(position)}
            velocity: {list(velocity)}
        duration: 72000 s
        initial_rates: [0.3, 0.02, 0.0]
        """)
    world = build_world(load(path))
    batches = []
    world.on_progress = batches.append
    return world, batches


def test_a_cruise_on_a_high_ellipse_takes_few_steps_and_matches_dop853(write, scenario):
    # perigee 10 000 km (outside the shell), apogee ~300 000 km
    world, batches = world_for(write, scenario, (1.0e7, 0.0, 0.0), (0.0, 8700.0, 1000.0))
    body = world.bodies[0]
    y0, p = body.y.copy(), body.p.copy()
    world.run()
    assert world.k * world.h == 72000.0 and body.t == 72000.0
    assert len(batches) < 1000                 # 20 h at 10 Hz would be 720 000 samples
    reference = integrate_reference(y0, 0.0, 72000.0, p, rtol=1e-13, atol=1e-9)
    error = np.linalg.norm(body.y[:3] - reference[:3])
    print(f"\n[world cruise] 20 h in {len(batches)} batches, {error:.3f} m off DOP853")
    assert error < 100.0
    # the attitude turned torque-free: angular momentum direction kept
    inertia = p[1:4]
    h0 = quat_rotate(y0[6:10], inertia * y0[10:13])
    h1 = quat_rotate(body.y[6:10], inertia * body.y[10:13])
    np.testing.assert_allclose(h1, h0, rtol=0, atol=1e-12 * np.linalg.norm(h0))


def test_inside_the_shell_a_cruise_flies_20_ms_steps(write, scenario):
    # a 400 km orbit is inside Earth's 2 000 km clearance shell: nothing changes
    world, batches = world_for(write, scenario, (6.778e6, 0.0, 0.0), (0.0, 7668.0, 0.0))
    world.n_steps = 500
    body = world.bodies[0]
    y0, p = body.y.copy(), body.p.copy()
    world.run()
    awake, _ = advance(y0, 0, world.h, 500, p)
    np.testing.assert_array_equal(body.y[:6], awake[:6])
