"""Payload deploy: fc.deploy_payload() makes the payload a body of its own.

The reference is conservation: the parts' masses add up to the stack's, and
their mass-weighted positions and velocities to the stack's centre of mass
and momentum (no separation impulse), to rounding, here with the stack
turning (0.02 rad/s in pitch) so that the lever arm's velocity term counts.
"""

import numpy as np
import pytest

from rocketsim.layout import P_IXX, P_IYY, P_IZZ
from rocketsim.scenario.load import load
from rocketsim.api.telemetry_flight import fly_to_file as fly
from rocketsim.sim.build import build_world
from rocketsim.telemetry.reader import messages
from tests.conftest import ROOT

PROGRAM = """
def main(fc):
    fc.sleep(1.0)
    fc.jettison_fairing()
    fc.event("before", mass=fc.mass)
    name = fc.deploy_payload()
    fc.event("after", mass=fc.mass, deployed=name)
"""


def electron_in_orbit(write, program=True):
    if program:
        write("deploy.py", PROGRAM)
    return write("scenario.yaml", f"""\
        name: deploy
        vehicle: {ROOT / 'vehicles' / 'electron.yaml'}
        payload: {{name: a smallsat, mass: 100 kg, length: 0.8 m, diameter: 0.6 m}}
        {'program: deploy.py' if program else ''}
        mission:
          epoch: 2026-11-26T12:00:00Z
          start: {{orbit: {{altitude: 500 km, inclination: 97.4 deg}}}}
          initial_rates: [0.0, 0.02, 0.0]
          duration: 3 s
        """)


def test_the_payload_leaves_with_the_stack_s_mass_centre_and_momentum(write):
    world = build_world(load(electron_in_orbit(write, program=False)))
    stack = world.bodies[0]
    with pytest.raises(ValueError, match="fairing"):
        world.deploy_payload(stack)                    # still inside the fairing
    world.jettison_fairing(stack)
    mass = stack.mass
    centre, momentum = mass * stack.position.copy(), mass * stack.velocity.copy()
    payload = world.deploy_payload(stack)
    assert payload.name == "payload" and payload.mass == pytest.approx(100.0)
    assert payload.vehicle is None                     # a rigid body: a solid cylinder
    r, length = 0.3, 0.8                               # m r^2/2 and m (3 r^2 + L^2)/12
    assert payload.p[[P_IXX, P_IYY, P_IZZ]] == pytest.approx([100 * r * r / 2, 100 * (3 * r * r + length ** 2) / 12,
                                                  100 * (3 * r * r + length ** 2) / 12], rel=1e-12)
    assert stack.mass + payload.mass == pytest.approx(mass, rel=1e-12)
    assert np.allclose(stack.mass * stack.position + payload.mass * payload.position, centre,
                       rtol=1e-12, atol=1e-3)
    assert np.allclose(stack.mass * stack.velocity + payload.mass * payload.velocity, momentum,
                       rtol=1e-12, atol=1e-6)
    # the payload sits ahead of the stage along the nose, and moves with the turn
    nose = payload.position - stack.position
    assert np.linalg.norm(nose) > 1.0
    assert not np.allclose(payload.velocity, stack.velocity)
    assert [e["name"] for e in stack.events] == ["fairing jettison", "payload deploy"]
    with pytest.raises(ValueError, match="no payload"):
        world.deploy_payload(stack)


def test_a_program_deploys_the_payload_into_its_own_channel(write, tmp_path):
    out = tmp_path / "run.mcap"
    summary = fly(load(electron_in_orbit(write)), out)
    stage = {e["name"]: e for e in summary["bodies"]["electron"]["events"]}
    payload = {e["name"]: e for e in summary["bodies"]["payload"]["events"]}
    assert stage["after"]["deployed"] == "payload"
    assert stage["after"]["mass"] + payload["payload deploy"]["payload_mass_kg"] == pytest.approx(
        stage["before"]["mass"], rel=1e-12)
    assert payload["payload deploy"]["from_body"] == "electron"
    states = [m["t"] for _, _, m in messages(out, ["/payload/state"])]
    assert states[0] == pytest.approx(1.0) and states[-1] == pytest.approx(3.0)
