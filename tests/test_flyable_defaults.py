"""Defaults a designer can fly: no default makes a vehicle unflyable in silence.

Each trap a new user met writing a vehicle from the docs is either refused before
anything flies, with an error naming the file, line and field, why, and a typical
value, or flies as designed:

- an engine with a gimbal cone and no slew rate (0 rad/s would hold it centred: a
  launcher so turns over in the air) is refused.
"""

from tests.test_scenario_errors import assert_clean_error

LAUNCHER = """\
name: two-stage
stages:
  - name: booster
    length: 20 m
    diameter: 2 m
    structure_mass: 2 t
    tanks:
      - {name: LOX, propellant: LOX, density: 1141 kg/m3, radius: 0.95 m, length: 6 m, position: 2 m}
      - {name: RP-1, propellant: RP-1, density: 810 kg/m3, radius: 0.95 m, length: 4 m, position: 9 m}
    engines:
      - name: main
        count: 4
        layout_radius: 0.6 m
        thrust_vacuum: 200 kN
        isp_vacuum: 300 s
        exit_area: 0.3 m2
        gimbal_range: 5 deg
  - name: upper
    length: 6 m
    diameter: 2 m
    structure_mass: 500 kg
    tanks:
      - {name: LOX, propellant: LOX, density: 1141 kg/m3, radius: 0.95 m, length: 1.5 m, position: 1.5 m}
      - {name: RP-1, propellant: RP-1, density: 810 kg/m3, radius: 0.95 m, length: 1 m, position: 3.2 m}
    engines:
      - {name: vacuum, thrust_vacuum: 50 kN, isp_vacuum: 340 s, exit_area: 0.8 m2,
         gimbal_range: 5 deg, gimbal_rate: 10 deg/s}
"""


def test_a_gimbal_without_a_slew_rate_is_refused_at_its_line(write, cli):
    path = write("launcher.yaml", LAUNCHER)
    assert_clean_error(cli("validate", path), "launcher.yaml:11:9:",
                       "stages.0.engines.0.gimbal_rate:", "gimbals 5 deg but gives no gimbal_rate",
                       "cannot steer", "e.g. gimbal_rate: 10 deg/s")
    zero = write("zero.yaml", LAUNCHER.replace("gimbal_range: 5 deg\n", "gimbal_range: 5 deg\n"
                                               "        gimbal_rate: 0 deg/s\n", 1))
    assert_clean_error(cli("validate", zero), "zero.yaml:18:9:", "its gimbal_rate is 0")
    fixed = write("fixed.yaml", LAUNCHER.replace("gimbal_range: 5 deg\n", "gimbal_range: 5 deg\n"
                                                 "        gimbal_rate: 10 deg/s\n", 1))
    assert cli("validate", fixed).exit_code == 0
