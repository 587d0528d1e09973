"""A sleeping body in the world goes on rails and comes back the same.

References: the awake RK4 kernel (``rocketsim.dynamics.rk4.advance``) for the
orbit, which the rails must reproduce to the bit, and DOP853 of Euler's
equations and the quaternion kinematics (``rocketsim.dynamics.reference``)
for the torque-free attitude.
"""

import numpy as np

from rocketsim.dynamics.reference import integrate_reference
from rocketsim.dynamics.rk4 import advance
from rocketsim.scenario.load import load
from rocketsim.sim.build import build_world

AXISYMMETRIC = """\
name: spinner
rigid_body:
  mass: 10 kg
  inertia: [0.15, 0.12, 0.12]
"""

SLEEPER = """
def main(fc):
    fc.sleep(60.0)
    fc.log("awake", repr(fc.time))
    while fc.time < 61.0:
        fc.step()
"""


def fly_world(write, scenario, monkeypatch_calls):
    path = scenario(SLEEPER, duration="61 s")
    write("vehicle.yaml", AXISYMMETRIC)
    mission = path.parent / "mission.yaml"
    mission.write_text(mission.read_text() + "initial_rates: [0.8, 0.05, -0.03]\n")
    world = build_world(load(path))
    body = world.bodies[0]
    y0, p = body.y.copy(), body.p.copy()
    on_rails = world.schedule.on_rails

    def record(b):
        answer = on_rails(b)
        monkeypatch_calls.append((world.k, answer))
        return answer
    world.schedule.on_rails = record
    world.run()
    return world, y0, p


def test_a_sleeping_body_rides_the_rails_and_wakes_on_the_same_orbit(write, scenario):
    calls = []
    world, y0, p = fly_world(write, scenario, calls)
    body = world.bodies[0]
    n = round(61.0 / world.h)
    # on rails while asleep, awake once the program steps again
    assert any(answer for k, answer in calls if k < 3000)
    assert not any(answer for k, answer in calls if k >= 3000)
    awake, _ = advance(y0, 0, world.h, n, p)
    np.testing.assert_array_equal(body.y[:6], awake[:6])
    reference = integrate_reference(y0, 0.0, n * world.h, p, rtol=1e-13, atol=1e-13)
    q_ref = reference[6:10] / np.linalg.norm(reference[6:10])
    assert min(np.linalg.norm(body.y[6:10] - q_ref), np.linalg.norm(body.y[6:10] + q_ref)) < 1e-9
    np.testing.assert_allclose(body.y[10:13], reference[10:13], atol=1e-9)


def test_an_asymmetric_or_stepping_body_stays_awake(scenario):
    # the default probe (inertia 0.15, 0.12, 0.05) has no closed-form torque-free motion here
    world = build_world(load(scenario(SLEEPER, duration="2 s")))
    assert not world.schedule.on_rails(world.bodies[0])
