"""The pre-flight design review (rocketsim/vehicle/review.py, ``rocketsim.review``,
``rocketsim vehicle``), each figure against an independent reference:

- the static margin of the hobby rocket and of the two measured-flight rockets
  against RocketPy's ``static_margin`` (a peer library used only in tests, its own
  Barrowman sum and mass model) for the same rocket (tests/rocketpy_rockets.py), at
  liftoff and at burnout: within 0.1 calibre (measured within 1e-4: 2.516 and 3.208,
  0.323 and 0.773, 2.387 and 2.769 calibres);
- the crossflow centre of pressure of a slender body against Jorgensen's eq. (1), its
  two terms at their stations: the nose's slender-body lift at the nose's centre of
  pressure, the crossflow at the planform's centroid (NASA TR R-474, 1977);
- the rail exit of a constant-thrust, constant-mass rocket against
  ``v = sqrt(2 L (T/m - g sin theta))``, ``t = sqrt(2 L / (T/m - g sin theta))``, and
  the hobby rocket's against its flight's ``off_rail``;
- the peak axial load of a constant-thrust motor: at its burnout, ``T / m_burnout``;
- the warnings: one line each for a design that will break up, tumble, cannot steer or,
  leaving a site with no aero section, flies as in vacuum, from ``rocketsim validate`` and
  before ``rocketsim fly`` flies;
- each shipped stack's length from its base to the nose's tip against the sum of its
  parts' published lengths;
- the review's pure-Python centre of mass (what ``rocketsim validate`` computes without
  numpy) against the compiled mass model's, for every shipped staged vehicle, loaded and
  after each stage's burn (to 1e-12 relative).
"""

import math

import pytest

import rocketsim
from rocketsim.constants import G0
from rocketsim.vehicle.aero import NOSE_FIRST_CA, NOSE_FIRST_MACH
from rocketsim.vehicle.build import build
from rocketsim.constants import UNUSABLE_PROPELLANT
from rocketsim.vehicle.review import (centre_of_mass, crossflow_centre_of_pressure, rail_exit, review,
                                      stage_loads)
from tests.aero_vehicles import SLENDER, shipped, spec
from tests.conftest import ROOT


@pytest.mark.parametrize("name", ["hobby-rocket.yaml", "ndrt-2020.yaml", "bella-lui.yaml"])
def test_the_static_margin_is_rocketpys_for_the_same_rocket(name):
    pytest.importorskip("rocketpy")
    from tests.rocketpy_rockets import rocketpy_rocket
    vehicle = shipped(name)
    drag = list(zip(NOSE_FIRST_MACH.tolist(), NOSE_FIRST_CA.tolist()))
    rocket, motor = rocketpy_rocket(vehicle, drag)
    liftoff, burnout = review(vehicle).phases
    peer = (rocket.static_margin(0), rocket.static_margin(motor.burn_out_time))
    print(f"\n[margin] {name}: CP {liftoff.centre_of_pressure_m:.4f} m (RocketPy "
          f"{rocket.cp_position(0):.4f}); margin {liftoff.static_margin_cal:.4f} / "
          f"{burnout.static_margin_cal:.4f} cal at liftoff / burnout, RocketPy {peer[0]:.4f} / {peer[1]:.4f}")
    assert liftoff.static_margin_cal == pytest.approx(peer[0], abs=0.1)
    assert burnout.static_margin_cal == pytest.approx(peer[1], abs=0.1)


@pytest.mark.parametrize("scenario", ["hobby-rocket.yaml", "measured/ndrt-2020.yaml",
                                      "measured/bella-lui.yaml"])
def test_rocketsim_vehicle_prints_the_centre_of_pressure_and_static_margin(cli, scenario):
    result = cli("vehicle", ROOT / "scenarios" / scenario)
    assert result.exit_code == 0, result.output
    liftoff = rocketsim.review(ROOT / "scenarios" / scenario).phases[0]
    line = next(row for row in result.output.splitlines() if row.startswith("rocket liftoff"))
    assert f"{liftoff.centre_of_pressure_m:.3f}" in line and f"{liftoff.static_margin_cal:.2f}" in line
    assert "CP m" in result.output and "margin cal" in result.output and "off a " in result.output


@pytest.mark.parametrize("name", ["falcon9-block5.yaml", "electron.yaml", "starship-superheavy.yaml",
                                  "lander.yaml", "hobby-rocket.yaml", "ndrt-2020.yaml", "bella-lui.yaml"])
