"""Hostile files are refused within the bounds of rocketsim.limits and
rocketsim.scenario.bounds, at their line.

Each input here once hung the reader, took gigabytes, ended in a traceback or
flew a vehicle whose state went non-finite; each must now be an input error
(exit 2) naming the file, the line and the limit or physical bound, reading no
more than a bounded amount of memory.
"""

import json
import os
import tracemalloc

import numpy as np
import pytest

from rocketsim.atmosphere.sounding import parse_yaml
from rocketsim.constants import G0, GROUND_SUBSTEP_MAX, MAX_HEADLESS_STEP
from rocketsim.errors import InputError
from rocketsim.limits import MAX_DEPTH, MAX_TEXT_LENGTH, MAX_VALUES, MAX_YAML_BYTES, check_data
from rocketsim.scenario.bounds import MAX_CONTACT_RATE, MIN_DESCENT_SPEED, contact_rate, descent_speed
from rocketsim.scenario.load import load
from rocketsim.scenario.models import Scenario
from rocketsim.scenario.yaml_source import read_yaml
from tests.conftest import MISSION, ROOT, VEHICLE
from tests.unit.scenario.test_scenario_errors import assert_clean_error
from tests.unit.vehicle.test_vehicle_files import GOOD

# nine lists of nine, eight levels deep: 9^9 = 387 million strings once expanded
BILLION_LAUGHS = "a: &a [lol, lol, lol, lol, lol, lol, lol, lol, lol]\n" + "".join(
    f"{b}: &{b} [{', '.join(['*' + a] * 9)}]\n" for a, b in zip("abcdefg", "bcdefgh")) + "mission: *h\n"


def test_a_billion_laughs_is_refused_at_its_line_in_bounded_memory(write, cli):
    path = write("laughs.yaml", BILLION_LAUGHS)
    assert len(BILLION_LAUGHS) < 400
    tracemalloc.start()
    try:
        result = cli("validate", path)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    # expanding stops at the 100 001st value, under the first field that gets there
    assert_clean_error(result, "laughs.yaml:6:1", f"more than {MAX_VALUES} values")
    # 100 000 values and their positions take tens of MB; the expansion would take ~40 GB
    assert peak < 200e6, peak


@pytest.mark.parametrize("text, where", [
    ("a: " + "[" * 200 + "]" * 200 + "\n", "deep.yaml:1:"),           # would be a RecursionError
    ("a: &a [*a]\n", "deep.yaml:1:4"),                                  # an alias of itself
    ("a: &a {b: *a}\n", "deep.yaml:1:8"),
    ("a:\n" + "".join("  " * i + f"k{i}:\n" for i in range(1, 40)) + "  " * 40 + "x: 1\n", "deep.yaml:"),
])
def test_nesting_deeper_than_the_limit_is_refused(write, cli, text, where):
    result = cli("validate", write("deep.yaml", text))
    assert_clean_error(result, where, f"nested deeper than {MAX_DEPTH} levels")


