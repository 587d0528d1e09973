"""The central body's rotation in the parameters: the air and the ground turn with the
body the vehicle flies about.

``p[P_SPIN]`` (rad/s about the frame's z, which is the body's pole: Earth's ECI, or
the IAU-pole frame a sphere-of-influence handover sets up) is Earth's WGS84 rate
about Earth and the prime meridian's rate W-dot of the IAU rotation model about
the Moon and Mars. References (typed here, not read from the code): WGS84
(NIMA TR8350.2) omega_E = 7.2921159e-5 rad/s; Archinal et al., "Report of the IAU
WGCCRE: 2015", Celest. Mech. Dyn. Astr. 130:22 (2018): Mars W = 176.049863 deg +
350.891982443297 deg/day d (Table 1), the Moon W = 38.3213 deg + 13.17635815 deg/day
d (Table 2). The analytic checks: the ground (and still air) at ``r`` moves at
``Omega x r``; a body resting on Mars's equator presses its legs by its weight less
the centrifugal term, ``m (mu/r^2 (1 + 3/2 J2 (R/r)^2) - Omega^2 r) / (n k)``
(point mass + J2 on the equator).
"""

import math

import numpy as np
import pytest

from rocketsim.constants import (EARTH_J2, EARTH_MU, EARTH_RADIUS_EQ, EARTH_RADIUS_POLAR, MARS_J2,
                                 MARS_MU, MARS_RADIUS_EQ)
from rocketsim.dynamics.derivative import body_air_velocity, derivative
from rocketsim.dynamics.rk4 import step
from rocketsim.dynamics.soi import central_params
from rocketsim.layout import P_SPIN, make_params
from rocketsim.flight.readings import StateView
from rocketsim.frames.quaternion import quat_from_matrix
from rocketsim.dynamics.central import air_about
from rocketsim.vehicle.contact import contact_heights
from rocketsim.vehicle.aero import A_WIND
from rocketsim.vehicle.build import build
from tests.aero_vehicles import shipped

DAY = 86400.0
WGS84_OMEGA = 7.2921159e-5                              # rad/s
MARS_OMEGA = math.radians(350.891982443297) / DAY       # rad/s, IAU 2015 W-dot
MOON_OMEGA = math.radians(13.17635815) / DAY
K_LEG, N_LEGS = 8.5e7, 4                                # N/m, vehicles/lander.yaml


def earth_p():
    return make_params(1.0, (1.0, 1.0, 1.0), EARTH_MU, EARTH_RADIUS_EQ, EARTH_J2, EARTH_RADIUS_POLAR)


def test_each_central_body_turns_at_its_own_rate():
    p = earth_p()
    assert p[P_SPIN] == WGS84_OMEGA
    assert central_params(p, "mars")[P_SPIN] == pytest.approx(MARS_OMEGA, rel=1e-15)
    assert central_params(p, "moon")[P_SPIN] == pytest.approx(MOON_OMEGA, rel=1e-15)
    assert central_params(p, "sun")[P_SPIN] == 0.0       # its frame's z is J2000's, not its pole
    assert central_params(central_params(p, "mars"), "earth")[P_SPIN] == WGS84_OMEGA


def test_about_mars_a_body_at_rest_on_the_turning_ground_sees_still_air():
    # a body riding Mars's ground at 20 deg north (planetocentric), nose up
    p = central_params(earth_p(), "mars")
    lat = math.radians(20.0)
    up = np.array([math.cos(lat), 0.0, math.sin(lat)])
    r = (MARS_RADIUS_EQ + 100.0) * up
    y = np.zeros(13)
    y[0:3], y[3:6] = r, np.cross((0.0, 0.0, MARS_OMEGA), r)      # Omega x r: 226 m/s here
    y[6] = 1.0
    air = body_air_velocity(y, np.zeros(3), p[P_SPIN])
    assert np.max(np.abs(air)) < 1e-12
    view = StateView.of_state(0.0, y, p=p)
    assert np.linalg.norm(view.surface_velocity) < 1e-12
    # with Earth's rate the same body would see a wind of (Omega_E - Omega_M) r cos(lat)
    assert np.linalg.norm(body_air_velocity(y, np.zeros(3), WGS84_OMEGA)) == pytest.approx(
        (WGS84_OMEGA - MARS_OMEGA) * np.linalg.norm(r[:2]), rel=1e-9)
    # the readings' gravity is Mars's (point mass + J2), not Earth's
    g = MARS_MU / (r @ r) * math.sqrt((1.0 + 1.5 * MARS_J2 * (MARS_RADIUS_EQ / np.linalg.norm(r)) ** 2
                                       * (1.0 - 5.0 * math.sin(lat) ** 2)) ** 2 * math.cos(lat) ** 2
                                      + (1.0 + 1.5 * MARS_J2 * (MARS_RADIUS_EQ / np.linalg.norm(r)) ** 2
                                         * (3.0 - 5.0 * math.sin(lat) ** 2)) ** 2 * math.sin(lat) ** 2)
    assert view.gravity == pytest.approx(g, rel=1e-12)


