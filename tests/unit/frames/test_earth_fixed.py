"""ECI <-> Earth-fixed rotation against the sidereal day, the pad's speed and calculus.

References:
* WGS84 rotation rate omega_E = 7.292 115 9e-5 rad/s (NIMA TR8350.2 table
  3.1) is the rate relative to the mean equinox: one turn takes the mean
  sidereal day, 23 h 56 m 4.0905 s = 86 164.0905 s (Astronomical Almanac,
  glossary "sidereal day"; the stellar day, 86 164.0989 s, is not it).
* The ground's motion: on the pad a vehicle moves east at omega_E R cos(lat),
  465.1 m/s at the equator (R = 6 378 137 m; docs/physics.md#frames).
* Calculus: the Earth-fixed velocity is the time derivative of the Earth-
  fixed position, checked by central differences.
"""

import math

import numpy as np
import pytest

from rocketsim.constants import EARTH_OMEGA, EARTH_RADIUS_EQ
from rocketsim.frames.earth_fixed import (
    earth_rotation_angle,
    ecef_to_eci,
    ecef_to_eci_velocity,
    eci_to_ecef,
    eci_to_ecef_velocity,
)

SIDEREAL_DAY = 86164.0905  # s, mean sidereal day (Astronomical Almanac)
PAD = np.array([EARTH_RADIUS_EQ, 0.0, 0.0])     # on the equator at Greenwich


def test_equator_point_returns_after_one_sidereal_day():
    r_eci = ecef_to_eci(PAD, SIDEREAL_DAY)
    # WGS84's 8-digit omega_E gives 86 164.0900 s: 0.5 ms short, 0.23 m at 465 m/s
    assert np.linalg.norm(r_eci - PAD) < 0.3
    assert earth_rotation_angle(SIDEREAL_DAY) == pytest.approx(2.0 * math.pi, abs=1e-7)


def test_quarter_day_turns_greenwich_east():
    # After a quarter sidereal day Greenwich has turned 90 deg east: it lies
    # on inertial +y, and the inertial x axis is at longitude -90 deg (-y).
    t = 0.25 * 2.0 * math.pi / EARTH_OMEGA
    np.testing.assert_allclose(ecef_to_eci(PAD, t), [0.0, EARTH_RADIUS_EQ, 0.0], atol=1e-8)
    np.testing.assert_allclose(eci_to_ecef(PAD, t), [0.0, -EARTH_RADIUS_EQ, 0.0], atol=1e-8)
    # theta0 shifts the start: x through Greenwich at theta0 = pi/2 means the
    # same picture at t = 0.
    np.testing.assert_allclose(ecef_to_eci(PAD, 0.0, theta0=math.pi / 2), [0.0, EARTH_RADIUS_EQ, 0.0],
                               atol=1e-8)


def test_pad_on_the_equator_moves_east_at_465_m_s():
    for t in (0.0, 1234.5):
        v_eci = ecef_to_eci_velocity(PAD, np.zeros(3), t)
        east = ecef_to_eci(np.array([0.0, 1.0, 0.0]), t)     # local east at Greenwich
        assert float(v_eci @ east) == pytest.approx(465.1, abs=0.05)
        assert np.linalg.norm(v_eci) == pytest.approx(465.1, abs=0.05)
    # and back: a point moving with the ground is at rest Earth-fixed
    r_eci = ecef_to_eci(PAD, 1234.5)
    np.testing.assert_allclose(eci_to_ecef_velocity(r_eci, v_eci, 1234.5), 0.0, atol=1e-12)


def test_velocity_is_derivative_of_position():
    # A body on a straight inertial line r(t) = r0 + v t: its Earth-fixed
    # velocity equals d/dt eci_to_ecef(r(t), t) (central difference, h = 1 s).
    r0 = np.array([7.0e6, -1.2e6, 3.3e6])
    v = np.array([-1.5e3, 7.1e3, 0.4e3])
    t, h = 500.0, 1.0
    numeric = (eci_to_ecef(r0 + v * (t + h), t + h, 0.3) - eci_to_ecef(r0 + v * (t - h), t - h, 0.3)) / (2 * h)
    analytic = eci_to_ecef_velocity(r0 + v * t, v, t, 0.3)
    # central-difference truncation ~ h^2 omega^2 |v|  ~ 4e-5 m/s here
    np.testing.assert_allclose(analytic, numeric, atol=1e-4)


def test_round_trips_vectorised():
    rng = np.random.default_rng(11)
    r = rng.normal(size=(100, 3)) * 7e6
    v = rng.normal(size=(100, 3)) * 7e3
    t = rng.uniform(0, 1e5, size=100)
    np.testing.assert_allclose(ecef_to_eci(eci_to_ecef(r, t), t), r, atol=1e-8)
    r_f = eci_to_ecef(r, t)
    v_f = eci_to_ecef_velocity(r, v, t)
    np.testing.assert_allclose(ecef_to_eci_velocity(r_f, v_f, t), v, atol=1e-9)
    # rows agree with the scalar calls
    for k in (0, 57, 99):
        np.testing.assert_array_equal(r_f[k], eci_to_ecef(r[k], t[k]))
        np.testing.assert_array_equal(v_f[k], eci_to_ecef_velocity(r[k], v[k], t[k]))
    # one time for many rows, and many times for one position
    assert eci_to_ecef(r, 10.0).shape == (100, 3)
    assert eci_to_ecef(r[0], t).shape == (100, 3)
    np.testing.assert_array_equal(eci_to_ecef(r[0], t)[5], eci_to_ecef(r[0], t[5]))


def test_rotation_angle_is_linear_in_time():
    assert earth_rotation_angle(0.0) == 0.0
    assert earth_rotation_angle(100.0, theta0=1.0) == 1.0 + EARTH_OMEGA * 100.0
    np.testing.assert_array_equal(earth_rotation_angle(np.array([0.0, 10.0])), [0.0, EARTH_OMEGA * 10.0])
