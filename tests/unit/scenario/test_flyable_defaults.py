"""Defaults a designer can fly: no default makes a vehicle unflyable in silence.

Each trap a new user met writing a vehicle from the docs is either refused before
anything flies, with an error naming the file, line and field, why, and a typical
value, or flies as designed:

- an engine with a gimbal cone and no slew rate (0 rad/s would hold it centred: a
  launcher so turns over in the air) is refused;
- a site with a height and no ground_height has its ground at the pad's height: the
  vehicle stands on its legs, compressed by their static deflection ``m g / (n k)``
  (on the ellipsoid's ground it would start in the air and fall); a ground given
  explicitly below a pad the vehicle stands on is refused;
- ``fc.ignite()`` lights the lowest stage's engines, never an upper stage's stacked above
  it (which would burn inside its interstage);
- a hobby rocket whose motor alone pushes it past the 15 g axial limit assumed for a
  launcher (a K1000T on 7 kg: 15.3 g at T+0.02 s, on the rail) is refused unless the
  file gives its airframe's limit; with one it flies as designed;
- a payload with no length or diameter (a 1 m by 1 m default would put a drum on a
  hobby rocket's nose) is refused.
"""

import pytest

import rocketsim
from rocketsim.constants import G0
from tests.conftest import ROOT
from tests.unit.scenario.test_scenario_errors import assert_clean_error

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


def _standing(site: dict, duration: str = "2 s") -> dict:
    return {"name": "standing", "vehicle": str(ROOT / "vehicles" / "lander.yaml"), "site": site,
            "mission": {"epoch": "2026-11-26T12:00:00Z", "start": {"site": {}}, "duration": duration}}


def test_the_ground_is_at_the_pads_height_unless_the_site_says_otherwise():
    """The lander on its four legs (8.5e7 N/m each) on a pad 40 m above the ellipsoid, no
    ground_height: after 2 s its centre of mass has sunk by the legs' static deflection
    ``m g / (4 k)`` = 0.436 mm (15.1 t), measured 0.463 mm (the pad's height is geodetic,
    the flat ground's radial: 26 um apart at 10 deg of latitude), not fallen 40 m to the
    ellipsoid."""
    run = rocketsim.fly(_standing({"name": "pad", "latitude": "10 deg", "longitude": "20 deg",
                                   "height": "40 m"}))
    table = run.bodies["lander"].table()
    sunk = table["altitude_m"].iloc[0] - table["altitude_m"].iloc[-1]
    mass = table["mass_kg"].iloc[0]
    deflection = mass * G0 / (4 * 8.5e7)
    print(f"\n[ground] sunk {sunk * 1e3:.4f} mm on the legs, static deflection {deflection * 1e3:.4f} mm")
    assert sunk == pytest.approx(deflection, abs=0.05e-3)
    assert run.events.empty or "impact" not in set(run.events["name"])


def test_a_ground_below_a_pad_the_vehicle_stands_on_is_refused():
    with pytest.raises(rocketsim.InputError, match="starts at rest on the pad, 40 m above the "
                       "ground .* it would fall at T\\+0"):
        rocketsim.load(_standing({"name": "pad", "latitude": "10 deg", "longitude": "20 deg",
                                  "height": "40 m", "ground_height": "0 m"}))


IGNITE = """
def main(fc):
    fc.event("lit", engines=",".join(fc.ignite()))
    fc.shutdown()
"""


def test_ignite_with_no_argument_lights_the_lowest_stage_only(write):
    """In orbit, the whole two-stage stack: ``fc.ignite()`` lights the booster's four
    engines and not the upper stage's."""
    vehicle = write("launcher.yaml", LAUNCHER.replace("gimbal_range: 5 deg\n", "gimbal_range: 5 deg\n"
                                                      "        gimbal_rate: 10 deg/s\n", 1))
    program = write("ignite.py", IGNITE)
    run = rocketsim.fly({"name": "ignite", "vehicle": str(vehicle), "program": str(program),
                         "mission": {"epoch": "2026-11-26T12:00:00Z", "duration": "1 s",
                                     "start": {"orbit": {"altitude": "400 km", "inclination": "51.6 deg"}}}})
    lit = run.events.set_index("name").loc["lit", "engines"]
    assert lit == ",".join(f"booster/main/{k}" for k in range(1, 5))


