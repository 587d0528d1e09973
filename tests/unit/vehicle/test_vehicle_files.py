"""Vehicle files: bad input named by file, line and field; the shipped
vehicles validate; ``rocketsim vehicle`` figures of the Falcon 9-class stack against
the public figures quoted in its file."""

import json
import math
from pathlib import Path

import pytest

from rocketsim.constants import G0, UNUSABLE_PROPELLANT
from tests.unit.scenario.test_scenario_errors import assert_clean_error

VEHICLES = Path(__file__).resolve().parents[3] / "vehicles"

GOOD = """\
name: bad
stages:
  - name: S1
    length: 10 m
    diameter: 2 m
    structure_mass: 1000 kg
    tanks:
      - name: T
        propellant: X
        density: 1000 kg/m3
        radius: 0.9 m
        length: 6 m
        position: 1 m
    engines:
      - name: E
        thrust_vacuum: 100 kN
        isp_vacuum: 300 s
        exit_area: 0.5 m2
        throttle: [0.5, 1.0]
"""


def test_the_good_file_is_good(write, cli):
    assert cli("validate", write("v.yaml", GOOD)).exit_code == 0


@pytest.mark.parametrize("command", ["validate", "vehicle"])
def test_tank_longer_than_its_stage(write, cli, command):
    path = write("v.yaml", GOOD.replace("length: 6 m", "length: 9.5 m"))
    assert_clean_error(cli(command, path), "v.yaml:12:", "stages.0.tanks.0.length",
                       "longer than its stage", "10.5 m")


def test_negative_isp(write, cli):
    path = write("v.yaml", GOOD.replace("isp_vacuum: 300 s", "isp_vacuum: -300 s"))
    assert_clean_error(cli("validate", path), "v.yaml:17:", "stages.0.engines.0.isp_vacuum",
                       "must be at least 1 s")


def test_engine_without_a_stage(write, cli):
    path = write("v.yaml", GOOD + "engines:\n  - name: loose\n    thrust_vacuum: 1 kN\n")
    assert_clean_error(cli("validate", path), "v.yaml:20:1", "engines", "must belong to a stage")


@pytest.mark.parametrize("throttle", ["[0.5, 1.2]", "[-0.1, 1.0]", "[0.9, 0.5]"])
def test_throttle_range_outside_zero_one(write, cli, throttle):
    path = write("v.yaml", GOOD.replace("[0.5, 1.0]", throttle))
    assert_clean_error(cli("validate", path), "v.yaml:19:", "stages.0.engines.0.throttle",
                       "0 <= min <= max <= 1")


def test_engines_without_tanks(write, cli):
    no_tanks = GOOD[:GOOD.index("    tanks:")] + GOOD[GOOD.index("    engines:"):]
    path = write("v.yaml", no_tanks)
    assert_clean_error(cli("validate", path), "v.yaml:7:", "stages.0.engines", "no tanks")


def test_rigid_body_and_stages_together(write, cli):
    path = write("v.yaml", GOOD + "rigid_body:\n  mass: 1 kg\n  inertia: [1, 1, 1]\n")
    assert_clean_error(cli("validate", path), "v.yaml:1:", "exactly one of 'rigid_body' or 'stages'")


def test_propellant_that_does_not_fit(write, cli):
    path = write("v.yaml", GOOD.replace("position: 1 m", "position: 1 m\n        propellant_mass: 99 t"))
    assert_clean_error(cli("validate", path), "v.yaml:14:", "propellant_mass", "does not fit")


@pytest.mark.parametrize("name", sorted(p.name for p in VEHICLES.glob("*.yaml")))
def test_shipped_vehicles_validate(cli, name):
    result = cli("validate", VEHICLES / name)
    assert result.exit_code == 0, result.output


def test_falcon9_figures_against_the_public_ones(cli):
    """Public figures (quoted in vehicles/falcon9-block5.yaml): liftoff mass 549 054 kg
    without payload (SpaceX); stages 22 200 + 410 900 kg and 4 000 + 107 500 kg, Isp 311 s
    and 348 s in vacuum, 282 s at sea level (Wikipedia, Falcon 9 Full Thrust / Merlin).
    The Delta-v reference is worked here by hand from those figures (rocket equation,
    1 % unusable, fairing 1 900 kg and the 22 800 kg LEO payload carried)."""
    result = cli("vehicle", VEHICLES / "falcon9-block5.yaml", "--format", "json")
    assert result.exit_code == 0, result.output
    f = json.loads(result.output)
    assert abs(f["liftoff_mass_kg"] - f["payload_mass_kg"] - 549_054) / 549_054 < 0.02
    upper = 4_000 + 107_500 + 1_900 + 22_800
    m0 = 22_200 + 410_900 + upper
    dv1 = 311 * G0 * math.log(m0 / (m0 - (1 - UNUSABLE_PROPELLANT) * 410_900))
    dv2 = 348 * G0 * math.log(upper / (upper - (1 - UNUSABLE_PROPELLANT) * 107_500))
    assert abs(f["delta_v_vacuum_m_s"] - (dv1 + dv2)) / (dv1 + dv2) < 0.02
    sea1 = 282 * G0 * math.log(m0 / (m0 - (1 - UNUSABLE_PROPELLANT) * 410_900))
    assert abs(f["stages"][0]["delta_v_sea_level_m_s"] - sea1) / sea1 < 0.02
    assert [s["name"] for s in f["stages"]] == ["booster", "second stage"]
    for s in f["stages"]:
        assert {"wet_mass_kg", "dry_mass_kg", "delta_v_vacuum_m_s", "delta_v_sea_level_m_s"} <= set(s)
    # thrust-to-weight at liftoff: 7 607 kN / (m g0)
    assert f["liftoff_thrust_to_weight"] == pytest.approx(7_607e3 / (f["liftoff_mass_kg"] * G0), rel=0.01)


def test_vehicle_table_and_plot(cli, tmp_path):
    result = cli("vehicle", VEHICLES / "falcon9-block5.yaml", "--plot", tmp_path / "f9.png")
    assert result.exit_code == 0, result.output
    assert "booster" in result.output and "second stage" in result.output and "T/W" in result.output
    assert (tmp_path / "f9.png").stat().st_size > 10_000


def test_vehicle_command_refuses_a_rigid_body(cli):
    assert_clean_error(cli("vehicle", VEHICLES / "cubesat-6u.yaml"), "stages", "rigid-body")


def test_methalox_stages_carry_their_oxidiser_aft():
    """docs/physics.md#mass-properties: methalox stages carry their oxidiser aft (the LOX
    tank is the lower)."""
    from rocketsim.scenario.load import validate
    from rocketsim.scenario.models import VehicleSpec
    from rocketsim.scenario.yaml_source import read_yaml
    found = 0
    for path in VEHICLES.glob("*.yaml"):
        spec = validate(read_yaml(path), VehicleSpec)
        for stage in spec.stages or []:
            kinds = {t.propellant: t for t in stage.tanks}
            if "LCH4" in kinds:
                found += 1
                assert kinds["LOX"].position + kinds["LOX"].length <= kinds["LCH4"].position
    assert found == 2
