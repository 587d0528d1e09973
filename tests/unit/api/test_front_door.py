"""The Python front door: rocketsim.load, rocketsim.fly, rocketsim.open_run and Run.

What is checked, each against an independent way to the same result:

* a run kept in memory and the same flight's MCAP file read back are the same run:
  every table equal bit for bit (float64 bit patterns compared), the same events,
  summary and log lines; and the tables hold the CSV export's columns and numbers;
* a scenario given as a dict (its files' YAML read with PyYAML and inlined) flies
  bit-identically to the files; a program given as a callable (the file's own
  ``main``) flies identically to the program file; a dict scenario's run with a
  function program flies again from the file alone (``replay --verify``);
* an override of the booster's dry mass lands the booster exactly as a vehicle file
  with that mass written in does, and not as the nominal one;
* bad paths and units name the path and the nearest valid name (exit 2 on the command
  line, which reads quantities with the files' units);
* the summary names the central body of its orbits;
* examples/ runs.

Flights are short (the hop at the 0.05 s step of tests/flights/test_hop.py, 20 s where
the landing is not needed; 170 s of the Falcon 9 ascent at 0.05 s for the staging).
"""

from __future__ import annotations

import runpy
import subprocess
import sys

import numpy as np
import pytest
import yaml

import rocketsim
from rocketsim.api.run import same_table
from rocketsim.telemetry.names import column_name
from rocketsim.errors import InputError
from rocketsim.api.reflight import verify
from rocketsim.flight.program import load_program, load_program_module
from rocketsim.telemetry.tables import table as csv_table
from tests.conftest import ROOT

SCENARIOS = ROOT / "scenarios"
HOP = SCENARIOS / "falcon9-hop.yaml"
BOOSTER = "vehicle.stages[booster].structure_mass"


def same_flight(a: rocketsim.Run, b: rocketsim.Run) -> None:
    """Two runs fly the same: summary, events, log lines and every table, bit for bit."""
    assert a.summary == b.summary
    assert a.file.events == b.file.events
    assert a.logs == b.logs
    assert list(a.bodies) == list(b.bodies)
    for name in a.bodies:
        assert same_table(a.bodies[name].table(), b.bodies[name].table()), name


@pytest.fixture(scope="module")
def ascent(tmp_path_factory):
    """170 s of the Falcon 9 mission, in memory and to a file: MECO, the booster's
    separation and its programs, five bodies, throttles null when no engine runs."""
    path = tmp_path_factory.mktemp("ascent") / "run.mcap"
    options = dict(step=0.05, duration=170.0)
    return (rocketsim.fly(SCENARIOS / "falcon9-leo.yaml", **options),
            rocketsim.fly(SCENARIOS / "falcon9-leo.yaml", path, **options), path)


def test_a_run_in_memory_is_its_file_bit_for_bit(ascent):
    """Reference: the MCAP file the same flight wrote (rocketsim.open_run reads it back
    without executing its programs)."""
    memory, from_file, path = ascent
    assert memory.path is None and from_file.path == path
    assert len(memory.bodies) >= 2 and "booster" in memory.bodies
    assert memory == from_file
    assert memory == rocketsim.open_run(path)
    for name, body in memory.bodies.items():
        mine, theirs = body.table(), from_file.bodies[name].table()
        assert len(mine) > 0
        for column in mine.columns:
            x, y = mine[column].to_numpy(), theirs[column].to_numpy()
            if x.dtype.kind == "f":
                assert np.array_equal(x.view(np.int64), y.view(np.int64)), (name, column)
    throttle = memory.bodies["booster"].table()["throttle"]
    assert throttle.isna().any() and throttle.notna().any()      # null once its engines stop
    # a changed number is seen
    changed = memory.bodies["booster"].table()
    changed.iloc[-1, 0] = np.nextafter(changed.iloc[-1, 0], np.inf)
    assert not same_table(changed, from_file.bodies["booster"].table())


def test_the_tables_are_the_csv_export_with_units(ascent):
    """Reference: rocketsim.telemetry.tables.table, the columns the CSV export writes,
    decoded from the file message by message; units in the names (altitude_m...)."""
    memory, _, path = ascent
    for name, body in memory.bodies.items():
        columns = csv_table(path, name)
        frame = body.table(units=False)
        assert ["t"] + list(frame.columns) == list(columns)
        assert np.array_equal(frame.index.to_numpy(), np.round(np.array(columns["t"]), 6))
        for column in frame.columns:
            expected = [np.nan if v is None else v for v in columns[column]]
            got = frame[column].tolist()
            assert all(a == b or (a != a and b != b) for a, b in zip(got, expected)), column
        with_units = body.table()
        assert with_units.index.name == "t_s"
        assert list(with_units.columns) == [column_name(c) for c in frame.columns]
        assert with_units.index.to_list() == [round(t, 6) for t in columns["t"]]      # no float noise
    units = memory.bodies["booster"].table().columns
    assert {"altitude_m", "inertial_speed_m_s", "surface_speed_m_s", "height_agl_m", "position_x_m",
            "velocity_z_m_s", "mass_kg", "thrust_N", "dynamic_pressure_Pa", "latitude_deg", "mach", "propellant_tanks_booster_LOX_kg",
            "orbit_period_s", "engines_running"} <= set(units)
    assert memory.bodies["booster"].table()["engines_running"].dtype == np.int64


