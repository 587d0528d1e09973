"""Solid motors: thrust curves from RASP files, the impulse law of the propellant, the grain.

References, each independent of the code under test:

* the header of motors/Cesaroni_4895L1395-P.eng (thrustcurve.org's file), read
  here with plain string splitting;
* the motor's designation: "4895" is its total impulse in N s (the leading
  number of a Cesaroni designation), the trapezoid of the file's points within 1 %;
* the impulse law ``m(t) = m0 (1 - I(t)/I_total)`` with ``I(t)`` the exact
  integral of the piecewise-linear curve, written out here;
* a hollow cylinder's (BATES segment's) mass and inertia, by the textbook
  formulas segment by segment with the parallel-axis theorem.

The flights here are 4 s burns at the 20 ms step, stepped with the kernel
alone (no world): enough to cover the whole curve.
"""

import math
from pathlib import Path

import numpy as np
import pytest

from rocketsim.constants import EARTH_RADIUS_EQ
from rocketsim.dynamics.rk4 import step
from rocketsim.errors import InputError
from rocketsim.scenario.load import validate
from rocketsim.scenario.models import VehicleSpec
from rocketsim.scenario.motor_file import read_thrust_curve
from rocketsim.scenario.yaml_source import read_yaml
from rocketsim.vehicle.build import build
from rocketsim.vehicle.mass_properties import shell
from tests.aero_vehicles import earth_params, spec

ROOT = Path(__file__).resolve().parents[3]
L1395 = ROOT / "motors" / "Cesaroni_4895L1395-P.eng"
GRAIN = {"count": 5, "outer_diameter": "66 mm", "core_diameter": "30 mm", "length": "120 mm",
         "separation": "3 mm"}       # the 4895L1395's five BATES grains (RocketPy's NDRT 2020 figures)


def rocket(**motor) -> dict:
    return {"name": "motor test", "stages": [{
        "name": "sustainer", "length": "2 m", "diameter": "0.1 m", "structure_mass": "8 kg",
        "motors": [{"name": "L1395", "file": str(L1395), "position": "0.1 m", **motor}]}]}


def raw_file():
    """The file's header fields and points, read with plain string handling."""
    lines = [line.split() for line in L1395.read_text().splitlines()
             if line.strip() and not line.startswith(";")]
    return lines[0], np.array([[float(a), float(b)] for a, b in lines[1:]])


def test_the_header_figures_are_read_exactly():
    header, _ = raw_file()
    motor = spec(rocket()).stages[0].motors[0]
    assert header[:6] == ["L1395-BS", "75", "621", "0", "2.475", "4.323"]
    assert motor.diameter == 0.075 and motor.length == 0.621
    assert motor.propellant_mass == 2.475 and motor.total_mass == 4.323
    assert motor.case_mass == pytest.approx(4.323 - 2.475, abs=1e-15)
    model = build(spec(rocket()))
    # structure 8 kg + the loaded motor 4.323 kg
    assert model.mass_properties(model.state([0, 0, 0], [0, 0, 0]))[0] == pytest.approx(12.323, abs=1e-12)


def test_the_total_impulse_is_the_designation_within_one_percent():
    _, points = raw_file()
    t = np.concatenate(([0.0], points[:, 0]))       # RASP: the curve starts from no thrust at 0
    f = np.concatenate(([0.0], points[:, 1]))
    trapezoid = float(np.sum(0.5 * (f[1:] + f[:-1]) * np.diff(t)))
    motor = spec(rocket()).stages[0].motors[0]
    print(f"\n[motor] 4895L1395: trapezoid {trapezoid:.2f} N s, model {motor.total_impulse:.2f} N s")
    assert motor.total_impulse == pytest.approx(trapezoid, rel=1e-12)
    assert trapezoid == pytest.approx(4895.0, rel=0.01)


def impulse_to(points: np.ndarray, c: float) -> float:
    """Exact integral (N s) of the linear interpolation of ``points`` from 0 to ``c`` s."""
    total = 0.0
    for (t0, f0), (t1, f1) in zip(points[:-1], points[1:]):
        if c <= t0:
            break
        dt = min(c, t1) - t0
        total += f0 * dt + 0.5 * (f1 - f0) / (t1 - t0) * dt * dt
    return total


def test_propellant_burns_in_proportion_to_the_impulse_delivered():
    model = build(spec(rocket(ignition="0.3 s")))
    a = model.arrays
    r = np.array([EARTH_RADIUS_EQ + 100e3, 0.0, 0.0])       # above the air: the motor alone
    y = model.state(r, [0.0, 7000.0, 0.0], q=(1.0, 0.0, 0.0, 0.0))
    _, points = raw_file()
    points = np.vstack(([0.0, 0.0], points))
    total = impulse_to(points, 10.0)
    p = earth_params()
    worst = 0.0
    for k in range(200):
        y = step(y, 0.02 * k, 0.02, p, a)
        c = 0.02 * (k + 1) - 0.3
        expected = 2.475 * (1.0 - impulse_to(points, max(c, 0.0)) / total)
        worst = max(worst, abs(y[model.motors][0] - expected))
    print(f"\n[motor] propellant against m0 (1 - I/I_total): worst {worst:.2e} kg")
    assert worst < 1e-11
    assert abs(y[model.motors][0]) < 1e-11          # burnt out: none left