def test_a_lander_resting_on_mars_equator_stays_at_rest():
    """The lander (vehicles/lander.yaml) stands on Mars's equator, turning with the ground,
    its legs pressed by the static load: 3 s later it is still there, at rest over
    the ground (the contact's ground turns at Mars's rate: at Earth's, the feet would
    slide at 6.9 m/s against it and friction would drag the lander along)."""
    model = build(shipped("lander.yaml"))
    model.arrays = model.arrays._replace(air=air_about("mars", None).arrays())
    assert model.arrays.aero.ref[A_WIND] == 0.0          # Earth's standard day is calm
    p = central_params(earth_p(), "mars")
    y0 = model.state([0, 0, 0], [0, 0, 0])
    mass, x_cm = model.mass_properties(y0)[:2]
    up = np.array([1.0, 0.0, 0.0])
    # weight less the centrifugal term at the equator (point mass + J2), shared by the legs
    r_ground = MARS_RADIUS_EQ
    g = MARS_MU / r_ground ** 2 * (1.0 + 1.5 * MARS_J2) - MARS_OMEGA ** 2 * r_ground
    static = mass * g / (N_LEGS * K_LEG)
    axes = np.column_stack((up, (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)))         # body x up
    q, w = quat_from_matrix(axes), axes.T @ np.array([0.0, 0.0, MARS_OMEGA])
    r = (r_ground + 1.2 + x_cm) * up                                       # feet 1.2 m below the base
    # the footpads' 4.7 m ring stands 3.3 um higher on the curved ground: sink them to -static
    r = r - (contact_heights(model.state(r, (0, 0, 0), q=q, w=w), p, model)[0] + static) * up
    y = model.state(r, np.cross((0.0, 0.0, MARS_OMEGA), r), q=q, w=w)
    assert contact_heights(y, p, model)[:N_LEGS] == pytest.approx(-static, abs=1e-9)
    dy = np.zeros(y.shape[0])
    derivative(0.0, y, p, dy, model.arrays)
    # at rest on the ground: the acceleration is the ground's centripetal one (to 1e-4 m/s^2 of
    # its 0.017: gravity at the centre of mass, ~5 m above the feet, is 1e-5 m/s^2 weaker)
    assert np.linalg.norm(dy[3:6] + MARS_OMEGA ** 2 * r) < 1e-4
    t, h = 0.0, 0.1
    for k in range(30):
        y = step(y, k * h, h, p, model.arrays)
    t = 30 * h
    ground = np.cross((0.0, 0.0, MARS_OMEGA), y[0:3])
    turned = np.array([math.cos(MARS_OMEGA * t), math.sin(MARS_OMEGA * t), 0.0])
    print(f"\n[mars lander] after 3 s: {np.linalg.norm(y[3:6] - ground) * 1e3:.3g} mm/s over the ground, "
          f"{np.linalg.norm(y[0:3] - np.linalg.norm(r) * turned) * 1e3:.3g} mm from where the ground took it")
    assert np.linalg.norm(y[3:6] - ground) < 1e-3
    assert np.linalg.norm(y[0:3] - np.linalg.norm(r) * turned) < 1e-3
    assert contact_heights(y, p, model)[:N_LEGS] == pytest.approx(-static, abs=1e-4)
