"""Burn pricing against a worked example and the orbits the burns produce.

References:
- Curtis, *Orbital Mechanics for Engineering Students*, Example 8.3: Earth
  departure to a Hohmann transfer to Mars from a 300 km circular parking
  orbit (Earth radius 6378 km, mu 398600 km^3/s^2), v_inf = 2.943 km/s,
  needs dv = 3.59 km/s.
- The orbit after each burn, integrated with scipy's DOP853 (an independent
  reference): the escape burn must leave on a hyperbola whose speed far out
  tends to v_inf, the capture burn must leave an ellipse whose apoapsis is
  the requested one.
"""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from rocketsim.constants import MARS_MU, MARS_RADIUS_EQ
from rocketsim.transfer.burns import (asymptote_direction, c3, capture_dv, escape_dv,
                                      escape_dv_c3, v_infinity)


def test_curtis_example_8_3_escape():
    dv = escape_dv(398600e9, 6678e3, 2.943e3)
    assert abs(dv / 1e3 - 3.59) <= 0.005
    assert escape_dv_c3(398600e9, 6678e3, 2.943e3 ** 2) == pytest.approx(dv, rel=1e-15)


def _integrate(mu, r0, v0, t_end, event=None):
    def rhs(t, y):
        r = y[:3]
        return np.concatenate([y[3:], -mu * r / np.linalg.norm(r) ** 3])

    return solve_ivp(rhs, (0.0, t_end), np.concatenate([r0, v0]), method="DOP853",
                     rtol=1e-12, atol=1e-6, events=event)


def test_escape_burn_leaves_with_the_requested_excess_speed():
    mu, r_park, v_inf = 398600.4418e9, 6578e3, 3.2e3
    v_circ = math.sqrt(mu / r_park)
    v_burn = v_circ + escape_dv(mu, r_park, v_inf)
    sol = _integrate(mu, np.array([r_park, 0.0, 0.0]), np.array([0.0, v_burn, 0.0]), 3.0e7)
    r_far = np.linalg.norm(sol.y[:3, -1])
    speed_far = np.linalg.norm(sol.y[3:, -1])
    assert r_far > 5e10
    # Far out the speed is v_inf plus what the remaining potential gives.
    assert speed_far == pytest.approx(math.sqrt(v_inf ** 2 + 2 * mu / r_far), rel=1e-9)
    assert speed_far == pytest.approx(v_inf, rel=2e-3)


@pytest.mark.parametrize("apoapsis_altitude", [400e3, 10_000e3, 33_000e3])
def test_capture_burn_reaches_the_requested_apoapsis(apoapsis_altitude):
    mu = MARS_MU
    rp = MARS_RADIUS_EQ + 400e3
    ra = MARS_RADIUS_EQ + apoapsis_altitude
    v_inf = 2.65e3
    v_hyperbola = math.sqrt(v_inf ** 2 + 2 * mu / rp)
    v_after = v_hyperbola - capture_dv(mu, rp, ra, v_inf)

    def apoapsis(t, y):
        return np.dot(y[:3], y[3:])
    apoapsis.terminal = True
    apoapsis.direction = -1.0

    sol = _integrate(mu, np.array([rp, 0.0, 0.0]), np.array([0.0, v_after, 0.0]), 1e6,
                     event=apoapsis)
    if ra == rp:
        # A circle: the radius stays rp all along.
        assert np.allclose(np.linalg.norm(sol.y[:3], axis=0), rp, rtol=1e-9)
    else:
        r_top = np.linalg.norm(sol.y_events[0][0][:3])
        assert r_top == pytest.approx(ra, rel=1e-9)


def test_c3_v_infinity_and_asymptote():
    v_sc = np.array([[30e3, 3e3, 0.0], [29e3, 0.0, 2e3]])
    v_earth = np.array([29e3, 0.0, 0.0])
    vinf = v_infinity(v_sc, v_earth)
    np.testing.assert_allclose(c3(vinf), [1e6 + 9e6, 4e6])
    ra, dec = asymptote_direction(vinf)
    np.testing.assert_allclose(ra, [math.atan2(3, 1), 0.0])
    np.testing.assert_allclose(dec, [0.0, math.pi / 2])
    ra, dec = asymptote_direction([-1.0, -1.0, -math.sqrt(2.0)])
    assert ra == pytest.approx(1.25 * math.pi)
    assert dec == pytest.approx(-math.pi / 4)
