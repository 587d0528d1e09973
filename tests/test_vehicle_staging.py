"""A separated stage is a complete vehicle of its own (issue 4, "staging as data").

References: the centre of mass and the momentum of a system are the mass-weighted
sums of its parts' (Newton; no impulse at separation), and each part's mass
properties equal those of the part built alone from the file."""

from pathlib import Path

import numpy as np
import pytest

from rocketsim.constants import EARTH_RADIUS_EQ
from rocketsim.frames.quaternion import quat_from_axis_angle, quat_rotate
from rocketsim.scenario.load import validate
from rocketsim.scenario.models import VehicleSpec
from rocketsim.scenario.yaml_source import read_yaml
from rocketsim.vehicle import engines as E
from rocketsim.vehicle.build import build
from rocketsim.vehicle.staging import jettison_fairing, separate

F9 = Path(__file__).resolve().parents[1] / "vehicles" / "falcon9-block5.yaml"


def test_separation_conserves_centre_of_mass_and_momentum():
    spec = validate(read_yaml(F9), VehicleSpec)
    whole = build(spec)
    q = quat_from_axis_angle(np.array([0.3, -0.5, 0.8]) / np.linalg.norm([0.3, -0.5, 0.8]), 1.1)
    y = whole.state([EARTH_RADIUS_EQ + 80e3, 1e4, -2e3], [1500.0, 2200.0, 300.0], q, (0.01, 0.03, -0.02))
    y[whole.tanks] *= 0.1                                     # booster near the end of its burn
    y[whole.tanks][2:] = whole.tank_load[2:]
    whole.arrays.stage[0, E.S_DRY] = 1.0
    (lower, y_l), (upper, y_u) = separate(spec, whole, y, 1)
    m, m_l, m_u = (x.mass_properties(yy)[0] for x, yy in ((whole, y), (lower, y_l), (upper, y_u)))
    assert m_l + m_u == pytest.approx(m, rel=1e-14)
    assert np.allclose((m_l * y_l[:3] + m_u * y_u[:3]) / m, y[:3], rtol=0, atol=1e-8)
    assert np.allclose((m_l * y_l[3:6] + m_u * y_u[3:6]) / m, y[3:6], rtol=0, atol=1e-10)
    # the upper part's centre of mass lies ahead of the stack's along the nose (body +x)
    nose = quat_rotate(q, np.array([1.0, 0.0, 0.0]))
    assert np.dot(y_u[:3] - y[:3], nose) > 10.0 and np.dot(y_l[:3] - y[:3], nose) < 0.0
    # each part is the vehicle its file describes
    assert lower.n_engines == 9 and upper.n_engines == 1
    assert np.allclose(upper.mass_properties(y_u), build(spec, 1).mass_properties(whole.tank_load[2:]),
                       rtol=1e-14)
    assert lower.arrays.stage[0, E.S_DRY] == 1.0 and upper.arrays.stage[0, E.S_DRY] == 0.0
    assert np.array_equal(y_u[upper.tanks], whole.tank_load[2:])


def test_fairing_jettison_conserves_centre_of_mass_and_momentum():
    spec = validate(read_yaml(F9), VehicleSpec)
    whole = build(spec)
    (_, _), (upper, y_u) = separate(spec, whole, whole.state([EARTH_RADIUS_EQ + 110e3, 0.0, 0.0],
                                                             [0.0, 2500.0, 800.0], w=(0.0, 0.02, 0.0)), 1)
    (bare, y_b), fairing = jettison_fairing(spec, upper, y_u, 1)
    m, m_b = upper.mass_properties(y_u)[0], bare.mass_properties(y_b)[0]
    assert m - m_b == pytest.approx(1900.0, rel=1e-12) and fairing["mass"] == 1900.0
    assert np.allclose((m_b * y_b[:3] + 1900.0 * fairing["position"]) / m, y_u[:3], rtol=0, atol=1e-8)
    assert np.allclose((m_b * y_b[3:6] + 1900.0 * fairing["velocity"]) / m, y_u[3:6], rtol=0, atol=1e-10)
    # thin shell, r = 2.6 m, L = 13.1 m: Ixx = m r^2, Iyy = m (r^2/2 + L^2/12)
    assert fairing["inertia"] == pytest.approx((1900 * 2.6 ** 2, 1900 * (2.6 ** 2 / 2 + 13.1 ** 2 / 12),
                                                1900 * (2.6 ** 2 / 2 + 13.1 ** 2 / 12)), rel=1e-14)
    assert not bare.has_fairing and bare.length == pytest.approx(13.8 + 6.0)
    with pytest.raises(ValueError):
        jettison_fairing(spec, bare, y_b, 1)
