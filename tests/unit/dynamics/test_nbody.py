"""The n-body field against hand-computed fields, and the sphere-of-influence handover.

References: the direct-minus-indirect field (docs/physics.md#n-body-field) evaluated by hand
(closed form for a collinear case; an independent heliocentric numpy sum over
the ephemeris, ``tests/nbody_reference.py``); radiation pressure from the
solar irradiance over c (Kopp & Lean 2011); SOI radii from Curtis, *Orbital
Mechanics for Engineering Students*, Table 8.1 (Earth 925 000 km, Moon
66 100 km, Mars 577 000 km).
"""

import datetime as dt
import math

import numpy as np
import pytest

from rocketsim.bodies.orientation import pole, spin_rate
from rocketsim.constants import (AU, EARTH_J2, EARTH_MU, EARTH_RADIUS_EQ, EARTH_RADIUS_POLAR,
                                 MOON_J2, MOON_MU, MOON_RADIUS, SUN_MU)
from rocketsim.dynamics import nbody, soi
from rocketsim.layout import make_params
from rocketsim.ephemeris.solar_system import states
from rocketsim.timescales import Epoch
from tests.nbody_reference import field_j2000

JD0 = Epoch.from_utc(dt.datetime(2026, 11, 26, 12, tzinfo=dt.timezone.utc)).jd_tt()
EARTH_P = make_params(1.0, (1.0, 1.0, 1.0), EARTH_MU, EARTH_RADIUS_EQ, EARTH_J2, EARTH_RADIUS_POLAR)
MOON_P = make_params(1.0, (1.0, 1.0, 1.0), MOON_MU, MOON_RADIUS, MOON_J2, MOON_RADIUS,
                     spin=spin_rate("moon"))     # the IAU W rate: the Moon's ground turns at it


def test_collinear_sun_tide_matches_the_closed_form():
    # Sun at 1 AU on +x from Earth, vehicle at r on +x: direct minus indirect is
    # mu [1/(AU - r)^2 - 1/AU^2] = mu r (2 AU - r) / (AU^2 (AU - r)^2), written without cancellation
    fp = nbody.make_field("earth", JD0, bodies=("sun",))
    s = np.zeros((4, 3))
    s[0] = (AU, 0.0, 0.0)
    r = 7.0e6
    ax, ay, az = nbody.perturbation(r, 0.0, 0.0, s, fp)
    expected = SUN_MU * r * (2 * AU - r) / (AU ** 2 * (AU - r) ** 2)
    assert ax == pytest.approx(expected, abs=1e-12)          # +5.5e-7 m/s^2, towards the Sun
    assert expected > 5e-7 and ay == 0.0 and az == 0.0
    # on the far side the tide also points away from Earth (the indirect term's sign decides it)
    ax_far, _, _ = nbody.perturbation(-r, 0.0, 0.0, s, fp)
    assert ax_far == pytest.approx(-SUN_MU * r * (2 * AU + r) / (AU ** 2 * (AU + r) ** 2), abs=1e-12)


@pytest.mark.parametrize("offset", [(6.0e7, 1.0e7, -2.0e6), (2.0e6, 0.0, 0.0), (-3.0e7, 4.0e7, 1.0e7)])
def test_field_about_the_moon_matches_a_heliocentric_hand_sum(offset):
    t = 3600.0
    jd = JD0 + t / 86400.0
    rot = soi.frame_rotation("moon", JD0)
    fp = nbody.make_field("moon", JD0, rotation=rot, bodies=("sun", "earth", "mars"))
    got = nbody.field(np.array(offset), t, fp, MOON_P, held=False)
    expected = field_j2000(np.array(offset), jd, "moon", rot, ("sun", "earth", "mars"),
                           (MOON_MU, MOON_RADIUS, MOON_J2))
    np.testing.assert_allclose(got, expected, rtol=0, atol=1e-12)
    # within the Moon's sphere the others add a tide, not a second Earth: near the sphere's
    # edge (61 000 km) it is under half the Moon's pull (a wrong indirect sign gave +601 %)
    central = nbody.field(np.array(offset), t, nbody.make_field("moon", JD0, rot, ()), MOON_P,
                          held=False)
    if np.linalg.norm(offset) > 5e7:
        assert np.linalg.norm(got - central) < 0.5 * np.linalg.norm(central)


def test_field_about_earth_in_the_mission_eci_matches_the_hand_sum():
    gmst0 = 1.234
    rot = soi.frame_rotation("earth", JD0, gmst0)
    fp = nbody.make_field("earth", JD0, rotation=rot)
    r = np.array([-2.0e8, 1.5e8, 3.0e7])
    got = nbody.field(r, 100.0, fp, EARTH_P, held=False)
    expected = field_j2000(r, JD0 + 100.0 / 86400.0, "earth", rot, ("sun", "moon", "mars"),
                           (EARTH_MU, EARTH_RADIUS_EQ, EARTH_J2))
    np.testing.assert_allclose(got, expected, rtol=0, atol=1e-12)