def test_the_reviews_centre_of_mass_is_the_mass_models(name):
    vehicle = shipped(name)
    for first in range(len(vehicle.stages)):
        model = build(vehicle, first=first)
        burnt_tanks = model.tank_load * [UNUSABLE_PROPELLANT if s == 0 and tank.feeds_engines else 1.0
                                         for s, st in enumerate(vehicle.stages[first:]) for tank in
                                         sorted(st.tanks, key=lambda t: not t.feeds_engines)]
        burnt_motors = [0.0 if s == 0 else m.propellant_mass
                        for s, st in enumerate(vehicle.stages[first:]) for m in st.motors]
        for burnt, tanks, motors in ((False, model.tank_load, None), (True, burnt_tanks, burnt_motors)):
            mass, x_cm = model.mass_properties(tanks, motors)[:2]
            assert centre_of_mass(vehicle, first, burnt) == pytest.approx((mass, x_cm), rel=1e-12)


def test_the_crossflow_centre_of_pressure_is_jorgensens():
    # The 10 m x 0.5 m body with its 2 m cone (tests/aero_vehicles.py) at 5 deg, Mach 0.5
    # (crossflow Mach 0.044: C_dc 1.2, eta 0.70 for fineness 20): Jorgensen's eq. (1) puts
    # the nose's (A_b/A_r) sin 2a cos(a/2) at the cone's 2/3 L from its tip and
    # eta C_dc (A_p/A_r) sin^2 a at the planform's centroid.
    model = build(spec(SLENDER))
    a = math.radians(5.0)
    area = math.pi * 0.25 ** 2
    nose = math.sin(2 * a) * math.cos(a / 2)
    cylinder, cone = 0.5 * 8.0, 0.5 * 0.5 * 2.0                  # planform areas, m^2
    centroid = (cylinder * 4.0 + cone * (8.0 + 2.0 / 3.0)) / (cylinder + cone)
    cross = 0.70 * 1.2 * (cylinder + cone) / area * math.sin(a) ** 2
    expected = (nose * (10.0 - 2.0 * 2.0 / 3.0) + cross * centroid) / (nose + cross)
    found = crossflow_centre_of_pressure(model.arrays.aero)
    print(f"\n[crossflow] centre of pressure {found:.3f} m, Jorgensen {expected:.3f} m")
    assert found == pytest.approx(expected, abs=0.1)


def _motor_rocket(thrust_points, propellant, total, limits=None):
    vehicle = {"name": "dart", "stages": [{"name": "dart", "length": "1.5 m", "diameter": "0.1 m",
                                           "structure_mass": "8 kg",
                                           "motors": [{"name": "M", "thrust": thrust_points,
                                                       "diameter": "75 mm", "length": "0.4 m",
                                                       "propellant_mass": f"{propellant} kg",
                                                       "total_mass": f"{total} kg"}]}],
               "aero": {"nose": {"length": "0.3 m", "shape": "ogive"},
                        "fins": [{"stage": "dart", "count": 4, "position": "0.2 m",
                                  "root_chord": "0.2 m", "tip_chord": "0.1 m", "span": "0.1 m"}]}}
    if limits is not None:
        vehicle["aero"]["limits"] = limits
    return spec(vehicle)


def test_the_rail_exit_of_a_constant_thrust_rocket_is_the_closed_form():
    # 1 kN from 1 ms on (the curve starts from nothing), 1 g of propellant on a 10 kg
    # rocket: constant mass to 1e-4; a 5 m rail at 80 deg, 0.2 m to its last button
    rocket = _motor_rocket([[0, 0], [0.001, 1000.0], [30.0, 1000.0]], 0.001, 2.0)
    mass = 10.0
    length, theta, button = 5.0, math.radians(80.0), 0.2
    accel = 1000.0 / mass - G0 * math.sin(theta)
    travel = length - button
    found = rail_exit(rocket, length, theta, button, G0)
    print(f"\n[rail] {found.surface_speed_m_s:.5f} m/s at {found.time_s:.5f} s, closed form "
          f"{math.sqrt(2 * travel * accel):.5f} m/s at {math.sqrt(2 * travel / accel):.5f} s")
    assert found.surface_speed_m_s == pytest.approx(math.sqrt(2 * travel * accel), rel=2e-4)
    assert found.time_s == pytest.approx(math.sqrt(2 * travel / accel), abs=1.5e-3)


