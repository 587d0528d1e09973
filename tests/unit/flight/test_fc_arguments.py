"""Every fc call checks its arguments: a bad one stops the flight at the program's line.

Each case here was once accepted silently (a nan pitch flew on, a condition
returning None waited out the flight), or ended in a numba traceback (a
1e30 s cruise overflowed the kernels' step count), or ended the simulator
with no message (``sys.exit``). Now each is a program error: exit 2, the
program's file and line, the telemetry finished with the error recorded.
"""

import math

import numpy as np
import pytest

from rocketsim.flight import arguments
from rocketsim.telemetry.reader import metadata
from tests.unit.scenario.test_scenario_errors import assert_clean_error

CASES = [
    ("fc.cruise(1e30)", "fc.cruise(): seconds must be within"),
    ("fc.sleep(1e30)", "fc.sleep(): seconds must be within"),
    ("fc.sleep(float('inf'))", "fc.sleep(): seconds must be a finite number"),
    ("fc.sleep(-5)", "fc.sleep(): seconds must be within"),
    ("fc.throttle(10**400)", "fc.throttle(): value must be a finite number, got inf"),
    ("fc.sleep('5')", "fc.sleep(): seconds must be a number, got '5'"),
    ("fc.point(float('nan'), 0.0)", "fc.point(): pitch must be a finite number, got nan"),
    ("fc.point(1e300, 0.0)", "fc.point(): pitch must be within"),
    ("fc.point(0.0, 1e300)", "fc.point(): heading must be within"),
    ("fc.point(0.0, 0.0, roll=float('inf'))", "fc.point(): roll must be a finite number"),
    ("fc.point(True, 0.0)", "fc.point(): pitch must be a number, got True"),
    ("fc.wait_until(lambda: None)", "fc.wait_until(): the condition must return True or False, got None"),
    ("fc.wait_until(5)", "fc.wait_until() needs a function"),
    ("fc.point_at([1.0, float('nan'), 0.0])", "fc.point_at(): vector[1] must be a finite number"),
    ("fc.point_at([1e308, 1e308, 0.0])", "fc.point_at(): vector[0] must be within -1e+150 .. 1e+150, got 1e+308"),
    ("fc.point_at([0.0, 0.0, 0.0])", "fc.point_at() needs a non-zero vector"),
    ("fc.point_at('abc')", "fc.point_at(): vector must be 3 numbers"),
    ("fc.point_at([1, 0, 0], frame='ecef')", "fc.point_at(): frame must be one of eci, local"),
    ("fc.hold(['prograde'])", "fc.hold(): mode must be one of prograde"),
    ("fc.rcs(np.array([1, 2]))", "fc.rcs(): on must be True or False"),
    ("fc.throttle(float('nan'))", "fc.throttle(): value must be a finite number"),
    ("fc.ignite(1.5)", "fc.ignite(): which must be None, an engine index or name"),
    ("fc.event('x', figure=[1, [2]])", "fc.event(): the figure figure[1] must be a number"),
    ("fc.event('x', figure={'a': 1})", "fc.event(): the figure figure must be a number"),
    ("fc.event('x', n=10**30)", "fc.event(): the figure n is an integer beyond 64 bits"),
    ("fc.log('x' * 100_000)", "fc.log(): the line is 100000 characters long"),
    ("fc.body_state('pluto')", "fc.body_state(): name must be one of sun, earth, moon, mars"),
    ("fc.predict(float('nan'))", "fc.predict(): seconds must be a finite number"),
    ("fc.predict(60.0, delta_v=[1.0, 2.0])", "fc.predict(): delta_v must be 3 numbers, got 2"),
    ("fc.predict(60.0, delta_v=[3e8, 1.0, 0.0])", "fc.predict(): delta_v must be slower than light (299792458 m/s), "
                                                  "got 3e+08 m/s"),
    ("fc.predict(60.0, delta_v=[1e160, 0.0, 0.0])", "fc.predict(): delta_v[0] must be within -1e+150 .. 1e+150"),
    ("fc.below('nose_angle', 0.1, towards=[0.0, 0.0, 0.0])", "fc.below(): towards must be a non-zero vector"),
    ("import sys; sys.exit(3)", "the program called sys.exit(3)"),
    ("raise GeneratorExit", "the program raised GeneratorExit"),
]


@pytest.mark.parametrize("call, message", CASES, ids=[c for c, _ in CASES])
def test_a_bad_fc_call_stops_the_flight_at_the_programs_line(scenario, cli, tmp_path, call, message):
    program = f"import numpy as np\n\ndef main(fc):\n    fc.step()\n    {call}\n    fc.step()\n"
    out = tmp_path / "run.mcap"
    result = cli("fly", scenario(program, duration="0.2 s"), "-o", out)
    assert_clean_error(result, "program.py:5:", message)
    outcome = metadata(out)["outcome"]         # the telemetry was finished, with the error
    assert outcome["status"] == "error" and message[:20] in outcome["error"], outcome


def test_a_condition_that_is_not_true_or_false_names_the_conditions_line(scenario, cli, tmp_path):
    program = "def main(fc):\n    fc.step()\n    fc.wait_until(\n        lambda: fc.altitude)\n"
    result = cli("fly", scenario(program, duration="0.2 s"), "-o", tmp_path / "run.mcap")
    assert_clean_error(result, "program.py:4:", "must return True or False, got 415")


def test_sys_exit_at_the_top_level_is_a_program_error(scenario, cli, tmp_path):
    program = "import sys\nsys.exit(0)\n\ndef main(fc):\n    pass\n"
    result = cli("fly", scenario(program), "-o", tmp_path / "run.mcap")
    assert_clean_error(result, "program.py:2:", "the program called sys.exit(0)")


def test_good_arguments_pass_as_the_simulator_uses_them():
    assert arguments.number("fc.throttle", "value", np.float32(0.5)) == 0.5
    assert arguments.angle("fc.point", "pitch", math.radians(90.0), arguments.MAX_PITCH) == math.pi / 2
    assert arguments.vector("fc.point_at", "v", np.array([1, 2, 3])).tolist() == [1.0, 2.0, 3.0]
    assert arguments.flag("fc.rcs", "on", np.bool_(True)) is True
    assert arguments.engines("fc.ignite", ["booster", 0, np.int64(1)]) == ["booster", 0, np.int64(1)]
    assert arguments.figures("fc.event", {"n": np.int64(3), "x": np.float64(1.5), "ok": np.bool_(False),
                                          "unknown": math.nan, "phase": "coast",
                                          "target": np.array([1.0, 0.0, 0.0]), "names": ("a", "b")}) == \
        {"n": 3, "x": 1.5, "ok": False, "unknown": pytest.approx(math.nan, nan_ok=True), "phase": "coast",
         "target": [1.0, 0.0, 0.0], "names": ["a", "b"]}
    assert arguments.truth(np.bool_(True)) is True