def test_a_file_over_the_size_limit_is_refused_before_parsing(write, cli):
    path = write("vehicle.yaml", "name: probe\n# " + "x" * MAX_YAML_BYTES + "\n")
    # named at the line where the limit is crossed (found by tests/fuzz: an error with no line)
    assert_clean_error(cli("validate", path), "vehicle.yaml:2:",
                       f"larger than the {MAX_YAML_BYTES // 1024} KiB")
    many = write("scenario.yaml", "name: probe\n" + "# a comment line\n" * (MAX_YAML_BYTES // 17 + 9))
    line = (MAX_YAML_BYTES - len("name: probe\n")) // len("# a comment line\n") + 2
    assert_clean_error(cli("validate", many), f"scenario.yaml:{line}:")


def test_a_fifo_is_refused_not_read_forever(tmp_path, cli):
    fifo = tmp_path / "vehicle.yaml"
    os.mkfifo(fifo)
    # opening a FIFO for reading blocks until a writer comes: keep one open
    writer = os.open(fifo, os.O_RDWR | os.O_NONBLOCK)
    try:
        assert_clean_error(cli("validate", fifo), "vehicle.yaml", "not a regular file")
    finally:
        os.close(writer)


def test_a_long_text_is_refused_and_a_quoted_value_stays_short(write, cli):
    long = "y" * (MAX_TEXT_LENGTH + 1)
    result = cli("validate", write("vehicle.yaml", f"name: {long}\nrigid_body: {{}}\n"))
    assert_clean_error(result, "vehicle.yaml:1:1: name:", f"more than the {MAX_TEXT_LENGTH} allowed")
    # a long value that is merely wrong is quoted by its ends, not in full
    result = cli("validate", write("vehicle.yaml", f"name: probe\nrigid_body: {{mass: {'9' * 5000} kg}}\n"))
    assert_clean_error(result, "vehicle.yaml:2:", "rigid_body.mass")
    assert len(result.output) < 1000


@pytest.mark.parametrize("value", [".nan", ".inf", "-.inf", "1e400", "'1e308 km'", "'1e309 m'"])
def test_a_number_that_is_not_finite_is_refused_at_its_line(write, cli, value):
    path = write("vehicle.yaml", f"name: probe\nrigid_body:\n  mass: 10 kg\n  inertia: [0.15, 0.12, 0.05]\n"
                                 f"  length: {value}\n")
    assert_clean_error(cli("validate", path), "vehicle.yaml:5:3", "rigid_body.length", "finite")


def test_merge_keys_let_explicit_keys_win_and_earlier_merges_win(write):
    source = read_yaml(write("m.yaml", """\
        first: &first {x: 1, y: 1}
        second: &second {x: 2, y: 2, z: 2}
        merged:
          <<: [*first, *second]
          y: 3
        """))
    # the YAML merge-key rule: keys written in the mapping win, then the mappings in order
    assert source.data["merged"] == {"x": 1, "y": 3, "z": 2}


def test_merge_keys_cannot_expand_without_bound(write, cli):
    levels = "a: &a {k0: 0, k1: 1, k2: 2, k3: 3, k4: 4, k5: 5, k6: 6, k7: 7}\n" + "".join(
        f"{b}: &{b} {{{', '.join(f'{b}{i}: *{a}' for i in range(8))}}}\n" for a, b in zip("abcdefg", "bcdefgh"))
    assert_clean_error(cli("validate", write("m.yaml", levels)), "m.yaml:", f"more than {MAX_VALUES} values")


def test_a_scenario_handed_over_as_data_is_held_to_the_same_limits():
    looped = {"name": "x"}
    looped["self"] = looped
    with pytest.raises(InputError, match=f"nested deeper than {MAX_DEPTH}") as caught:
        Scenario.model_validate(looped)
    assert caught.value.field.startswith("self.self")
    with pytest.raises(InputError, match="more than the 65536 allowed") as caught:
        Scenario.model_validate({"name": "x", "vehicle": {"name": "y" * (MAX_TEXT_LENGTH + 1)}})
    assert caught.value.field == "vehicle.name"
    shared = ["lol"] * 10
    for _ in range(6):
        shared = [shared] * 10          # a million values by reference, ten lists in memory
    with pytest.raises(InputError, match=f"more than {MAX_VALUES} values"):
        check_data({"mission": shared})


def test_a_sounding_nested_too_deep_is_an_input_error():
    with pytest.raises(InputError, match="nested deeper") as caught:
        parse_yaml("PRES: " + "[" * 500 + "]" * 500 + "\n", "day.yaml")
    assert caught.value.file == "day.yaml" and caught.value.line == 1


@pytest.mark.parametrize("option, value, message", [
    ("--step", "nan", "got 'nan'"), ("--step", "1e-300", "not at least"),
    ("--duration", "inf", "got 'inf'"), ("--duration", "nan", "got 'nan'"),
    ("--duration", "-1", "not at least 0 s")])
def test_a_step_or_duration_out_of_range_on_the_command_line_is_refused(scenario, cli, tmp_path,
                                                                        option, value, message):
    result = cli("fly", scenario(), "-o", tmp_path / "run.mcap", option, value)
    assert_clean_error(result, option, message)


@pytest.mark.parametrize("mass", ["1e31 kg", "1.0e+308", "-2e30 t"])
def test_a_quantity_beyond_max_quantity_is_refused_at_its_line(write, cli, mass):
    # found by tests/fuzz (long profile): a stage 1e308 m long overflowed length ** 2 in its
    # inertia; every quantity is now held to MAX_QUANTITY (1e30 SI), its square and cube finite
    write("mission.yaml", MISSION.format(duration="1 s"))
    write("vehicle.yaml", VEHICLE.replace("mass: 10 kg", f"mass: {mass}"))
    path = write("scenario.yaml", "name: x\nvehicle: vehicle.yaml\nmission: mission.yaml\n")
    assert_clean_error(cli("validate", path), "vehicle.yaml:3:", "beyond the 1e+30")


@pytest.mark.parametrize("extra, where", [
    # found by tests/fuzz (long profile): numpy's SeedSequence refused a negative seed
    ("seed: -3\n", "scenario.yaml:4:"), ("weather: {kind: random, seed: -1}\n", "scenario.yaml:4:"),
    (f"seed: {2 ** 64}\n", "scenario.yaml:4:")])
def test_a_seed_outside_0_to_2_64_is_refused_at_its_line(scenario, cli, extra, where):
    assert_clean_error(cli("validate", scenario(extra=extra)), where, "seed")


@pytest.mark.parametrize("extra", [
    # found by tests/fuzz (long profile): a rate of 5e-324 Hz made rate * step 0 (a division by 0)
    "telemetry: {rate: 5.0e-324}\n", "telemetry: {rate: 0}\n"])
def test_a_telemetry_rate_under_a_microhertz_is_refused_at_its_line(scenario, cli, extra):
    assert_clean_error(cli("validate", scenario(extra=extra)), "scenario.yaml:4:", "telemetry.rate")


def test_a_pad_below_the_ground_is_refused_at_its_line(write, cli):
    # found by tests/fuzz (long profile): a pad 120 m below the ground started the vehicle
    # inside it, and its contact springs made the state non-finite at T+0.1 s
    write("site.yaml", "name: low\nlatitude: 28 deg\nlongitude: -80 deg\nheight: -120 m\n"
          "ground_height: 0 m\n")
    write("vehicle.yaml", VEHICLE)
    write("mission.yaml", "epoch: 2026-11-26T12:00:00Z\nstart: {site: {}}\nduration: 1 s\n")
    path = write("scenario.yaml", "name: x\nvehicle: vehicle.yaml\nsite: site.yaml\nmission: mission.yaml\n")
    assert_clean_error(cli("validate", path), "site.yaml:1:", "below the ground")


def test_an_integer_too_large_for_a_float_is_refused_at_its_line(scenario, cli):
    # found by tests/fuzz (long profile): float() of a 400-digit YAML integer overflowed
    result = cli("validate", scenario(duration="1" + "0" * 400))
    assert_clean_error(result, "mission.yaml:6:", "duration", "integer of 401 digits")


def test_a_mission_of_more_than_a_century_is_refused_at_its_line(scenario, cli):
    path = scenario(duration="1e30 s")
    result = cli("validate", path)
    assert_clean_error(result, "mission.yaml:6:", "duration", "a century")
    with pytest.raises(InputError):
        load(path)


@pytest.mark.parametrize("start, message", [
    # found by tests/fuzz (long profile): 1e308 m overflowed the J2 short-period terms (now
    # also beyond MAX_QUANTITY); a start beyond 67 au or 1 000 km/s is refused on its own
    ("orbit: {altitude: 1.0e+20, inclination: 51.6 deg}", "less than or equal to 10000000000000"),
    ("orbit: {altitude: -7000 km, inclination: 51.6 deg}", "below its surface"),
    ("orbit: {altitude: -25 km, inclination: 90 deg}", "below its surface"),
    ("orbit: {body: moon, semi_major_axis: 1 km, inclination: 0 deg}", "below its surface"),
    ("orbit: {semi_major_axis: 8000 km, eccentricity: 0.5, true_anomaly: 0 deg, "
     "inclination: 0 deg}", "below its surface"),
    ("state: {position: [1.0e+20, 0, 0], velocity: [0, 7.7 km/s, 0]}", "less than or equal to"),
    ("state: {position: [7000 km, 0, 0], velocity: [0, -1.0e+10, 0]}", "greater than or equal to"),
])
def test_a_start_too_far_too_fast_or_underground_is_refused_at_its_line(write, cli, start, message):
    """The start's distances and speeds are bounded (constants MAX_START_DISTANCE, 67 au,
    and MAX_START_SPEED, 1 000 km/s), and an orbit that starts below the surface (the
    polar radius) is refused: no overflow or square root of a negative number later."""
    write("vehicle.yaml", VEHICLE)
    write("mission.yaml", f"epoch: 2026-11-26T12:00:00Z\nstart:\n  {start}\nduration: 1 s\n")
    path = write("scenario.yaml", "name: x\nvehicle: vehicle.yaml\nmission: mission.yaml\n")
    assert_clean_error(cli("validate", path), "mission.yaml:3:", message)


@pytest.mark.parametrize("name, why", [("9" * 400 + ".yaml", "File name too long"),
                                       ("a\\0b.yaml", "embedded null byte")])
def test_a_referenced_file_name_the_system_cannot_take_is_an_error_at_its_line(write, cli, name, why):
    # found by tests/fuzz: the check that the file exists raised OSError / ValueError
    path = write("scenario.yaml", f'name: x\nvehicle: "{name}"\nmission: mission.yaml\n')
    assert_clean_error(cli("validate", path), "scenario.yaml:2:1: vehicle:", "cannot be a file name", why)


def test_inline_sounding_columns_are_checked_where_they_are_written(write, cli):
    # found by tests/fuzz: columns of different lengths passed validation and failed at
    # the flight's start with no file or line
    path = write("scenario.yaml", """\
        name: probe
        vehicle: {name: probe, rigid_body: {mass: 10 kg, inertia: [0.15, 0.12, 0.05]}}
        mission: {epoch: 2026-11-26T12:00:00Z, start: {orbit: {altitude: 415 km, inclination: 0 deg}},
                  duration: 1 s}
        weather:
          kind: sounding
          columns: {PRES: [1000, 850, 700], HGHT: [100, 1500, 3000], TEMP: [20.0, 12.5]}
        """)
    assert_clean_error(cli("validate", path), "scenario.yaml:5:1: weather:", "column TEMP has 2 values, HGHT has 3")


# the staged vehicle of tests/unit/vehicle/test_vehicle_files.py, one line a field, with legs and a thruster
STAGED = GOOD + """\
        count: 1
        spool_up: 1 s
        gimbal_range: 5 deg
        gimbal_rate: 10 deg/s
aero:
  nose: {length: 2 m, shape: ogive}
  legs: [{stage: S1, position: -1 m, radius: 2 m, stiffness: 1.0e+7, damping: 1.0e+5}]
  rcs: [{stage: S1, tank: T, position: 9 m, direction: [0, 1, 0], thrust: 400 N, isp: 70 s}]
"""


@pytest.mark.parametrize("written, changed, where, message", [
    # found by tests/fuzz (long profile): figures scaled by a careless edit (x 1e-6, x 1e6,
    # x 0) flew a vehicle whose state went non-finite in the first steps; each is now
    # refused at its line, naming the physical bound (rocketsim.scenario.bounds)
    ("length: 10 m", "length: 1.0e+7 m", "v.yaml:4:", "at most 1000 m"),
    ("diameter: 2 m", "diameter: 1.0e-6 m", "v.yaml:5:", "at least 0.001 m"),
    ("structure_mass: 1000 kg", "structure_mass: 0 kg", "v.yaml:6:", "at least 0.0001 kg"),
    ("density: 1000 kg/m3", "density: 1.0e+9 kg/m3", "v.yaml:10:", "at most 100000 kg/m3"),
    ("count: 1", "count: 1000000", "v.yaml:20:", "at most 1000"),
    ("thrust_vacuum: 100 kN", "thrust_vacuum: 1.0e+12 N", "v.yaml:16:", "at most 1e+08 N"),
    ("isp_vacuum: 300 s", "isp_vacuum: 3.0e-4 s", "v.yaml:17:", "at least 1 s"),
    ("isp_vacuum: 300 s", "mass_flow: 1.0e-9 kg/s", "v.yaml:17:", "specific impulse of 1.01972e+13 s"),
    ("exit_area: 0.5 m2", "exit_area: 5.0e+11 m2", "v.yaml:18:", "at most 1e+06 m2"),
    ("spool_up: 1 s", "spool_up: 1.0e-6 s", "v.yaml:21:", "at least 0.001 s"),
    ("gimbal_range: 5 deg", "gimbal_range: 500 deg", "v.yaml:22:", "at most 1.5708 rad"),
    ("stiffness: 1.0e+7", "stiffness: 1.0e+20", "v.yaml:26:", "at most 1e+12 N/m"),
    # within 1e12 N/m, but four legs of 1e10 N/m on the 1 t stage are a mode of 6 325 /s
    # (sqrt(4e10 / 1000)), far beyond RK4 at 5 ms; dampers of 1e7 N s/m one of 4e4 /s (c / m)
    ("stiffness: 1.0e+7", "stiffness: 1.0e+10", "v.yaml:26:", "aero.legs.0.stiffness: 4 legs "
     "(stiffness 4e+10 N/m together) on 1000 kg (the dry mass they hold up) are a mode of 6324.56 /s"),
    ("damping: 1.0e+5", "damping: 1.0e+7", "v.yaml:26:", "aero.legs.0.damping: 4 legs (damping "
     "4e+07 N s/m together) on 1000 kg (the dry mass they hold up) are a mode of 39999 /s"),
    ("direction: [0, 1, 0]", "direction: [1.0e+300, 1.0e+300, 0]", "v.yaml:27:", "within 1e30"),
    ("isp: 70 s", "isp: 7.0e+9 s", "v.yaml:27:", "at most 100000 s"),
    ("length: 2 m, shape", "length: 200 m, shape", "v.yaml:25:",
     "longer than the top stage 'S1' (10 m), the part it caps"),
    ("count: 1", "count: 3\n        layout_radius: 5 m", "v.yaml:21:", "wider than stage"),
])
def test_a_vehicle_figure_beyond_its_physical_bound_is_refused_at_its_line(write, cli, written, changed,
                                                                        where, message):
    assert written in STAGED
    path = write("v.yaml", STAGED.replace(written, changed, 1))
    assert_clean_error(cli("validate", path), where, message)


def test_the_staged_vehicle_of_these_tests_is_valid(write, cli):
    assert cli("validate", write("v.yaml", STAGED)).exit_code == 0


@pytest.mark.parametrize("inertia, message", [
    ("[0.15, 0.12, 0.5]", "more than the other two moments together"),
    ("[1.0e-12, 1.0e-12, 1.0e-12]", "radius of gyration of 3.16228e-07 m"),
    ("[1.0e+9, 1.0e+9, 1.0e+9]", "radius of gyration of 10000 m"),
])
def test_a_rigid_body_with_inertia_no_body_has_is_refused_at_its_line(write, cli, inertia, message):
    path = write("v.yaml", VEHICLE.replace("[0.15, 0.12, 0.05]", inertia))
    assert_clean_error(cli("validate", path), "v.yaml:4:", "rigid_body.inertia", message)


def test_an_orbit_whose_osculating_start_is_underground_is_refused_at_its_line(write, cli):
    # found by tests/fuzz (long profile): a Falcon 9 at a mean altitude of 0 km. The mean
    # radius passed the polar-radius check, but J2's short-period terms put the osculating
    # start 4 km below the ellipsoid, and the legs' springs, kilometres deep, made the state
    # non-finite at T+0.02 s. 10 km up is 3.6 km above the ground: it flies (and breaks up)
    write("vehicle.yaml", VEHICLE)
    for altitude, code in (("2 km", 2), ("10 km", 0)):
        write("mission.yaml", MISSION.format(duration="1 s").replace("415 km", altitude)
              .replace("51.6 deg", "28.5 deg"))
        path = write("scenario.yaml", "name: x\nvehicle: vehicle.yaml\nmission: mission.yaml\n")
        result = cli("validate", path)
        assert result.exit_code == code, result.output
    write("mission.yaml", MISSION.format(duration="1 s").replace("415 km", "2 km")
          .replace("51.6 deg", "28.5 deg"))
    assert_clean_error(cli("validate", path), "mission.yaml:3:", "below its surface there",
                       "osculating orbit of these mean elements")


def test_a_state_inside_the_earth_is_refused_at_its_line(write, cli):
    write("vehicle.yaml", VEHICLE)
    write("mission.yaml", "epoch: 2026-11-26T12:00:00Z\nstart:\n  state: {position: [0, 0, 6000 km], "
                          "velocity: [7 km/s, 0, 0]}\nduration: 1 s\n")
    path = write("scenario.yaml", "name: x\nvehicle: vehicle.yaml\nmission: mission.yaml\n")
    assert_clean_error(cli("validate", path), "mission.yaml:3:", "starts inside the Earth")


def test_a_cpu_budget_the_system_timer_cannot_hold_is_refused_at_its_line(scenario, cli, tmp_path):
    # setitimer takes no more than about 3e9 s: a budget of 1e10 s raised OverflowError
    # from the program's first step, a traceback
    path = scenario(program="def main(fc):\n    fc.sleep(0.1)\n", extra="program_cpu_budget: 1.0e+10 s\n")
    assert_clean_error(cli("fly", path, "-o", tmp_path / "run.mcap"), "scenario.yaml:4:",
                       "program_cpu_budget", "at most 3600 s")


@pytest.mark.parametrize("text, message", [
    ("; a motor\nK 54 300 P 0.1 0.2 X\n0.5 2.0e+9\n1 0\n", "line 3: thrust_N must be at least 0 N"),
    ("; a motor\nK 54 300 P 0.1 0.2 X\n0.5 5\n1.0e+9 0\n", "line 4: time_s must be at least 0 s and at most 3600 s"),
    ("; a motor\nK 1.0e+9 300 P 0.1 0.2 X\n0.5 5\n1 0\n", "line 2: diameter_mm must be"),
    ("; a motor\nK 54 300 P 0.1 0.2 X\n1.0e-9 1.0e-9\n2.0e-9 0\n", "delivers 1e-18 N s"),
])
def test_a_motor_file_beyond_the_physical_bounds_is_refused_at_its_line(write, cli, text, message):
    write("m.eng", text)
    path = write("v.yaml", "name: r\nstages:\n  - name: S\n    length: 1 m\n    diameter: 0.1 m\n"
                           "    structure_mass: 1 kg\n    motors: [{name: M, file: m.eng}]\n")
    assert_clean_error(cli("validate", path), "v.yaml:7:", message)


def test_the_schema_names_each_bound_and_why(cli):
    schema = json.loads(cli("schema", "--kind", "vehicle").output)
    engine = schema["$defs"]["EngineSpec"]["properties"]
    assert engine["thrust_vacuum"]["description"].startswith("vacuum thrust of one engine")
    assert "[bounds: above 0 N and at most 1e+08 N: no engine" in engine["thrust_vacuum"]["description"]
    assert "at least 1 and at most 1000" in engine["count"]["description"]
    stage = schema["$defs"]["StageSpec"]["properties"]
    assert "at least 0.001 m and at most 1000 m" in stage["length"]["description"]


@pytest.mark.parametrize("kind", ["scenario", "vehicle", "site", "mission"])
def test_every_quantity_in_the_schema_names_its_units_and_gives_an_example(cli, kind):
    """Every field of every model that reads a quantity (rocketsim.scenario.units) says in
    its schema's description its dimension and the units it takes, and gives an example
    value the file could hold (read back as that quantity, it parses)."""
    from rocketsim.scenario.load import REFERENCED
    from rocketsim.scenario.models import Scenario
    from rocketsim.scenario.units import Dimension, _dimension_of, parse_quantity
    schema = json.loads(cli("schema", "--kind", kind).output)
    models = {}

    def collect(model):
        if model.__name__ in models:
            return
        models[model.__name__] = model
        for info in model.model_fields.values():
            for inner in _models(info.annotation):
                collect(inner)

    collect(Scenario if kind == "scenario" else REFERENCED[kind])
    checked = 0
    for name, model in models.items():
        properties = (schema if model.__name__ == schema.get("title") else
                      schema.get("$defs", {}).get(name, {})).get("properties", {})
        for field, info in model.model_fields.items():
            dimension = next((m for m in info.metadata if isinstance(m, Dimension)), None) \
                or _dimension_of(info.annotation)
            if dimension is None or field not in properties:
                continue
            prop = properties[field]
            assert f"({dimension.name.replace('_', ' ')}:" in prop["description"], (name, field)
            for example in prop["examples"]:
                parse_quantity(example, dimension.name)
            checked += 1
    print(f"\n[schema] {kind}: {checked} quantity fields")
    assert checked > {"scenario": 100, "vehicle": 80, "site": 3, "mission": 10}[kind]


def _models(annotation):
    """The pydantic models inside an annotation (through Optional, Union, list, tuple, dict)."""
    import typing
    from pydantic import BaseModel
    if isinstance(annotation, type) and issubclass(annotation, BaseModel):
        yield annotation
    for arg in typing.get_args(annotation):
        yield from _models(arg)


# the hobby rocket of vehicles/hobby-rocket.yaml (13.9 kg dry with its nose cone, the payload),
# its motor file named where it is
HOBBY = (ROOT / "vehicles" / "hobby-rocket.yaml").read_text().replace(
    "../motors/", f"{(ROOT / 'motors').as_posix()}/")


@pytest.mark.parametrize("written, changed, where, message", [
    # a drag area a million times any parachute's: it flew 136 s to an altitude of 1e24 km
    # and exited 0 (its descent's mode, 2 g / v, far beyond RK4 at the step)
    ("cd_s: 5.65 m2", "cd_s: 1.0e+12 m2", "hobby.yaml:43:9: stages.0.parachutes.1.cd_s",
     "at most 10000 m2: the largest parachutes flown"),
    # within 1e4 m2, but 300 m2 on the 13.9 kg body descends at 0.86 m/s, sqrt(2 m g0 / (rho0 C_D S))
    ("cd_s: 5.65 m2", "cd_s: 300 m2", "hobby.yaml:43:9: stages.0.parachutes.1.cd_s",
     "(13.948 kg, dry) under all its parachutes (300.445 m2 of C_D S) would descend at 0.862 m/s"),
    ("inflation: 1.5 s", "inflation: 1.0e-9 s", "hobby.yaml:45:9: stages.0.parachutes.1.inflation",
     "at least 0.001 s"),
    ("lag: 1.0 s               # ejection", "lag: 1.0e+9 s  # ejection",
     "hobby.yaml:39:9: stages.0.parachutes.0.lag", "at most 3600 s"),
    ("deploy: {height: 300 m}", "deploy: {height: -3 m}",
     "hobby.yaml:46:18: stages.0.parachutes.1.deploy.height", "must be at least 0 m"),
    # the union's other branch (after:) knows no 'height': this said "unknown field
    # 'height'; did you mean 'height'?"
    ("deploy: {height: 300 m}", "deploy: {height: 300 stone}",
     "hobby.yaml:46:18: stages.0.parachutes.1.deploy.height", "unknown unit 'stone' for a length"),
    # a deployment a billion years after apogee never comes: bounded by the longest mission;
    # the union's other branch (height:) knows no 'after': this said "unknown field 'after'"
    ("deploy: {height: 300 m}", "deploy: {after: {event: apogee, delay: 1.0e+12 s}}",
     "hobby.yaml:46:41: stages.0.parachutes.1.deploy.after.delay", "at most 3.15576e+09 s"),
    # four base points of 1e10 N/m on 13.9 kg: a mode of 5.4e4 /s; it touched down at 7e9 m/s
    ("body_contact_stiffness: 2.0e5", "body_contact_stiffness: 1.0e+10",
     "hobby.yaml:59:3: aero.body_contact_stiffness", "a mode of 53551.8 /s, faster than 500 /s"),
])
def test_parachutes_and_contact_springs_beyond_their_bounds_are_refused_at_their_line(
        write, cli, written, changed, where, message):
    assert written in HOBBY
    path = write("hobby.yaml", HOBBY.replace(written, changed, 1))
    assert_clean_error(cli("validate", path), where, message)


def test_the_hobby_rocket_of_these_tests_is_valid(write, cli):
    assert cli("validate", write("hobby.yaml", HOBBY)).exit_code == 0


def rk4_growth(z: complex) -> float:
    """|R(z)|, RK4's amplification of the mode y' = lambda y over a step, z = lambda h
    (E. Hairer, G. Wanner, Solving Ordinary Differential Equations II, section IV.2)."""
    return abs(1 + z + z ** 2 / 2 + z ** 3 / 6 + z ** 4 / 24)


def test_the_mass_bounds_keep_rk4_stable_at_their_steps():
    # a contact's mode of MAX_CONTACT_RATE at the longest ground sub-step, at any damping
    # (the roots of m s^2 + c s + k, in the left half-plane), does not grow
    z = MAX_CONTACT_RATE * GROUND_SUBSTEP_MAX
    assert max(rk4_growth(z * np.exp(1j * a)) for a in np.linspace(np.pi / 2, np.pi, 1001)) <= 1.0
    assert rk4_growth(2.9j) > 1.0           # an undamped one of 580 /s would
    # a descent at its terminal speed v: m v' = m g - rho C_D S v^2 / 2 linearised is a
    # mode of -2 g / v; at MIN_DESCENT_SPEED and the longest step it does not grow
    assert rk4_growth(-2 * G0 / MIN_DESCENT_SPEED * MAX_HEADLESS_STEP) <= 1.0
    # the figures the bounds are checked with, against numpy's roots and the drag balance
    for m, k, c in ((1000.0, 4e10, 4e5), (1000.0, 4e7, 4e7), (2.0, 1e4, 1e2)):
        assert contact_rate(m, k, c) == pytest.approx(max(abs(np.roots([m, c, k]))), rel=1e-9)
    v = descent_speed(13.948, 300.0)
    assert 0.5 * 1.225 * 300.0 * v ** 2 == pytest.approx(13.948 * G0, rel=1e-5)  # USSA's 1.2250 kg/m3
