"""Kozai mean elements (rocketsim.frames.mean_elements) against the closed-form
short-period terms and against the J2 motion the simulator integrates.

References:
- Kozai (1959, Astron. J. 64, 367) and Brouwer (1959, Astron. J. 64, 378),
  first-order short-period J2 terms of a circular orbit, ``u`` the argument of
  latitude: ``delta a = (3/2) J2 R^2 / a sin^2 i cos 2u`` and
  ``delta i = (3/4) J2 (R/a)^2 sin i cos i cos 2u``;
- the reference integrator (scipy DOP853, :mod:`rocketsim.dynamics.reference`)
  on the point mass plus J2: along the integrated orbit the mean semi-major
  axis, eccentricity and inclination stay constant (J2 has no secular effect
  on them) while the osculating ones ripple by kilometres.
"""

import math

import numpy as np
import pytest

from rocketsim.constants import EARTH_J2, EARTH_MU, EARTH_RADIUS_EQ, EARTH_RADIUS_POLAR
from rocketsim.dynamics.reference import integrate_reference
from rocketsim.layout import R, V, make_params, make_state
from rocketsim.frames.elements import Elements, state_to_elements
from rocketsim.frames.mean_elements import (mean_elements_of_state, mean_to_osculating,
                                            osculating_to_mean, state_of_mean_elements)

A700 = EARTH_RADIUS_EQ + 700e3
I_SSO = math.radians(98.19)


@pytest.mark.parametrize("u", [0.0, 0.4, 1.1, 2.5, 4.0])
def test_circular_orbit_short_period_terms_are_kozai_s(u):
    osc = mean_to_osculating(Elements(A700, 0.0, I_SSO, 0.7, 0.0, u))
    da = 1.5 * EARTH_J2 * EARTH_RADIUS_EQ ** 2 / A700 * math.sin(I_SSO) ** 2 * math.cos(2 * u)
    di = 0.75 * EARTH_J2 * (EARTH_RADIUS_EQ / A700) ** 2 * math.sin(I_SSO) * math.cos(I_SSO) * math.cos(2 * u)
    assert osc.a - A700 == pytest.approx(da, abs=1e-6)          # 9.14 km at the node
    assert osc.i - I_SSO == pytest.approx(di, abs=1e-12)


@pytest.mark.parametrize("mean", [
    Elements(A700, 0.0, I_SSO, 0.7, 0.0, 0.3),
    Elements(EARTH_RADIUS_EQ + 1000e3, 0.1, 0.9, 0.3, 1.2, 2.0),
    Elements(EARTH_RADIUS_EQ + 20000e3, 0.7, 1.1, 5.0, 4.0, 0.1),
    Elements(EARTH_RADIUS_EQ + 400e3, 0.001, math.radians(51.6), 2.0, 3.0, 6.0),
])
def test_osculating_to_mean_inverts_mean_to_osculating(mean):
    back = osculating_to_mean(mean_to_osculating(mean))
    assert back.a == pytest.approx(mean.a, rel=1e-13)
    assert back.e == pytest.approx(mean.e, abs=1e-12)
    assert back.i == pytest.approx(mean.i, abs=1e-12)
    assert math.remainder(back.raan - mean.raan, 2 * math.pi) == pytest.approx(0.0, abs=1e-12)
    assert math.remainder(back.argp + back.nu - mean.argp - mean.nu, 2 * math.pi) == pytest.approx(
        0.0, abs=1e-9)


@pytest.mark.parametrize("mean", [
    Elements(A700, 0.0, I_SSO, 0.7, 0.0, 0.0),
    Elements(EARTH_RADIUS_EQ + 600e3, 0.05, math.radians(51.6), 1.0, 0.5, 0.0),
])
def test_mean_elements_stay_put_along_the_integrated_j2_orbit(mean):
    # Two revolutions with DOP853 (rtol 1e-12): the osculating a ripples by 18.3 km
    # peak to peak (the circular orbit; 12.7 km the eccentric one); the mean a stays
    # within 31 m (5 m), the mean e within 2.9e-6 (1.1e-6) and the mean i within
    # 1.5e-7 rad (2.6e-7), with no drift -- the second-order (J2^2) short-period
    # terms a first-order theory leaves.
    r, v = state_of_mean_elements(mean)
    p = make_params(10.0, (1.0, 1.0, 1.0), EARTH_MU, EARTH_RADIUS_EQ, EARTH_J2, EARTH_RADIUS_POLAR)
    period = 2 * math.pi * math.sqrt(mean.a ** 3 / EARTH_MU)
    osc_a, mean_a, mean_e, mean_i = [], [], [], []
    y = make_state(r, v)
    for k in range(40):
        y = integrate_reference(y, 0.0, period / 20, p, rtol=1e-12, atol=1e-6)
        osc_a.append(state_to_elements(y[R:R + 3], y[V:V + 3]).a)
        m = mean_elements_of_state(y[R:R + 3], y[V:V + 3])
        mean_a.append(m.a)
        mean_e.append(m.e)
        mean_i.append(m.i)
    assert np.ptp(osc_a) > 1e4
    assert np.max(np.abs(np.array(mean_a) - mean.a)) < 40.0
    assert np.max(np.abs(np.array(mean_e) - mean.e)) < 4e-6
    assert np.max(np.abs(np.array(mean_i) - mean.i)) < 5e-7
