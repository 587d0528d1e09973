"""Bad input: one clear message naming file, line, column and field; exit 2; no traceback."""

import pytest

from rocketsim.errors import InputError
from rocketsim.api.flying import fly
from rocketsim.scenario.load import load
from rocketsim.telemetry.reader import messages, metadata
from tests.conftest import MISSION, VEHICLE


def assert_clean_error(result, *fragments):
    assert result.exit_code == 2, result.output
    assert "Traceback" not in result.output
    for fragment in fragments:
        assert fragment in result.output, result.output


def test_misspelt_field_names_the_place_and_suggests_the_field(scenario, cli):
    path = scenario()
    path.with_name("mission.yaml").write_text(MISSION.format(duration="10 s").replace(
        "inclination:", "inclinaton:"))
    result = cli("fly", path, "-o", path.with_name("out.mcap"))
    assert_clean_error(result, "mission.yaml:5:5", "start.orbit.inclinaton",
                       "did you mean 'inclination'?")


def test_missing_referenced_file(scenario, cli):
    path = scenario()
    path.with_name("vehicle.yaml").unlink()
    result = cli("validate", path)
    assert_clean_error(result, "scenario.yaml:2:1", "vehicle", "not found")


def test_yaml_syntax_error_gives_line_and_column(write, cli):
    path = write("broken.yaml", "name: x\nvehicle: [1, 2\nmission: m.yaml\n")
    result = cli("validate", path)
    assert_clean_error(result, "broken.yaml:3:", "YAML syntax error")


def test_wrong_type(scenario, cli):
    path = scenario()
    path.with_name("vehicle.yaml").write_text(VEHICLE.replace("[0.15, 0.12, 0.05]", "heavy"))
    result = cli("validate", path)
    assert_clean_error(result, "vehicle.yaml:4:3", "rigid_body.inertia")


def test_unknown_unit(scenario, cli):
    path = scenario()
    path.with_name("vehicle.yaml").write_text(VEHICLE.replace("10 kg", "10 stone"))
    result = cli("validate", path)
    assert_clean_error(result, "vehicle.yaml:3:3", "rigid_body.mass", "unknown unit 'stone'", "'kg'")


def test_negative_mass(scenario, cli):
    path = scenario()
    path.with_name("vehicle.yaml").write_text(VEHICLE.replace("10 kg", "-10 kg"))
    result = cli("validate", path)
    assert_clean_error(result, "vehicle.yaml:3:3", "rigid_body.mass", "must be at least 0.0001 kg")


def test_angle_without_unit_is_refused(scenario, cli):
    path = scenario()
    path.with_name("mission.yaml").write_text(MISSION.format(duration="10 s").replace("51.6 deg", "51.6"))
    result = cli("validate", path)
    assert_clean_error(result, "mission.yaml:5:5", "inclination", "an angle needs a unit")


def test_step_larger_than_a_tenth_of_a_second_in_the_file(scenario, cli):
    path = scenario(extra="step: 0.2 s\n")
    result = cli("fly", path, "-o", path.with_name("out.mcap"))
    assert_clean_error(result, "scenario.yaml:4:1", "step", "larger than the 0.1 s")


def test_step_larger_than_a_tenth_of_a_second_on_the_command_line(scenario, cli):
    path = scenario()
    result = cli("fly", path, "--step", "0.25", "-o", path.with_name("out.mcap"))
    assert_clean_error(result, "--step", "larger than the 0.1 s")