def test_the_run_reads_as_a_notebook_user_expects(ascent):
    memory, _, _ = ascent
    text = repr(memory)
    assert "\n" not in text and "falcon9-leo" in text and "in memory" in text
    events = memory.events
    assert list(events.columns[:3]) == ["t_s", "body", "name"]
    assert "liftoff" in set(events["name"]) and "separation" in set(events["name"])
    booster = memory.bodies["booster"]
    assert set(booster.events["body"]) == {"booster"}
    assert booster.final["time_s"] == pytest.approx(170.0)
    assert booster.orbit is None                # coming back down: its flight, not an orbit
    # it flew the ascent with the stack: its largest q is the ascent's (max-Q, 34 kPa), not
    # the 1.2 kPa of its own samples after the separation at T+133.7 s
    split = float(booster.events.set_index("name").loc["separation", "t_s"])
    stack = memory.bodies["falcon9-block5"].table()
    assert booster.flight["max_dynamic_pressure_Pa"] == stack.loc[:split, "dynamic_pressure_Pa"].max() > 20e3
    assert booster.table()["dynamic_pressure_Pa"].max() < 2e3
    assert 2684 * 0.05 != 134.2 and booster.table().loc[134.2, "altitude_m"] > 0.0   # found by its time
    assert booster.touchdown is None


def test_a_run_draws_inline_and_to_a_file(hop_20s, tmp_path):
    picture = hop_20s.plot()                    # a notebook shows it inline
    assert picture._repr_png_().startswith(b"\x89PNG")
    assert picture.save(tmp_path / "run.png").read_bytes() == picture.png


def _inlined(path):
    """The scenario at ``path`` as a dict with its vehicle, site and mission files inlined
    (read with PyYAML), its program paths relative to its folder."""
    data = yaml.safe_load(path.read_text())
    for name in ("vehicle", "site", "mission"):
        if isinstance(data.get(name), str):
            data[name] = yaml.safe_load((path.parent / data[name]).read_text())
    return data


@pytest.fixture(scope="module")
def hop_20s():
    return rocketsim.fly(HOP, step=0.05, duration=20.0)


def test_a_dict_scenario_flies_as_its_files(hop_20s):
    """Reference: the same scenario flown from its YAML files."""
    data = _inlined(HOP)
    assert isinstance(data["vehicle"], dict)
    run = rocketsim.fly(rocketsim.load(data, base_dir=SCENARIOS), step=0.05, duration=20.0)
    same_flight(run, hop_20s)
    assert run.metadata["files"]["scenario"] == "falcon9-hop.yaml"     # the dict, as a file


def test_a_dict_scenario_with_a_function_program_flies_again_from_its_file(hop_20s, tmp_path):
    """A run of a dict scenario whose program is a function not named ``main`` carries
    the scenario as YAML and the function's name: ``replay --verify`` flies it again
    from the file alone, message for message (reference: the run itself), and the
    flight is the file scenario's (reference: ``hop_20s``)."""
    source = (SCENARIOS / "programs" / "hop.py").read_text()
    assert source.count("def main(fc") == 1
    program = tmp_path / "programs" / "my_hop.py"
    program.parent.mkdir()
    program.write_text(source.replace("def main(fc", "def climb(fc"))
    data = _inlined(HOP)
    data["program"] = load_program(program, "climb")
    out = tmp_path / "run.mcap"
    run = rocketsim.fly(rocketsim.load(data, base_dir=SCENARIOS), out, step=0.05, duration=20.0)
    same_flight(run, hop_20s)
    assert run.metadata["entries"] == {"program": "climb"}
    verdict = verify(out, trust=True)
    assert verdict.identical and verdict.flight_error is None, verdict
    assert verdict.compared > 100


def test_a_callable_program_flies_as_its_file(hop_20s):
    """Reference: the program file the callable comes from, flown as a file."""
    main = load_program_module(SCENARIOS / "programs" / "hop.py").main
    run = rocketsim.fly(HOP, step=0.05, duration=20.0, program=main)
    same_flight(run, hop_20s)
    data = _inlined(HOP)
    data["program"] = main
    same_flight(rocketsim.fly(rocketsim.load(data, base_dir=SCENARIOS), step=0.05, duration=20.0), hop_20s)


