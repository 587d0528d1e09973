"""Mass properties of a staged vehicle against a hand calculation (docs/physics.md#mass-properties).

The reference is worked here, part by part, in exact rational arithmetic
(``fractions.Fraction``) and directly about the centre of mass (the kernel
sums about the base and shifts once), from the textbook formulas:
thin cylindrical shell ``Ixx = m r^2``, ``Iyy = m (r^2/2 + L^2/12)``; solid
cylinder ``Ixx = m r^2/2``, ``Iyy = m (3 r^2 + L^2)/12`` (e.g. Beer &
Johnston, Vector Mechanics, inside back cover); point masses ``m d^2``; only
10 % of a liquid column's own roll inertia (docs/physics.md#mass-properties).
"""

from fractions import Fraction as F

import numpy as np
import pytest

from rocketsim.vehicle.build import build
from tests.vehicle_specs import ENGINE, single_stage, spec

RTOL = 1e-12


def hand_stack(propellant):
    """Structure shell (1000 kg, r 1, L 10, centre 5), tank wall shell (200 kg, r 1, L 6,
    centre 4), settled column (1000 kg/m, r 1, from x = 1), engine 100 kg at x = 0.5,
    four 50 kg legs on a 2 m ring at x = 1, payload cylinder 300 kg (r 0.5, L 2) on top."""
    m_p = F(propellant)
    h = m_p / 1000
    # (mass, x, own Ixx, own Iyy, sum m z^2 (adds to Iyy), sum m y^2 (adds to Izz), sum m (y^2+z^2))
    parts = [
        (F(1000), F(5), F(1000), 1000 * (F(1, 2) + F(100, 12)), 0, 0, 0),       # structure
        (F(200), F(4), F(200), 200 * (F(1, 2) + F(36, 12)), 0, 0, 0),           # tank wall
        (m_p, 1 + h / 2, F(1, 10) * m_p / 2, m_p * (3 + h * h) / 12, 0, 0, 0),  # propellant
        (F(100), F(1, 2), 0, 0, 0, 0, 0),                                       # engine
        (F(200), F(1), 0, 0, F(50 * 8), F(50 * 8), F(200 * 4)),                 # legs at 0/90/180/270 deg
        (F(300), F(11), F(300, 8), 300 * (F(3, 4) + 4) / 12, 0, 0, 0),          # payload
    ]
    mass = sum(p[0] for p in parts)
    x_cm = sum(p[0] * p[1] for p in parts) / mass
    ixx = sum(p[2] + p[6] for p in parts)
    iyy = sum(p[3] + p[0] * (p[1] - x_cm) ** 2 + p[4] for p in parts)
    izz = sum(p[3] + p[0] * (p[1] - x_cm) ** 2 + p[5] for p in parts)
    return [float(v) for v in (mass, x_cm, ixx, iyy, izz)]


def model():
    data = single_stage(point_masses=[{"name": "legs", "mass": "50 kg", "count": 4, "radius": "2 m",
                                       "position": "1 m"}],
                        engines=[{**ENGINE, "position": "0.5 m"}])
    data["payload"] = {"mass": "300 kg", "length": "2 m", "diameter": "1 m"}
    return build(spec(data))


@pytest.mark.parametrize("propellant", [6000.0, 3000.0, 1234.5, 1e-3])
def test_shell_cylinder_point_mass_stack_matches_hand_calculation(propellant):
    got = model().mass_properties(np.array([propellant]))
    assert np.allclose(got, hand_stack(propellant), rtol=RTOL, atol=0.0)


def test_full_tank_by_default_and_dry_mass():
    m = model()
    assert m.tank_load[0] == pytest.approx(6000.0, rel=1e-15)     # 6 m of 1000 kg/m
    assert m.stage_dry_mass[0] == 1000 + 200 + 100 + 200          # structure, wall, engine, legs


def test_separated_stage_is_a_vehicle_of_its_own():
    """Two identical stages stacked: the upper one built alone has the hand-calculated
    properties of the one-stage stack (payload on top), measured from its own base."""
    data = single_stage(point_masses=[{"name": "legs", "mass": "50 kg", "count": 4, "radius": "2 m",
                                       "position": "1 m"}],
                        engines=[{**ENGINE, "position": "0.5 m"}])
    data["stages"] = [dict(data["stages"][0], name="lower"), dict(data["stages"][0], name="upper")]
    data["payload"] = {"mass": "300 kg", "length": "2 m", "diameter": "1 m"}
    upper = build(spec(data), first=1)
    assert np.allclose(upper.mass_properties(np.array([2500.0])), hand_stack(2500.0), rtol=RTOL)
    whole = build(spec(data))
    lower = build(spec(data), last=0)
    assert whole.n_engines == 2 and lower.n_engines == 1 and upper.n_engines == 1
    # the spent lower stage: no payload; mass = its dry mass + what is left in its tank
    assert lower.mass_properties(np.array([60.0]))[0] == pytest.approx(1500.0 + 60.0, rel=1e-15)
