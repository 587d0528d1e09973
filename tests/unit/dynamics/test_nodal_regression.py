"""J2 nodal regression against the analytic secular rate.

Vallado (4th ed., eq. 9-41; docs/physics.md#j2): dOmega/dt = -(3/2) n J2 (R/p)^2 cos i.
The seed description quotes -5.0 deg/day for the ISS's 51.6 deg and +0.986
deg/day for a 700 km, 98.2 deg sun-synchronous orbit. The node is measured
at each ascending-node crossing (the same argument of latitude every orbit,
so the short-period J2 terms repeat and a straight-line fit gives the
secular rate) over ten orbits.

Step: 0.1 s, the largest headless step, to keep the test to a few seconds
(ten orbits at 20 ms would be 2.9 million steps); at this step a coasting
orbit's RK4 error is still at rounding level (see test_integrator).
"""

import math

import numpy as np
import pytest

from rocketsim.constants import EARTH_J2, EARTH_MU, EARTH_RADIUS_EQ, EARTH_RADIUS_POLAR
from rocketsim.dynamics.rk4 import advance
from rocketsim.layout import R, V, make_params, make_state
from rocketsim.frames.elements import elements_to_state

STEP = 0.1
DAY = 86400.0


def analytic_rate(a, e, i):
    n = math.sqrt(EARTH_MU / a ** 3)
    p = a * (1 - e * e)
    return -1.5 * n * EARTH_J2 * (EARTH_RADIUS_EQ / p) ** 2 * math.cos(i)


def measured_rate(a, i, orbits=10):
    r, v = elements_to_state(a, 0.0, i, 1.0, 0.0, 0.5, EARTH_MU)
    y = make_state(r, v)
    p = make_params(10.0, (1.0, 1.0, 1.0), EARTH_MU, EARTH_RADIUS_EQ, EARTH_J2, EARTH_RADIUS_POLAR)
    period = 2 * math.pi * math.sqrt(a ** 3 / EARTH_MU)
    times, nodes = [], []
    k = 0
    while k * STEP < orbits * period:
        z_before = y[R + 2]
        y, _ = advance(y, k, STEP, 1, p)
        k += 1
        if z_before < 0.0 <= y[R + 2]:
            h = np.cross(y[R:R + 3], y[V:V + 3])
            times.append(k * STEP)
            nodes.append(math.atan2(h[0], -h[1]))
    nodes = np.unwrap(nodes)
    assert len(nodes) >= 6
    return np.polyfit(times, nodes, 1)[0]


@pytest.mark.parametrize("altitude_km, inclination_deg, quoted_deg_per_day", [
    (400.0, 51.6, -5.0),
    (700.0, 98.2, 0.986),
])
def test_nodal_regression_matches_the_analytic_rate(altitude_km, inclination_deg, quoted_deg_per_day):
    a = EARTH_RADIUS_EQ + altitude_km * 1e3
    i = math.radians(inclination_deg)
    expected = analytic_rate(a, 0.0, i)
    assert math.degrees(expected) * DAY == pytest.approx(quoted_deg_per_day, rel=0.02)
    measured = measured_rate(a, i)
    assert measured == pytest.approx(expected, rel=0.01)
