"""A separated stage is a complete vehicle of its own (staging as data).

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
from rocketsim.vehicle.engines import S_DRY
from rocketsim.vehicle.build import build
from rocketsim.vehicle.staging import jettison_fairing, separate

F9 = Path(__file__).resolve().parents[3] / "vehicles" / "falcon9-block5.yaml"


def test_separation_conserves_centre_of_mass_and_momentum():
    spec = validate(read_yaml(F9), VehicleSpec)
    whole = build(spec)
    q = quat_from_axis_angle(np.array([0.3, -0.5, 0.8]) / np.linalg.norm([0.3, -0.5, 0.8]), 1.1)
    y = whole.state([EARTH_RADIUS_EQ + 80e3, 1e4, -2e3], [1500.0, 2200.0, 300.0], q, (0.01, 0.03, -0.02))
    y[whole.tanks] *= 0.1                                     # booster near the end of its burn
    y[whole.tanks][2:] = whole.tank_load[2:]
    whole.arrays.stage[0, S_DRY] = 1.0
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
    assert lower.arrays.stage[0, S_DRY] == 1.0 and upper.arrays.stage[0, S_DRY] == 0.0
    assert np.array_equal(y_u[upper.tanks], whole.tank_load[2:])


def test_fairing_halves_conserve_centre_of_mass_and_momentum():
    """The fairing opens into two halves pushed apart along body +/-y at half the
    separation speed (2 m/s apart by default): stack + halves keep the centre of mass
    and momentum of the stack before (to rounding), and the halves' centres lie
    2 R / pi off the axis (the centroid of a half circle's arc)."""
    spec = validate(read_yaml(F9), VehicleSpec)
    whole = build(spec)
    q = quat_from_axis_angle(np.array([0.3, -0.5, 0.8]) / np.linalg.norm([0.3, -0.5, 0.8]), 1.1)
    (_, _), (upper, y_u) = separate(spec, whole, whole.state([EARTH_RADIUS_EQ + 110e3, 0.0, 0.0],
                                                             [0.0, 2500.0, 800.0], q, w=(0.01, 0.02, -0.03)), 1)
    (bare, y_b), (one, two) = jettison_fairing(spec, upper, y_u, 1)
    m, m_b = upper.mass_properties(y_u)[0], bare.mass_properties(y_b)[0]
    assert m - m_b == pytest.approx(1900.0, rel=1e-12) and one["mass"] == two["mass"] == 950.0
    centre = (m_b * y_b[:3] + 950.0 * one["position"] + 950.0 * two["position"]) / m
    momentum = m_b * y_b[3:6] + 950.0 * one["velocity"] + 950.0 * two["velocity"]
    assert np.allclose(centre, y_u[:3], rtol=0, atol=1e-8)
    assert np.allclose(momentum / m, y_u[3:6], rtol=0, atol=1e-10)
    side = quat_rotate(q, np.array([0.0, 1.0, 0.0]))
    assert np.dot(one["position"] - two["position"], side) == pytest.approx(4 * 2.6 / np.pi, abs=1e-8)
    # relative speed along body y: the push (2 m/s) plus the turn of the offset (w_x, w_z)
    turn = np.cross([0.01, 0.02, -0.03], [0.0, 4 * 2.6 / np.pi, 0.0])
    assert np.allclose(one["velocity"] - two["velocity"], quat_rotate(q, turn + [0.0, 2.0, 0.0]),
                       rtol=0, atol=1e-9)
    assert not bare.has_fairing and bare.length == pytest.approx(13.8 + 6.0)
    with pytest.raises(ValueError):
        jettison_fairing(spec, bare, y_b, 1)


def test_half_shell_inertia_against_quadrature():
    """The inertia of a half cylindrical shell about its own centre against a direct
    midpoint quadrature of the integrals sum m_i (y^2 + z^2) etc. over 2 000 x 400
    area elements of the half shell (the reference: the definition, not the
    parallel-axis formulas), and a cylinder's mean projected area (surface / 4, Cauchy)
    against the average of its projections over all directions."""
    from rocketsim.vehicle.staging import half_shell
    from rocketsim.vehicle.tumbling import cylinder_area
    mass, radius, length = 950.0, 2.6, 13.1
    phi = (np.arange(2000) + 0.5) / 2000 * np.pi - np.pi / 2     # the +y half: y = R cos(phi)
    x = ((np.arange(400) + 0.5) / 400 - 0.5) * length
    yy, zz = radius * np.cos(phi)[:, None], radius * np.sin(phi)[:, None]
    xx = x[None, :]
    dm = mass / (2000 * 400)
    yc = np.sum(yy * np.ones_like(xx)) * dm / mass
    (ixx, iyy, izz), d = half_shell(mass, radius, length)
    assert d == pytest.approx(yc, rel=1e-6)
    ones = np.ones((2000, 400))
    assert ixx == pytest.approx(dm * np.sum((yy - yc) ** 2 * ones + zz ** 2 * ones), rel=1e-5)
    assert iyy == pytest.approx(dm * np.sum(xx ** 2 * ones + zz ** 2 * ones), rel=1e-5)
    assert izz == pytest.approx(dm * np.sum(xx ** 2 * ones + (yy - yc) ** 2 * ones), rel=1e-5)
    # Cauchy: mean projected area of a convex body = surface / 4. Reference for the closed
    # cylinder: its projection seen at theta from the axis, pi R^2 |cos| + 2 R L sin, averaged
    # over the sphere of directions (sin theta dtheta / 2) by quadrature
    theta = (np.arange(20000) + 0.5) / 20000 * np.pi
    seen = np.pi * 2.0 ** 2 * np.abs(np.cos(theta)) + 2 * 2.0 * 6.0 * np.sin(theta)
    assert cylinder_area(2.0, 6.0) == pytest.approx(np.sum(seen * np.sin(theta)) * np.pi / 20000 / 2, rel=1e-7)