def test_a_state_that_diverges_ends_the_flight_with_a_clear_error(scenario, cli):
    # a body spinning at 3000 rad/s flown at 0.1 s: |lambda h| = 150 for the attitude's
    # kinematics, far outside RK4's stability region (|lambda h| < 2.8), so the state
    # overflows within a few steps; the flight stops there with exit status 2 and a
    # readable file whose samples are all finite
    path = scenario(extra="step: 0.1 s\n")
    mission = path.with_name("mission.yaml")
    mission.write_text(mission.read_text() + "initial_rates: [3000, 100, 0]\n")
    out = path.with_name("out.mcap")
    result = cli("fly", path, "-o", out)
    # named: the scenario's file and the step's line in it, and the vehicle's
    assert_clean_error(result, f"error: {path.resolve()}:4: step: the state of probe (vehicle file "
                       f"{path.with_name('vehicle.yaml').resolve()}) is no longer finite", "smaller step")
    states = [m for _, _, m in messages(out, ["/probe/state"])]
    assert states and all(None not in m["position"] for m in states)
    assert metadata(out)["outcome"]["status"] == "error"
    # a vehicle written inline has no file of its own: the scenario's is named alone
    path.write_text(path.read_text().replace(
        "vehicle: vehicle.yaml", "vehicle: {name: probe, rigid_body: {mass: 10 kg, inertia: [0.15, 0.12, 0.05]}}"))
    with pytest.raises(InputError) as caught:
        fly(path)
    assert caught.value.message.startswith("the state of probe is no longer finite at T+")
    assert caught.value.file == str(path.resolve()) and caught.value.field == "step"
    assert caught.value.line == 4
    # a step given over the file's names no line of it
    path.write_text(path.read_text().replace("step: 0.1 s\n", ""))
    result = cli("fly", path, "--step", "0.1", "-o", out)
    assert_clean_error(result, f"error: {path.resolve()}: step: the state of probe is no longer finite")


def test_the_error_is_an_input_error_for_library_callers(scenario):
    path = scenario()
    path.with_name("vehicle.yaml").write_text(VEHICLE.replace("10 kg", "-1 kg"))
    with pytest.raises(InputError) as caught:
        load(path)
    assert (caught.value.line, caught.value.column, caught.value.field) == (3, 3, "rigid_body.mass")
    assert caught.value.file.endswith("vehicle.yaml")


def test_shipped_scenarios_validate(cli):
    from tests.conftest import ROOT
    files = sorted((ROOT / "scenarios").glob("*.yaml")) + sorted((ROOT / "vehicles").glob("*.yaml"))
    result = cli("validate", *files)
    assert result.exit_code == 0, result.output


def test_yaml_merge_keys_work_and_bad_values_are_input_errors(write, cli):
    """YAML merge keys (<<: *anchor) are applied as PyYAML applies them; a
    value YAML cannot construct is an input error with its line, not a traceback."""
    vehicle = write("vehicle.yaml", """\
        defaults: &body {mass: 10 kg, inertia: [0.15, 0.12, 0.05]}
        name: probe
        rigid_body:
          <<: *body
          length: 0.3 m
        """)
    result = cli("validate", vehicle)
    assert_clean_error(result, "vehicle.yaml:1:1", "unknown field 'defaults'")
    vehicle.write_text(vehicle.read_text().replace("defaults: &body", "name2: &body").replace(
        "name: probe", "name: !!python/name:os.system probe"))
    result = cli("validate", vehicle)
    assert_clean_error(result, "vehicle.yaml:2:")


def test_an_epoch_before_1970_is_refused_not_written_wrong(scenario, cli, tmp_path):
    """MCAP timestamps are unsigned ns since 1970: a 1969 epoch cannot be written, so it is an
    input error at the epoch's line, not a file of wrapped-around stamps."""
    path = scenario()
    mission = path.with_name("mission.yaml")
    mission.write_text(mission.read_text().replace("2026-11-26T12:00:00Z", "1969-07-16T13:32:00Z"))
    result = cli("fly", path, "-o", tmp_path / "run.mcap")
    assert_clean_error(result, "mission.yaml:1:1", "epoch", "before 1970-01-01")


def test_a_wait_until_condition_without_a_line_of_its_own_is_named_at_the_call(scenario, cli):
    # found by tests/fuzz (long profile): fc.wait_until(print) returned None from a builtin,
    # which has no line in the program: the error named the program but no line
    path = scenario(program="def main(fc):\n    fc.step()\n    fc.wait_until(print)\n")
    result = cli("fly", path, "-o", path.with_name("out.mcap"))
    assert_clean_error(result, "program.py:3: ", "the condition must return True or False, got None")