def test_other_bodies_are_held_per_five_seconds_of_mission_time():
    fp = nbody.make_field("moon", JD0, rotation=soi.frame_rotation("moon", JD0))
    r = np.array([3.0e6, 1.0e6, 0.0])
    held = nbody.field(r, 7.3, fp, MOON_P)
    np.testing.assert_array_equal(held, nbody.field(r, 5.0, fp, MOON_P, held=False))
    assert not np.array_equal(held, nbody.field(r, 7.3, fp, MOON_P, held=False))
    assert nbody.hold_time(9.99) == 5.0 and nbody.hold_time(10.0) == 10.0


def test_radiation_pressure_is_off_by_default_and_matches_irradiance_over_c():
    r = np.array([AU, 0.0, 0.0])
    p_sun = make_params(1.0, (1.0, 1.0, 1.0), SUN_MU, 6.957e8, 0.0, 6.957e8)
    off = nbody.field(r, 0.0, nbody.make_field("sun", JD0, bodies=()), p_sun, held=False)
    assert off[0] == pytest.approx(-SUN_MU / AU ** 2, rel=1e-15)
    k = 0.02        # C_R A/m, m^2/kg
    on = nbody.field(r, 0.0, nbody.make_field("sun", JD0, bodies=(), srp=k), p_sun, held=False)
    # 1361 W/m^2 / c = 4.54e-6 N/m^2 at 1 AU, pushing away from the Sun
    assert on[0] - off[0] == pytest.approx(1361.0 / 299792458.0 * k, rel=1e-12)


def test_soi_radii_match_curtis_table_8_1():
    assert soi.soi_radius("earth") == pytest.approx(925e6, rel=0.01)
    assert soi.soi_radius("moon") == pytest.approx(66.1e6, rel=0.01)
    assert soi.soi_radius("mars") == pytest.approx(577e6, rel=0.01)
    assert soi.soi_radius("sun") == math.inf


def test_moon_frame_has_the_iau_pole_as_z():
    rot = soi.frame_rotation("moon", JD0)
    np.testing.assert_allclose(rot[:, 2], pole("moon", JD0), atol=1e-15)
    np.testing.assert_allclose(rot.T @ rot, np.eye(3), atol=1e-15)
    assert rot[2, 0] == 0.0             # x: the node on the J2000 equator


@pytest.mark.parametrize("new_center", ["moon", "sun"])
def test_handover_keeps_the_heliocentric_state_to_1e_9(new_center):
    gmst0 = 0.7
    t = 2.5 * 86400.0
    jd = JD0 + t / 86400.0
    fp = nbody.make_field("earth", JD0, rotation=soi.frame_rotation("earth", JD0, gmst0))
    moon = states(jd, "earth")["moon"]
    # near the Moon, in Earth's ECI (J2000 turned by GMST0 about z)
    rz = np.array([[math.cos(gmst0), math.sin(gmst0), 0], [-math.sin(gmst0), math.cos(gmst0), 0],
                   [0, 0, 1]])
    r = rz @ (moon[0] + np.array([3.0e7, -2.0e7, 1.0e7]))
    v = rz @ (moon[1] + np.array([100.0, 800.0, -50.0]))
    r_new, v_new, fp_new = soi.handover(r, v, fp, t, new_center, gmst0)
    helio = states(jd, "sun")
    rot = soi.frame_rotation(new_center, jd)
    x_before = helio["earth"][0] + rz.T @ r
    u_before = helio["earth"][1] + rz.T @ v
    x_after = helio[new_center][0] + rot @ r_new
    u_after = helio[new_center][1] + rot @ v_new
    assert np.linalg.norm(x_after - x_before) <= 1e-9 * np.linalg.norm(x_before)
    assert np.linalg.norm(u_after - u_before) <= 1e-9 * np.linalg.norm(u_before)
    assert soi.central_body(r, fp, t) == "moon"
    # and back again: the same vectors in Earth's ECI
    r_back, v_back, fp_back = soi.handover(r_new, v_new, fp_new, t, "earth", gmst0)
    np.testing.assert_allclose(r_back, r, rtol=1e-9 * np.linalg.norm(r) / np.min(np.abs(r)))
    np.testing.assert_allclose(v_back, v, rtol=1e-9 * np.linalg.norm(v) / np.min(np.abs(v)))
    np.testing.assert_array_equal(fp_back, fp)


def test_central_params_carry_each_bodys_gravity():
    p = soi.central_params(EARTH_P, "moon")
    np.testing.assert_array_equal(p, MOON_P)
    np.testing.assert_array_equal(soi.central_params(p, "earth"), EARTH_P)
