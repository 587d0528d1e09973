"""Staging in flight: a separated stage becomes a body of its own."""

import numpy as np
import pytest

from rocketsim.frames.quaternion import quat_rotate
from rocketsim.scenario.load import load
from rocketsim.sim.build import build_world
from rocketsim.api.telemetry_flight import fly_to_file as fly
from rocketsim.telemetry.reader import messages
from tests.conftest import ROOT

UPPER = """
def main(fc):
    fc.sleep(1.0)
    fc.event("before", mass=fc.mass)
    name = fc.stage()
    fc.event("after", mass=fc.mass, separated=name)
    fc.sleep(1.0)
    fc.event("later", mass=fc.mass)
"""

BOOSTER = """
def main(fc):
    fc.log("booster program flying from", repr(fc.time))
    fc.event("booster", mass=fc.mass)
"""


def scenario_with_programs(write):
    write("upper.py", UPPER)
    write("booster.py", BOOSTER)
    return write("scenario.yaml", f"""\
        name: staging
        vehicle: {ROOT / 'vehicles' / 'falcon9-block5.yaml'}
        program: upper.py
        programs: {{booster: booster.py}}
        mission:
          epoch: 2026-11-26T12:00:00Z
          start: {{orbit: {{altitude: 300 km, inclination: 51.6 deg}}}}
          duration: 3 s
        """)


def test_separation_makes_two_bodies_that_conserve_mass_and_momentum(write, tmp_path):
    """Conservation (the reference): the parts' masses add up to the stack's,
    and their mass-weighted velocities to the stack's momentum, to rounding."""
    world = build_world(load(scenario_with_programs(write)))
    stack = world.bodies[0]
    mass, momentum = stack.mass, stack.mass * stack.velocity.copy()
    booster = world.separate(stack)
    assert [b.name for b in world.bodies] == ["falcon9-block5", "booster"]
    assert booster.mass + stack.mass == pytest.approx(mass, rel=1e-12)
    both = booster.mass * booster.velocity + stack.mass * stack.velocity
    assert np.allclose(both, momentum, rtol=1e-12, atol=1e-6)
    with pytest.raises(ValueError, match="no stage left"):
        world.separate(stack)


def test_a_program_stages_and_the_stage_flies_its_own_program(write, tmp_path):
    path = scenario_with_programs(write)
    out = tmp_path / "run.mcap"
    summary = fly(load(path), out)
    upper = {e["name"]: e for e in summary["bodies"]["falcon9-block5"]["events"]}
    booster = {e["name"]: e for e in summary["bodies"]["booster"]["events"]}
    assert upper["after"]["separated"] == "booster"
    assert upper["separation"]["time_s"] == booster["separation"]["time_s"] == pytest.approx(1.0)
    assert upper["after"]["mass"] + booster["booster"]["mass"] == pytest.approx(upper["before"]["mass"])
    assert upper["later"]["mass"] == upper["after"]["mass"]          # engines off: no burn
    logs = [m["message"] for _, _, m in messages(out, ["/log"])]
    assert logs == ["booster program flying from 1.0"]
    booster_states = [m["t"] for _, _, m in messages(out, ["/booster/state"])]
    assert booster_states[0] == pytest.approx(1.0) and booster_states[-1] == pytest.approx(3.0)


def test_a_program_for_a_stage_the_vehicle_lacks_is_refused(write, cli):
    path = scenario_with_programs(write)
    path.write_text(path.read_text().replace("{booster: booster.py}", "{boster: booster.py}"))
    result = cli("validate", path)
    assert result.exit_code == 2
    assert "scenario.yaml:4:" in result.output and "no stage named 'boster'" in result.output


def test_the_fairing_is_jettisoned_into_two_halves_of_their_own(write):
    """Conservation again: mass and momentum of the stack and the two fairing halves
    add up to the stack's before; each half has half the vehicle file's 1 900 kg, and
    the halves move apart along the body's y axis at the separation speed (2 m/s
    by default) plus the turn of their lever arms (the stack starts at rest)."""
    world = build_world(load(scenario_with_programs(write)))
    stack = world.bodies[0]
    mass, momentum = stack.mass, stack.mass * stack.velocity.copy()
    one, two = world.jettison_fairing(stack)
    assert (one.name, two.name) == ("fairing_1", "fairing_2")
    assert one.mass == two.mass == pytest.approx(950.0)
    assert stack.mass + one.mass + two.mass == pytest.approx(mass, rel=1e-12)
    parts = stack.mass * stack.velocity + one.mass * one.velocity + two.mass * two.velocity
    assert np.allclose(parts, momentum, rtol=1e-12, atol=1e-6)
    side = quat_rotate(stack.attitude, np.array([0.0, 1.0, 0.0]))
    assert np.dot(one.velocity - two.velocity, side) == pytest.approx(2.0, abs=1e-9)
    assert [e["name"] for e in stack.events] == ["fairing jettison"]
    assert stack.events[0]["fairing_bodies"] == ["fairing_1", "fairing_2"]
    with pytest.raises(ValueError, match="no fairing"):
        world.jettison_fairing(stack)
    booster = world.separate(stack)                     # staging still works without it
    assert booster.name == "booster"