HOBBY = f"""\
name: hobby-k
stages:
  - name: rocket
    length: 1.6 m
    diameter: 0.1 m
    structure_mass: 4.1 kg
    motors: [{{name: K1000T, file: {ROOT / 'motors' / 'AeroTech_K1000T.eng'}}}]
    parachutes:
      - {{name: drogue, cd_s: 0.3 m2, deploy: apogee}}
      - {{name: main, cd_s: 2.5 m2, deploy: {{height: 300 m}}}}
payload: {{name: nose cone, mass: 0.4 kg, length: 0.4 m, diameter: 0.1 m}}
aero:
  nose: {{length: 0.4 m, shape: ogive}}
  fins: [{{stage: rocket, count: 4, position: 0.25 m, root_chord: 0.2 m, tip_chord: 0.08 m,
          span: 0.1 m, sweep: 0.1 m}}]
"""


def test_a_motor_past_the_launcher_limit_needs_the_airframes_own(write, cli):
    """The K1000T on a 7.1 kg rocket: 18.0 g 1.4 s into its burn (its thrust over the mass
    left), past the assumed 15 g. Refused at the aero section with a typical value; with
    ``limits: {axial_load: 40 g}`` it leaves its rail, burns out, reaches apogee and opens
    its drogue: no breakup."""
    path = write("hobby.yaml", HOBBY)
    assert_clean_error(cli("validate", path), "hobby.yaml:12:1:", "aero.limits:",
                       "the K1000T of stage 'rocket' pushes the stack at 18.0 g",
                       "past the 15 g axial limit assumed for a launcher",
                       "e.g. limits: {axial_load: 40 g}")
    path = write("hobby.yaml", HOBBY + "  limits: {axial_load: 40 g}\n")
    run = rocketsim.fly({"name": "hobby", "vehicle": str(path),
                         "site": {"name": "range", "latitude": "32.99 deg", "longitude": "-106.975 deg",
                                  "height": "1380 m"},
                         "mission": {"epoch": "2026-06-13T15:00:00Z", "duration": "40 s",
                                     "start": {"site": {"rail": {"length": "5.2 m", "inclination": "85 deg"}}}}})
    names = list(run.events["name"])
    print(f"\n[hobby] {names}")
    assert "breakup" not in names
    for name in ("off_rail", "burnout", "apogee", "parachute_deployed"):
        assert name in names


def test_a_payload_without_its_size_is_refused_at_its_line(write, cli):
    """A payload's size defaulted to 1 m by 1 m: on the 0.1 m hobby rocket, whose nose caps
    its payload, a 1 m drum on top. Its length and diameter are required, each refused
    at the payload's line with why and a typical value; given, the rocket is valid and its
    review finds it 0.1 m across (the stage's diameter, not the drum's)."""
    limited = HOBBY + "  limits: {axial_load: 40 g}\n"
    sized = "length: 0.4 m, diameter: 0.1 m"
    path = write("bare.yaml", limited.replace(", " + sized, ""))
    assert_clean_error(cli("validate", path), "bare.yaml:11:1:", "payload.length:",
                       "payload 'nose cone' gives no length", "the top of the vehicle's outline",
                       "e.g. length: 6 m for a launcher's satellite, 0.4 m for a hobby rocket's nose cone")
    path = write("short.yaml", limited.replace(sized, "length: 0.4 m"))
    assert_clean_error(cli("validate", path), "short.yaml:11:1:", "payload.diameter:",
                       "gives no diameter", "e.g. diameter: 4 m in a 5.2 m fairing")
    path = write("sized.yaml", limited)
    assert cli("validate", path).exit_code == 0
    assert rocketsim.review(path).diameter_m == pytest.approx(0.1)
