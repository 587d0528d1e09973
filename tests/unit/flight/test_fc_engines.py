"""A program commands engines through fc: ignition, throttle, shutdown, readings."""

import pytest

from rocketsim.constants import G0
from rocketsim.scenario.load import load
from rocketsim.api.telemetry_flight import fly_to_file as fly
from tests.conftest import ROOT

PROGRAM = """
def main(fc):
    fc.event("start", thrust=fc.thrust, mass=fc.mass, engines=len(fc.engines), g=fc.acceleration)
    fc.event("ignited", names=",".join(fc.ignite()))
    fc.throttle(1.0)
    fc.sleep(5.0)
    fc.event("burning", thrust=fc.thrust, mass=fc.mass, propellant=sum(fc.propellant.values()),
             g=fc.acceleration)
    fc.sleep(5.0)
    fc.event("still burning", mass=fc.mass, propellant=sum(fc.propellant.values()))
    fc.shutdown()
    fc.sleep(2.0)
    fc.event("off", thrust=fc.thrust, again=",".join(fc.shutdown()), g=fc.acceleration)
"""


def test_a_program_burns_the_lander_engine_in_orbit(write, tmp_path):
    """The lander's descent engine (Apollo DPS: 45.04 kN vacuum thrust, Isp
    311 s, from the file's cited sources) in vacuum: full thrust 5 s after
    ignition (dead time 0.3 s + spool-up 1.0 s), mass flow T / (g0 Isp), and no
    thrust 2 s after shutdown (tail-off 0.25 s). The accelerometers (fc.acceleration)
    read T / m at full thrust and nothing before ignition and after the tail-off (at
    700 km, above the air: at 400 km they read its drag, 2e-9 of the thrust)."""
    write("program.py", PROGRAM)
    path = write("scenario.yaml", f"""\
        name: burn
        vehicle: {ROOT / 'vehicles' / 'lander.yaml'}
        program: program.py
        mission:
          epoch: 2026-11-26T12:00:00Z
          start: {{orbit: {{altitude: 700 km, inclination: 28.5 deg}}}}
          duration: 14 s
        """)
    events = {e["name"]: e for e in fly(load(path), tmp_path / "run.mcap")["bodies"]["lander"]["events"]}
    assert events["start"]["thrust"] == 0.0 and events["start"]["engines"] == 1
    assert events["ignited"]["names"]
    assert events["burning"]["thrust"] == pytest.approx(45.04e3, rel=1e-9)
    flow = 45.04e3 / (G0 * 311.0)
    burned = events["burning"]["mass"] - events["still burning"]["mass"]
    assert burned == pytest.approx(flow * 5.0, rel=1e-9)
    assert events["burning"]["propellant"] - events["still burning"]["propellant"] == pytest.approx(burned)
    assert events["off"]["thrust"] == 0.0 and events["off"]["again"] == ""
    assert events["burning"]["g"] * G0 == pytest.approx(45.04e3 / events["burning"]["mass"], rel=1e-9)
    assert abs(events["start"]["g"]) < 1e-12 and abs(events["off"]["g"]) < 1e-12


def test_engine_commands_on_a_vehicle_without_engines_are_a_clear_error(scenario, cli, tmp_path):
    path = scenario("def main(fc):\n    fc.ignite()\n")
    result = cli("fly", path, "-o", tmp_path / "run.mcap")
    assert result.exit_code == 2
    assert "program.py:2" in result.output and "has no engines" in result.output
