"""A staged vehicle in a scenario (rocketsim.sim.build.build_world): the world builds the runtime
model, extends the state with the tanks and engine clocks, and advances it with the
vehicle's arrays. Reference: a coasting staged vehicle with its engines off follows the
same orbit as a rigid body (gravity does not depend on mass)."""

from pathlib import Path

import numpy as np

from rocketsim.scenario.load import load
from rocketsim.sim.build import build_world
from tests.conftest import MISSION, VEHICLE

VEHICLES = Path(__file__).resolve().parents[3] / "vehicles"


def test_staged_vehicle_flies_a_scenario_like_a_rigid_body_when_unpowered(write):
    write("mission.yaml", MISSION.format(duration="20 s"))
    write("rigid.yaml", VEHICLE)
    staged = write("staged.yaml", f"name: s\nvehicle: {VEHICLES / 'falcon9-block5.yaml'}\nmission: mission.yaml\n")
    rigid = write("rigid-scenario.yaml", "name: r\nvehicle: rigid.yaml\nmission: mission.yaml\n")
    w_staged = build_world(load(staged))
    w_rigid = build_world(load(rigid))
    body = w_staged.bodies[0]
    assert body.vehicle is not None and body.y.shape[0] == 13 + 5 + 10   # 4 tanks and the GN2 bottle
    liftoff = body.mass
    w_staged.run()
    w_rigid.run()
    assert body.mass == liftoff == 569_300.0
    assert np.allclose(body.y[:6], w_rigid.bodies[0].y[:6], rtol=0, atol=1e-6)