def test_the_rail_exit_is_the_flights_off_rail():
    """The hobby rocket off its 5.2 m rail (scenarios/hobby-rocket.yaml): the review's exit
    (thrust alone) against the flight's ``off_rail`` event (its drag, the turning Earth,
    the integrator's steps cut at the exit): measured 29.093 against 29.082 m/s, both at
    T+0.3668 s."""
    path = ROOT / "scenarios" / "hobby-rocket.yaml"
    found = rocketsim.review(path).rail
    flown = rocketsim.fly(path, duration=1.0).events.set_index("name").loc["off_rail"]
    print(f"\n[rail] review {found.surface_speed_m_s:.3f} m/s at {found.time_s:.4f} s, flight "
          f"{flown['surface_speed_m_s']:.3f} m/s at {flown['at_s']:.4f} s")
    assert found.surface_speed_m_s == pytest.approx(flown["surface_speed_m_s"], rel=1e-3)
    assert found.time_s == pytest.approx(flown["at_s"], abs=1e-3)


def test_the_peak_axial_load_of_a_constant_thrust_motor_is_at_its_burnout():
    # 2 kN for 2 s (1 ms ramps) burning 1.5 kg in proportion to the impulse: the last
    # instant of full thrust has burnt all but the tail's share, I_tail / I_total
    points = [[0, 0], [0.001, 2000.0], [2.0, 2000.0], [2.001, 0.0]]
    rocket = _motor_rocket(points, 1.5, 3.0, {"axial_load": "40 g"})
    impulse = 2000.0 * (0.0005 + 1.999 + 0.0005)
    left = 1.5 * (2000.0 * 0.0005) / impulse
    mass = 8.0 + 1.5 + left                             # structure, case, the tail's propellant
    loads = stage_loads(rocket, 0)
    print(f"\n[axial] peak {loads.peak_axial_load_g:.6f} g at {loads.peak_at_s:.4f} s, "
          f"T / m_burnout {2000.0 / mass / G0:.6f} g")
    assert loads.peak_axial_load_g == pytest.approx(2000.0 / mass / G0, rel=1e-6)
    assert loads.least_peak_axial_load_g == loads.peak_axial_load_g     # a motor cannot throttle
    assert loads.peak_at_s == pytest.approx(2.0, abs=1e-6)


def finless_rocket(write, name: str, axial_limit: str):
    """A K1000T rocket without fins, ``name``.yaml: its nose's lift ahead of its centre of
    mass (unstable), 16.7 g at its motor's burnout, its structure's ``axial_limit``."""
    motor = ROOT / "motors" / "AeroTech_K1000T.eng"
    return write(f"{name}.yaml", f"""\
        name: {name}
        stages:
          - name: rocket
            length: 1.6 m
            diameter: 0.1 m
            structure_mass: 4.5 kg
            structure_centre: 0.4 m
            motors: [{{name: K1000T, file: {motor}}}]
        payload: {{name: nose cone, mass: 0.5 kg, length: 0.4 m, diameter: 0.1 m}}
        aero:
          nose: {{length: 0.4 m, shape: ogive}}
          limits: {{axial_load: {axial_limit}}}
        """)


def test_validate_warns_one_line_each_of_a_design_that_breaks_tumbles_or_cannot_steer(write, cli):
    fragile = finless_rocket(write, "fragile", "12 g")
    blind = write("blind.yaml", """\
        name: blind
        stages:
          - name: kick
            length: 2 m
            diameter: 1 m
            structure_mass: 100 kg
            tanks: [{name: T, propellant: MMH, density: 880 kg/m3, radius: 0.45 m, length: 1 m, position: 0.5 m}]
            engines: [{name: E, thrust_vacuum: 5 kN, isp_vacuum: 300 s, exit_area: 0.05 m2}]
        """)
    result = cli("validate", ROOT / "vehicles" / "hobby-rocket.yaml", fragile, blind)
    assert result.exit_code == 0, result.output
    warnings = [line for line in result.output.splitlines() if line.startswith("warning:")]
    print("\n" + "\n".join(warnings))
    assert len(warnings) == 3
    assert "fragile.yaml: will break up: the burn of stage 'rocket' pushes the stack at 16.7 g" in warnings[0]
    assert "12 g axial limit (the file's aero.limits)" in warnings[0]
    assert "fragile.yaml: will tumble: static margin -1" in warnings[1]
    assert "blind.yaml: cannot steer: stage 'kick' burns liquid engines" in warnings[2]


def test_fly_prints_the_warnings_before_it_flies(write, cli, tmp_path):
    """A finless rocket (its nose's lift alone, ahead of its centre of mass; its own axial
    limit, so that only the tumble is warned of) is warned of on a line ``rocketsim fly``
    prints before the flight's summary; the flight still flies (a warning, not a refusal)."""
    finless_rocket(write, "finless", "40 g")
    hobby = (ROOT / "scenarios" / "hobby-rocket.yaml").read_text()
    flown = write("finless-flight.yaml", hobby.replace("../vehicles/hobby-rocket.yaml", "finless.yaml"))
    result = cli("fly", flown, "-o", tmp_path / "run.mcap", "--duration", "0.1s")
    assert result.exit_code == 0, result.output
    lines = result.output.splitlines()
    warned = [k for k, line in enumerate(lines) if line.startswith("warning:")]
    print("\n" + "\n".join(lines[k] for k in warned))
    assert len(warned) == 1 and "finless-flight.yaml: will tumble: static margin -" in lines[warned[0]]
    assert warned[0] < next(k for k, line in enumerate(lines) if line.startswith("telemetry:"))