def test_a_heavier_booster_lands_as_the_file_with_that_mass_says(tmp_path):
    """A booster 800 kg heavier (structure 9 690 kg for the file's 8 890): the override's
    touchdown equals, to the bit, that of a copy of the files with 9690 kg written in,
    and differs from the nominal one."""
    nominal = rocketsim.fly(HOP, step=0.05)
    heavier = rocketsim.fly(rocketsim.load(HOP, {BOOSTER: "9690 kg"}), step=0.05)
    vehicle = (ROOT / "vehicles" / "falcon9-block5.yaml").read_text()
    assert vehicle.count("structure_mass: 8890 kg") == 1
    (tmp_path / "vehicles").mkdir()
    (tmp_path / "vehicles" / "falcon9-block5.yaml").write_text(
        vehicle.replace("structure_mass: 8890 kg", "structure_mass: 9690 kg"))
    scenarios = tmp_path / "scenarios"
    scenarios.mkdir()
    (scenarios / "falcon9-hop.yaml").write_text(HOP.read_text())
    for folder in ("sites", "programs"):
        (scenarios / folder).symlink_to(SCENARIOS / folder)
    written = rocketsim.fly(scenarios / "falcon9-hop.yaml", step=0.05)
    booster = "falcon9-block5"
    landed = heavier.bodies[booster].touchdown
    assert landed is not None and nominal.bodies[booster].touchdown is not None
    assert landed == written.bodies[booster].touchdown
    assert landed != nominal.bodies[booster].touchdown
    same_flight(heavier, written)


@pytest.mark.parametrize("overrides, field, expected", [
    ({"vehicle.stages[boster].structure_mass": "26 t"}, "vehicle.stages[boster].structure_mass",
     "did you mean 'booster'?"),
    ({"vehicle.stage[booster].structure_mass": "26 t"}, "vehicle.stage[booster].structure_mass",
     "did you mean 'stages'?"),
    ({"vehicle.stages[booster].structure_mas": "26 t"}, "vehicle.stages[booster].structure_mas",
     "did you mean 'structure_mass'?"),
    ({"mision.epoch": "2026-11-27T15:00:00Z"}, "mision.epoch", "did you mean 'mission'?"),
    ({BOOSTER: "26 tonnes"}, BOOSTER, "unknown unit 'tonnes' for a mass"),
    ({"vehicle.stages[7].structure_mass": "26 t"}, "vehicle.stages[7].structure_mass", "out of range"),
    ({"vehicle.stages[*].engines[*].isp": "300 s"}, "vehicle.stages[*].engines[*].isp",
     "did you mean 'isp_vacuum'?"),
    ({"vehicle.stages..mass": 1}, "vehicle.stages..mass", "cannot read the path"),
])
def test_a_bad_override_names_its_path_and_the_nearest_name(overrides, field, expected):
    with pytest.raises(InputError) as caught:
        rocketsim.load(HOP, overrides)
    assert caught.value.field == field and expected in caught.value.message, str(caught.value)
    assert caught.value.file is None


def test_overrides_set_what_they_name():
    """Reference: the vehicle file's figures (a booster of 8 890 kg structure, nine
    engines of 311 s vacuum Isp on the booster) and the override's own values."""
    loaded = rocketsim.load(SCENARIOS / "falcon9-leo.yaml", {
        BOOSTER: "26 t", "mission.epoch": "2026-11-27T15:00:00Z",
        "vehicle.stages[*].engines[*].isp_vacuum": "300 s", "propellant[booster/LOX]": "100 t"})
    stages = loaded.scenario.vehicle.stages
    assert stages[0].structure_mass == 26_000.0 and stages[1].structure_mass != 26_000.0
    assert all(e.isp_vacuum == 300.0 for s in stages for e in s.engines)
    assert loaded.scenario.mission.epoch.isoformat() == "2026-11-27T15:00:00+00:00"
    assert rocketsim.load(SCENARIOS / "falcon9-leo.yaml").scenario.vehicle.stages[0].structure_mass == 8890.0


def test_a_dict_scenario_names_the_dotted_field():
    data = _inlined(HOP)
    data["mission"]["duration"] = "75 parsecs"
    with pytest.raises(InputError) as caught:
        rocketsim.load(data, base_dir=SCENARIOS)
    assert caught.value.file is None and caught.value.field == "mission.duration"
    assert "unknown unit 'parsecs'" in caught.value.message
    data = _inlined(HOP)
    data["vehicle"]["stages"][0]["structure_mas"] = 1
    with pytest.raises(InputError) as caught:
        rocketsim.load(data, base_dir=SCENARIOS)
    assert caught.value.field == "vehicle.stages[booster].structure_mas"
    assert "did you mean 'structure_mass'?" in caught.value.message


