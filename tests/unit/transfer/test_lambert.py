"""Izzo's Lambert solver against published worked examples and analytic cases.

References:
- Vallado, *Fundamentals of Astrodynamics and Applications*, 4th ed.,
  Example 7-5 (short way, 76 min).
- Curtis, *Orbital Mechanics for Engineering Students*, Example 5.2 (1 h).
- Der (2011), "The Superior Lambert Algorithm", AMOS conference: test
  cases I (zero revolutions) and II (a Molniya-like arc, zero and one
  revolution, both branches), to the paper's printed (truncated) digits.
- The Hohmann transfer (an exact 180-degree transfer, analytic velocities
  from the vis-viva equation).
"""

import math

import numpy as np
import pytest

from rocketsim.errors import InputError
from rocketsim.orbits import propagate
from rocketsim.transfer import lambert

KM = 1e3
MU_VALLADO = 398600.4418e9      # m^3/s^2, as in Vallado and Der
MU_CURTIS = 398600e9            # m^3/s^2, Curtis's value


def assert_to_digits(actual_m_s, expected_km_s, decimals, units=0.5):
    """Agreement to the printed digits: within ``units`` of the last one.

    Half a unit for rounded figures; Der's figures are truncated (e.g. our
    -2.0957280968 is printed -2.09572809), so one unit for his.
    """
    actual = np.asarray(actual_m_s) / KM
    tolerance = units * 10.0 ** (-decimals) + 1e-12
    assert np.all(np.abs(actual - np.asarray(expected_km_s)) <= tolerance), (actual, expected_km_s)


def test_vallado_example_7_5():
    # r1 = 15945.34 i km, r2 = 12214.83899 i + 10249.46731 j km, 76 min.
    # Book: v1 = 2.058913 i + 2.915965 j, v2 = -3.451565 i + 0.910315 j km/s.
    # The book's inputs are printed to ~7 digits (2.5 and (1.9151111,
    # 1.6069690) Earth radii), so agreement is to one unit of the 6th decimal.
    v1, v2 = lambert(MU_VALLADO, [15945.34e3, 0, 0], [12214.83899e3, 10249.46731e3, 0], 76 * 60)
    np.testing.assert_allclose(v1 / KM, [2.058913, 2.915965, 0.0], atol=1e-6)
    np.testing.assert_allclose(v2 / KM, [-3.451565, 0.910315, 0.0], atol=1e-6)


def test_curtis_example_5_2():
    # r1 = (5000, 10000, 2100) km, r2 = (-14600, 2500, 7000) km, 1 h, mu 398600.
    # Book: v1 = (-5.9925, 1.9254, 3.2456), v2 = (-3.3125, -4.1966, -0.38529) km/s.
    v1, v2 = lambert(MU_CURTIS, [5000e3, 10000e3, 2100e3], [-14600e3, 2500e3, 7000e3], 3600.0)
    assert_to_digits(v1, [-5.9925, 1.9254, 3.2456], 4)
    assert_to_digits(v2[:2], [-3.3125, -4.1966], 4)
    assert_to_digits(v2[2], -0.38529, 5)


def test_der_case_1_zero_revolutions():
    r1 = np.array([2249.171260, 1898.007100, 5639.599193]) * KM
    r2 = np.array([1744.495443, -4601.556054, 4043.864391]) * KM
    v1, v2 = lambert(MU_VALLADO, r1, r2, 1618.50)
    assert_to_digits(v1, [-2.09572809, 3.92602196, -4.94516810], 8, units=1)
    assert_to_digits(v2, [2.46309613, 0.84490197, 6.10890863], 8, units=1)


R1_DER2 = np.array([22592.145603, -1599.915239, -19783.950506]) * KM
R2_DER2 = np.array([1922.067697, 4054.157051, -8925.727465]) * KM


def test_der_case_2_zero_revolutions():
    v1, v2 = lambert(MU_VALLADO, R1_DER2, R2_DER2, 36000.0)
    assert_to_digits(v1, [2.000652697, 0.387688615, -2.666947760], 9, units=1)
    assert_to_digits(v2, [-3.79246619, -1.77707641, 6.856814395], 8, units=1)