def test_the_burn_is_bit_identical_in_one_batch_and_one_step_at_a_time():
    from rocketsim.dynamics.rk4 import advance
    model = build(spec(rocket(ignition="0.01 s")))
    r = np.array([EARTH_RADIUS_EQ + 100e3, 0.0, 0.0])
    y0 = model.state(r, [0.0, 7000.0, 0.0])
    y1, _ = advance(y0.copy(), 0, 0.02, 100, earth_params(), model.arrays)
    y2 = y0.copy()
    for k in range(100):
        y2 = step(y2, 0.02 * k, 0.02, earth_params(), model.arrays)
    assert np.array_equal(y1, y2)


def test_mass_centre_and_inertia_follow_the_hollow_grain():
    model = build(spec(rocket(grain=GRAIN)))
    n, outer, core, length, gap = 5, 0.033, 0.015, 0.120, 0.003
    density = 2.475 / (n * math.pi * (outer ** 2 - core ** 2) * length)
    centre = 0.1 + 0.5 * 0.621
    structure = (8.0, 1.0, *shell(8.0, 0.05, 2.0))           # mass, station, own Ixx, Iyy
    case = (4.323 - 2.475, centre, *shell(4.323 - 2.475, 0.0375, 0.621))
    for burnt in (0.0, 0.3, 0.7, 0.999):
        m = 2.475 * (1.0 - burnt)
        r_core2 = outer ** 2 - m / (n * density * math.pi * length)    # the core widened
        parts = [structure, case]
        for i in range(n):
            mi = m / n
            zi = centre + (i - (n - 1) / 2) * (length + gap)
            parts.append((mi, zi, mi * (outer ** 2 + r_core2) / 2,
                          mi * (3 * (outer ** 2 + r_core2) + length ** 2) / 12))
        mass = sum(p[0] for p in parts)
        x_cm = sum(p[0] * p[1] for p in parts) / mass
        ixx = sum(p[2] for p in parts)
        iyy = sum(p[3] + p[0] * (p[1] - x_cm) ** 2 for p in parts)
        got = model.mass_properties([], motors=[m])
        assert got[0] == pytest.approx(mass, rel=1e-13)
        assert got[1] == pytest.approx(x_cm, rel=1e-13)
        assert got[2] == pytest.approx(ixx, rel=1e-12)
        assert got[3] == pytest.approx(iyy, rel=1e-12) and got[4] == got[3]


def test_without_a_grain_the_propellant_is_a_uniform_cylinder_of_the_motor():
    model = build(spec(rocket()))
    empty = model.mass_properties([], motors=[0.0])
    full = model.mass_properties([], motors=[2.475])
    centre, radius, length, m = 0.1 + 0.3105, 0.0375, 0.621, 2.475
    # adding the propellant adds a solid cylinder at the motor's centre (parallel axes)
    mass = empty[0] + m
    x_cm = (empty[0] * empty[1] + m * centre) / mass
    iyy = (empty[3] + empty[0] * (empty[1] - x_cm) ** 2
           + m * (3 * radius ** 2 + length ** 2) / 12 + m * (centre - x_cm) ** 2)
    assert full[0] == pytest.approx(mass, rel=1e-14)
    assert full[1] == pytest.approx(x_cm, rel=1e-14)
    assert full[2] == pytest.approx(empty[2] + m * radius ** 2 / 2, rel=1e-13)
    assert full[3] == pytest.approx(iyy, rel=1e-12)


def test_a_csv_curve_and_an_inline_curve_fly_the_same_points(tmp_path):
    csv = tmp_path / "motor.csv"
    csv.write_text("time,thrust\n0.5,100\n1.5,100\n2.0,0\n")
    assert read_thrust_curve(csv).points == ((0.0, 0.0), (0.5, 100.0), (1.5, 100.0), (2.0, 0.0))
    figures = {"diameter": "50 mm", "length": "0.3 m", "propellant_mass": "0.1 kg", "total_mass": "0.3 kg"}
    from_csv = spec({"name": "x", "stages": [{"name": "s", "length": "1 m", "diameter": "0.1 m",
                                             "structure_mass": "1 kg", "motors": [
                                                 {"name": "m", "file": str(csv), **figures}]}]})
    inline = spec({"name": "x", "stages": [{"name": "s", "length": "1 m", "diameter": "0.1 m",
                                           "structure_mass": "1 kg", "motors": [
                                               {"name": "m", "thrust": [[0.5, 100], [1.5, 100], [2.0, 0]],
                                                **figures}]}]})
    assert from_csv.stages[0].motors[0].thrust == inline.stages[0].motors[0].thrust
    assert inline.stages[0].motors[0].total_impulse == pytest.approx(25 + 100 + 25)


@pytest.mark.parametrize("text, message", [
    ("L1395 75 621 0 2.475\n0.1 100\n", "needs 7 fields"),
    ("L1395 75 621 0 4.5 4.3 CTI\n0.1 100\n", "less than the total mass"),
    ("L1395 75 621 0 2.4 4.3 CTI\n0.1 100\n0.05 50\n", "increase"),
    ("L1395 75 621 0 2.4 4.3 CTI\n0.1 x\n", "thrust_N is not a number"),
])
def test_a_bad_motor_file_is_an_input_error_naming_its_line(tmp_path, text, message):
    bad = tmp_path / "bad.eng"
    bad.write_text("; a comment\n" + text)
    vehicle = tmp_path / "vehicle.yaml"
    vehicle.write_text("name: x\nstages:\n  - name: s\n    length: 1 m\n    diameter: 0.1 m\n"
                       "    structure_mass: 1 kg\n    motors:\n      - name: m\n        file: bad.eng\n")
    with pytest.raises(InputError) as error:
        validate(read_yaml(vehicle), VehicleSpec)
    assert message in str(error.value) and "bad.eng, line" in str(error.value)
    assert error.value.line == 9 and error.value.field == "stages.0.motors.0.file"
