"""A launcher of one's own, written from the docs alone, flies to orbit as designed.

A two-stage kerolox launcher (the vehicle example's fields in
docs/how-to/write-files.md: stages with their LOX and RP-1 tanks loaded in the engines'
mixture ratio, engines with their gimbal range and slew rate, payload, fairing, an ogive
nose capping the fairing) from Kourou, a site no file ships (that page's site example's
fields), to a 500 km orbit at 6 deg,
flown by the shipped ascent program (scenarios/programs/orbit_ascent.py, which flies
any two-stage vehicle to the mission's target). Nothing in the way: the files
validate without a warning, the vehicle stands on the pad at the site's height and
lifts off, the program's ``fc.ignite(first)`` and ``fc.ignite(upper)`` light one stage
each, and the upper stage reaches its orbit. Reference: the target the mission names,
periapsis within 10 % of its 500 km and the inclination within 0.1 deg of its 6 deg
(measured 491.0 x 518.6 km at 5.953 deg). Flown at the headless 0.1 s step (the
flight takes about 5 s).
"""

import math

import pytest

import rocketsim
from tests.conftest import ROOT

LAUNCHER = """\
name: kerolox-two
stages:
  - name: first stage
    length: 24 m
    diameter: 2.4 m
    structure_mass: 3.5 t
    tanks:
      - {name: RP-1, propellant: RP-1, density: 810 kg/m3, radius: 1.15 m, length: 7.5 m,
         position: 1.5 m, wall_mass: 500 kg, propellant_mass: 25 t}
      - {name: LOX, propellant: LOX, density: 1141 kg/m3, radius: 1.15 m, length: 13 m,
         position: 9.5 m, wall_mass: 900 kg, propellant_mass: 60 t}
    engines:
      - {name: main, count: 9, layout_radius: 0.8 m, position: 0.5 m, mass: 450 kg,
         thrust_vacuum: 200 kN, isp_vacuum: 300 s, exit_area: 0.25 m2, throttle: [0.5, 1.0],
         gimbal_range: 5 deg, gimbal_rate: 10 deg/s}
  - name: second stage
    length: 8 m
    diameter: 2.4 m
    structure_mass: 900 kg
    tanks:
      - {name: RP-1, propellant: RP-1, density: 810 kg/m3, radius: 1.15 m, length: 1.8 m,
         position: 1.2 m, wall_mass: 150 kg, propellant_mass: 5.8 t}
      - {name: LOX, propellant: LOX, density: 1141 kg/m3, radius: 1.15 m, length: 3.2 m,
         position: 3.2 m, wall_mass: 250 kg, propellant_mass: 14 t}
    engines:
      - {name: vacuum, position: 0.3 m, mass: 300 kg, thrust_vacuum: 120 kN, isp_vacuum: 340 s,
         exit_area: 1.2 m2, throttle: [0.6, 1.0], gimbal_range: 5 deg, gimbal_rate: 10 deg/s}
payload: {name: satellite, mass: 800 kg, length: 2 m, diameter: 1.8 m}
fairing: {mass: 400 kg, length: 5 m, diameter: 2.4 m}
aero:
  nose: {length: 2.5 m, shape: ogive}      # the top of the fairing
"""

SITE = """\
name: Kourou
latitude: 5.2390 deg
longitude: -52.7686 deg
height: 20 m
pad_azimuth: 90 deg
source: a launch site of one's own (the Guiana Space Centre's latitude and longitude)
"""

SCENARIO = f"""\
name: kourou-to-500-km
vehicle: launcher.yaml
site: kourou.yaml
program: {ROOT / 'scenarios' / 'programs' / 'orbit_ascent.py'}
mission:
  epoch: 2026-11-26T12:00:00Z
  start: {{site: {{}}}}
  duration: 700 s
  target: {{orbit: {{altitude: 500 km, inclination: 6 deg}}}}
step: 0.1 s
"""


def test_a_launcher_of_ones_own_from_a_new_site_reaches_its_orbit(write, cli):
    write("launcher.yaml", LAUNCHER)
    write("kourou.yaml", SITE)
    path = write("scenario.yaml", SCENARIO)
    checked = cli("validate", path)
    assert checked.exit_code == 0 and "warning" not in checked.output, checked.output
    run = rocketsim.fly(path)
    events = run.events[run.events["body"] == "kerolox-two"].set_index("name")
    lit = [[v for k, v in e.items() if k.startswith("engines[") and isinstance(v, str)]    # a list's
           for _, e in events.iterrows() if e.name == "ignition"]                      # items by column
    print(f"\n[own launcher] liftoff at T+{events.loc['liftoff', 't_s']:.1f} s; "
          f"orbit {events.loc['orbit', 'periapsis_altitude_m'] / 1e3:.1f} x "
          f"{events.loc['orbit', 'apoapsis_altitude_m'] / 1e3:.1f} km at "
          f"{events.loc['orbit', 'inclination_deg']:.3f} deg")
    assert lit == [[f"first stage/main/{k}" for k in range(1, 10)], ["second stage/vacuum"]]
    assert events.loc["liftoff", "t_s"] < 3.0           # standing on the pad, not falling to it
    assert "breakup" not in events.index and "impact" not in events.index
    assert events.loc["orbit", "periapsis_altitude_m"] == pytest.approx(500e3, rel=0.1)
    assert events.loc["orbit", "inclination_deg"] == pytest.approx(6.0, abs=0.1)
    assert "payload deploy" in events.index
    assert math.isfinite(run.bodies["payload"].final["altitude_m"])