def test_der_case_2_one_revolution_both_branches():
    # Left branch (low_path=False in the PyKEP/lamberthub convention).
    v1, v2 = lambert(MU_VALLADO, R1_DER2, R2_DER2, 36000.0, revs=1, low_path=False)
    assert_to_digits(v1, [0.50335770, 0.61869408, -1.57176904], 8, units=1)
    assert_to_digits(v2, [-4.18334626, -1.13262727, 6.13307091], 8, units=1)
    # Right branch. Der prints v2 = (-5.53841370, 0.01822220, 5.49641054):
    # ours differs by up to 5e-7 km/s there while v1 agrees to all 8 digits;
    # propagating our v1 for 36000 s lands on r2 (checked below) and
    # lamberthub's gooding1990 gives our v2, so the paper's v2 carries the
    # error. Agreement to 1e-6 km/s is asserted for it.
    v1, v2 = lambert(MU_VALLADO, R1_DER2, R2_DER2, 36000.0, revs=1, low_path=True)
    assert_to_digits(v1, [-2.45759553, 1.16945801, 0.43161258], 8, units=1)
    np.testing.assert_allclose(v2 / KM, [-5.53841370, 0.01822220, 5.49641054], atol=1e-6)
    r, v = propagate(MU_VALLADO, R1_DER2, v1, 36000.0)
    np.testing.assert_allclose(r, R2_DER2, rtol=0, atol=1e-10 * np.linalg.norm(R2_DER2))
    np.testing.assert_allclose(v, v2, rtol=0, atol=1e-9 * np.linalg.norm(v2))


@pytest.mark.parametrize("prograde", [True, False])
def test_exact_hohmann_180_degrees(prograde):
    # Earth-to-Mars-like circles in the xy plane: the positions are exactly
    # antiparallel, so the plane comes from the +z convention, and the
    # half-ellipse's velocities are the vis-viva ones.
    mu, ra, rb = 1.32712440018e20, 1.496e11, 2.279e11
    a = 0.5 * (ra + rb)
    tof = math.pi * math.sqrt(a ** 3 / mu)
    v1, v2 = lambert(mu, [ra, 0.0, 0.0], [-rb, 0.0, 0.0], tof, prograde=prograde)
    sign = 1.0 if prograde else -1.0
    vp = math.sqrt(mu * (2 / ra - 1 / a))
    va = math.sqrt(mu * (2 / rb - 1 / a))
    np.testing.assert_allclose(v1, [0.0, sign * vp, 0.0], atol=1e-9 * vp)
    np.testing.assert_allclose(v2, [0.0, -sign * va, 0.0], atol=1e-9 * va)


def test_retrograde_is_the_long_way_of_a_prograde_geometry():
    # Mirroring y flips the z component of every angular momentum, so it
    # maps a retrograde transfer onto a prograde one.
    r1 = np.array([7000e3, 1000e3, 2000e3])
    r2 = np.array([-3000e3, 9000e3, -1500e3])
    mirror = np.array([1.0, -1.0, 1.0])
    v1r, v2r = lambert(MU_VALLADO, r1, r2, 5000.0, prograde=False)
    v1p, v2p = lambert(MU_VALLADO, r1 * mirror, r2 * mirror, 5000.0, prograde=True)
    np.testing.assert_allclose(v1r * mirror, v1p, rtol=1e-12)
    np.testing.assert_allclose(v2r * mirror, v2p, rtol=1e-12)


def test_broadcasting_matches_scalar_calls():
    rng = np.random.default_rng(8)
    r1 = rng.normal(size=(4, 1, 3)) * 7e6
    r2 = rng.normal(size=(1, 5, 3)) * 9e6
    tof = rng.uniform(1e3, 2e4, size=(4, 5))
    v1, v2 = lambert(MU_VALLADO, r1, r2, tof)
    assert v1.shape == v2.shape == (4, 5, 3)
    for i in range(4):
        for j in range(5):
            s1, s2 = lambert(MU_VALLADO, r1[i, 0], r2[0, j], tof[i, j])
            assert s1.shape == (3,)
            np.testing.assert_array_equal(s1, v1[i, j])
            np.testing.assert_array_equal(s2, v2[i, j])


@pytest.mark.parametrize("tof", [-10.0, 0.0, float("nan")])
def test_non_positive_time_of_flight_is_an_input_error(tof):
    with pytest.raises(InputError, match="time of flight"):
        lambert(MU_VALLADO, [7e6, 0, 0], [0, 7e6, 0], tof)


def test_coincident_positions_are_an_input_error():
    with pytest.raises(InputError, match="coincide"):
        lambert(MU_VALLADO, R1_DER2, R1_DER2, 3600.0)


def test_too_short_for_the_revolutions_is_an_input_error():
    # Der case II in 5 h has no one-revolution solution (the minimum time
    # for one revolution between these points is longer).
    with pytest.raises(InputError, match="1-revolution"):
        lambert(MU_VALLADO, R1_DER2, R2_DER2, 5 * 3600.0, revs=1)