def test_the_command_line_reads_units_and_overrides(tmp_path, monkeypatch):
    """``rocketsim fly`` in-process (click's runner): exit statuses and messages as a shell sees them."""
    from click.testing import CliRunner
    from rocketsim_cli.main import main
    monkeypatch.chdir(tmp_path)
    ballistic = str(SCENARIOS / "spaceport-ballistic.yaml")
    done = CliRunner().invoke(main, ["fly", ballistic, "--duration", "2s", "--step", "50ms", "-o", "a.mcap",
                                     "--set", "vehicle.rigid_body.mass=310 kg"])
    assert done.exit_code == 0, done.output
    run = rocketsim.open_run(tmp_path / "a.mcap")
    assert run.summary["step_s"] == 0.05 and run.summary["mission_time_s"] == pytest.approx(2.0)
    assert run.metadata["overrides"] == {"vehicle.rigid_body.mass": '"310 kg"'}
    assert run.bodies["sounding-payload"].table()["mass_kg"].iloc[0] == 310.0
    for bad, words in [(["--duration", "2 fortnights"], "unknown unit 'fortnights' for a time"),
                       (["--step", "fast"], "'--step'"),
                       (["--set", "vehicle.rigid_body.mas=3 kg"], "did you mean 'mass'?"),
                       (["--set", "vehicle.rigid_body.mass=3 q"], "unknown unit 'q' for a mass")]:
        done = CliRunner().invoke(main, ["fly", ballistic, "-o", "b.mcap", *bad])
        assert done.exit_code == 2 and words in done.output, done.output
        assert done.exception is None or isinstance(done.exception, SystemExit)


def test_the_summary_names_the_central_body():
    """About Mars (scenarios/mars-entry.yaml starts in a 400 km Mars orbit) and about Earth."""
    mars = rocketsim.fly(SCENARIOS / "mars-entry.yaml", duration=5.0)
    assert {b["orbit"]["central_body"] for b in mars.summary["bodies"].values()} == {"mars"}
    assert mars.bodies["mars-entry-capsule"].orbit["central_body"] == "mars"


def test_the_summary_names_the_body_of_an_orbit_event():
    """An event with a periapsis (``orbit``, ``mars_orbit``, ``deorbit``...) names, in the
    summary, the body its body was about at the event; other events do not."""
    from rocketsim.scenario.load import load
    from rocketsim.sim.build import build_world
    world = build_world(load(SCENARIOS / "mars-entry.yaml"), duration=1.0)
    capsule = world.bodies[0]
    world.event(capsule, "mars_orbit", {"periapsis_altitude_m": 400e3})
    world.event(capsule, "hello", {"altitude_m": 1.0})
    assert capsule.events[-2] == {"name": "mars_orbit", "time_s": 0.0, "periapsis_altitude_m": 400e3,
                                  "central_body": "mars"}
    assert "central_body" not in capsule.events[-1]


def test_a_flight_that_fails_keeps_what_flew():
    """A program that raises after 1 s: the error names the program's line, and the run
    kept in memory up to it says so, as the file would."""
    def main(fc):
        fc.sleep(1.0)
        raise RuntimeError("engine out")

    with pytest.raises(InputError) as caught:
        rocketsim.fly(SCENARIOS / "spaceport-ballistic.yaml", program=main)
    assert "engine out" in str(caught.value) and caught.value.line == main.__code__.co_firstlineno + 2
    run = caught.value.run
    assert "engine out" in run.outcome and run.summary is None
    assert run.bodies["sounding-payload"].table().index[-1] == pytest.approx(1.0, abs=0.11)


def test_import_rocketsim_is_light():
    """``import rocketsim`` loads neither the compiled kernels nor pandas; every name of
    ``__all__`` resolves."""
    code = ("import sys, rocketsim; heavy = [m for m in ('numba', 'pandas') if m in sys.modules]; "
            "assert not heavy, heavy; [getattr(rocketsim, n) for n in rocketsim.__all__]")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr


def test_the_example_runs(tmp_path, monkeypatch, capsys):
    monkeypatch.setattr(sys, "argv", ["first_flight.py", str(tmp_path)])
    runpy.run_path(str(ROOT / "examples" / "first_flight.py"), run_name="__main__")
    assert "faster release is" in capsys.readouterr().out
    assert (tmp_path / "first_flight.png").read_bytes().startswith(b"\x89PNG")