def test_a_vehicle_leaving_a_site_without_aero_is_warned_it_flies_as_in_vacuum(write, cli):
    """The hobby rocket's scenario flying its vehicle without the aero section: one
    warning line; with ``aero: {aerodynamics: false}`` (vacuum on purpose) none."""
    hobby = (ROOT / "scenarios" / "hobby-rocket.yaml").read_text()
    vehicle = (ROOT / "vehicles" / "hobby-rocket.yaml").read_text().replace("../motors/", f"{ROOT}/motors/")
    bare = vehicle[:vehicle.index("\naero:")] + "\n"
    flights = []
    for name, text in (("bare", bare), ("vacuum", bare + "aero: {aerodynamics: false}\n")):
        write(f"{name}.yaml", text)
        flights.append(write(f"{name}-flight.yaml", hobby.replace("../vehicles/hobby-rocket.yaml", f"{name}.yaml")))
    result = cli("validate", *flights)
    assert result.exit_code == 0, result.output
    warnings = [line for line in result.output.splitlines() if line.startswith("warning:")]
    print("\n" + "\n".join(warnings))
    assert len(warnings) == 1
    assert "bare-flight.yaml: flies as in vacuum: the vehicle has no aero section" in warnings[0]


# Each shipped vehicle's length from its base to the nose's tip, as the review finds it,
# against the published lengths of its parts:
# - Falcon 9 Block 5: first stage 41.2 m, second stage 13.8 m, fairing 13.1 m (SpaceX's
#   Falcon User's Guide as Wikipedia "Falcon 9 Block 5" quotes them); overall 69.8 m there
# - Electron: first stage 12.1 m, second stage 2.4 m, fairing 2.5 m, 17 m tall (Space Launch
#   Report, "Electron"); Rocket Lab's vehicle page gives 18 m overall
# - Starship: Super Heavy 71 m, Starship 50 m (its payload section 17 m with the nose), 121 m
#   (SpaceX's Starship page)
# - Notre Dame 2020 and Bella Lui: RocketPy's acceptance stations, the base below the
#   centre of mass without motor (1.321656 m, 1.1356 m), the nose's base above it
#   (0.71971 m, 1.3 m), the nose (0.610 m, 0.242 m)
PUBLISHED_LENGTHS = [("falcon9-block5.yaml", (41.2, 13.8, 13.1), 69.8),
                     ("electron.yaml", (12.1, 2.4, 2.5), 18.0),
                     ("starship-superheavy.yaml", (71.0, 50.0), 121.0),
                     ("ndrt-2020.yaml", (1.321656, 0.71971, 0.610), None),
                     ("bella-lui.yaml", (1.1356, 1.3, 0.242), None)]


@pytest.mark.parametrize("name, parts, overall", PUBLISHED_LENGTHS)
def test_each_shipped_stack_is_as_long_as_its_published_parts(name, parts, overall):
    """The nose inside the part it caps, no part counted twice or left out: the stack is
    the sum of its parts' published lengths. Where a published overall height differs
    from that sum (Falcon 9 1.7 m, Electron 1 m), the difference is printed, not flown:
    which part spans it is not published (docs/physics.md#the-stack-and-its-nose)."""
    found = review(shipped(name))
    if overall is not None:
        print(f"\n[length] {name}: {found.length_m:.3f} m, published overall {overall:g} m "
              f"({found.length_m - overall:+.2f} m)")
    assert found.length_m == pytest.approx(sum(parts), abs=1e-9)


def test_the_geometry_figure_draws_from_the_shipped_files(tmp_path):
    """docs/vehicle-geometry.png's script (docs/vehicle_geometry.py) draws the shipped
    Notre Dame and Electron files with the review's centres of mass and pressure."""
    import importlib.util
    found = importlib.util.spec_from_file_location("vehicle_geometry", ROOT / "docs" / "vehicle_geometry.py")
    module = importlib.util.module_from_spec(found)
    found.loader.exec_module(module)
    module.main(tmp_path / "geometry.png")
    assert (tmp_path / "geometry.png").stat().st_size > 10_000
