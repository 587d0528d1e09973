"""A two-stage solid rocket: the booster's motor, a separation, the sustainer's motor lit later.

Checks the bookkeeping of staging with solid motors and parachutes against
what the vehicle file says, exactly: the sustainer's propellant is untouched
until its ignition time and then follows its own curve (its burnout at
ignition + the curve's last time, 3.0 + 2.5 s); each part reports its own
burnout once; the booster's parachute deploys on its own trigger (one second
after the separation event) on the booster's body; the masses of the parts
add up to the stack's at the separation. The sustainer lights at its file's
``ignition: 3 s``, or with ``ignition: program`` when the program lights it at
T+3 s (``fc.ignite``, docs/physics.md#solid-motors): the same flight. A 7 s
flight at 20 ms.
"""

from pathlib import Path

import pytest

from rocketsim.scenario.load import load
from rocketsim.sim.build import build_world

ROOT = Path(__file__).resolve().parents[2]
K1000T = str(ROOT / "motors" / "AeroTech_K1000T.eng")
PROGRAM = """
def main(fc):
    fc.wait_until(lambda: fc.time >= 2.6)
    fc.stage()
"""
LIGHT = """
    fc.wait_until(lambda: fc.time >= 3.0)
    assert fc.ignite("sustainer") == ["sustainer/K1000T"]
"""


@pytest.mark.parametrize("ignition", ["3 s", "program"])
def test_the_sustainer_lights_on_time_after_the_booster_separates(tmp_path, ignition):
    (tmp_path / "program.py").write_text(PROGRAM + (LIGHT if ignition == "program" else ""))
    # springs soft enough for the 3.4 kg booster alone at the 5 ms ground sub-steps (its
    # four base points: a mode of 150 /s, docs/physics.md#input-bounds)
    contact = {"body_contact_stiffness": 2e4, "body_contact_damping": 2e2,
               "limits": {"axial_load": "40 g"}}      # a K motor pushes the light sustainer at ~20 g
    vehicle = {"name": "two-stage", "stages": [
        {"name": "booster", "length": "0.8 m", "diameter": "0.1 m", "structure_mass": "2 kg",
         "motors": [{"name": "K1000T", "file": K1000T}],
         "parachutes": [{"name": "booster chute", "cd_s": "0.5 m2",
                         "deploy": {"after": {"event": "separation", "delay": "1 s"}}}]},
        {"name": "sustainer", "length": "1.2 m", "diameter": "0.1 m", "structure_mass": "3 kg",
         "motors": [{"name": "K1000T", "file": K1000T, "ignition": ignition}],
         "parachutes": [{"name": "main", "cd_s": "2 m2", "deploy": "apogee"}]}],
        "aero": {"nose": {"length": "0.3 m", "shape": "ogive"},
                 "fins": [{"stage": stage, "count": 4, "position": "0.2 m", "root_chord": "0.2 m",
                           "tip_chord": "0.1 m", "span": "0.12 m", "sweep": "0.1 m"}
                          for stage in ("booster", "sustainer")], **contact}}
    data = {"name": "two-stage", "vehicle": vehicle, "program": "program.py",
            "site": {"name": "pad", "latitude": "32.99 deg", "longitude": "-106.975 deg", "height": "0 m"},
            "mission": {"epoch": "2026-06-13T15:00:00Z", "duration": "7 s",
                        "start": {"site": {"rail": {"length": "5 m", "inclination": "88 deg"}}}}}
    world = build_world(load(data, base_dir=tmp_path))
    stack = world.bodies[0]
    seen = {}

    def watch(t):
        if len(world.bodies) == 2 and "split" not in seen:
            booster = world.bodies[1]
            seen["split"] = (stack.mass, booster.mass, float(stack.y[stack.vehicle.motors][0]))
        if len(world.bodies) == 2 and t < 2.999:      # the last look before T+3 s (called per batch)
            seen["before"] = float(stack.y[stack.vehicle.motors][0])
    world.on_progress = watch
    world.run()
    booster = world.bodies[1]
    upper = [e["name"] for e in stack.events]
    lower = [e["name"] for e in booster.events]
    assert upper.count("burnout") == 2 and lower.count("burnout") == 0
    assert upper.count("ignition") == (ignition == "program")
    burnouts = [e for e in stack.events if e["name"] == "burnout"]
    assert [b["motor"] for b in burnouts] == ["booster/K1000T", "sustainer/K1000T"]
    assert burnouts[1]["burnout_s"] == pytest.approx(5.5, abs=1e-12)
    assert seen["split"][2] == 1.182 and seen["before"] == 1.182       # untouched until T+3 s
    assert float(stack.y[stack.vehicle.motors][0]) == pytest.approx(0.0, abs=1e-9)
    deployed = next(e for e in booster.events if e["name"] == "parachute_deployed")
    separation = next(e for e in booster.events if e["name"] == "separation")
    assert deployed["parachute"] == "booster chute"
    assert separation["time_s"] + 1.0 <= deployed["time_s"] < separation["time_s"] + 1.0 + 0.02 + 1e-9
    assert not any(e["name"] == "parachute_deployed" for e in stack.events)    # no apogee yet
    assert separation["stage_mass_kg"] + separation["upper_mass_kg"] == pytest.approx(
        2 + 3 + 2 * 2.575 - 1.182, rel=1e-12)          # the booster's propellant burnt, the sustainer's not


def test_a_vehicle_file_sets_its_own_structural_limits():
    """``aero.limits`` replaces the launcher-sized defaults (15 g, 250 kPa deg): a 20 g
    push breaks a vehicle under the defaults and not under a 40 g limit (the closed form
    of docs/physics.md#structural-limits: the load is the sensed acceleration over g0)."""
    from rocketsim.constants import G0
    from rocketsim.scenario.aero_spec import LimitsSpec
    from rocketsim.sim.vehicle_checks import VehicleChecks
    from rocketsim.vehicle.limits import breakup
    default, own = VehicleChecks(), VehicleChecks(limits=LimitsSpec(axial_load="40 g", q_alpha=5e5))
    assert own.limits == (5e5, pytest.approx(40.0, rel=1e-15))
    assert breakup(1000.0, 0.0, 20 * G0, *default.limits)["cause"] == "axial load"
    assert breakup(1000.0, 0.0, 20 * G0, *own.limits) is None
    assert breakup(5e4, 0.2, 0.0, *own.limits)["cause"] == "bending"      # 5e4 Pa x 11.46 deg
