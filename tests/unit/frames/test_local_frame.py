"""The local vertical, the ground's motion and the air about the Moon and Mars: the readings,
the autopilot and the rails read the central body's ellipsoid turning at its own rate.

References typed here, not read from the code: Mars's IAU 2015 ellipsoid, equatorial radius
3396.19 km and polar radius 3376.20 km (flattening 1/169.894), and rotation W-dot = 350.891982443297 deg/day
(Archinal et al., Celest. Mech. Dyn. Astr. 130:22, 2018, tables 1 and 4). The analytic
geodetic point at latitude phi and height h on an ellipsoid (a, b), e^2 = 1 - b^2/a^2,
N = a / sqrt(1 - e^2 sin^2 phi): ((N + h) cos phi, 0, (N (1 - e^2) + h) sin phi), its up
(cos phi, 0, sin phi); the ground at r moves at Omega x r.
"""

import math

import numpy as np
import pytest

from rocketsim.constants import EARTH_J2, EARTH_MU, EARTH_RADIUS_EQ, EARTH_RADIUS_POLAR
from rocketsim.dynamics.rails import command_attitude
from rocketsim.dynamics.soi import central_params
from rocketsim.layout import make_params, make_state
from rocketsim.flight.autopilot import AttitudeCommand
from rocketsim.flight.readings import StateView
from rocketsim.frames.quaternion import quat_from_matrix, quat_rotate

A = 3396.19e3
B = A * (1.0 - 1.0 / 169.894)          # 3376.19995 km: the table's 3376.20 km to 5 cm
OMEGA = math.radians(350.891982443297) / 86400.0
MARS_P = central_params(make_params(1.0, (1.0, 1.0, 1.0), EARTH_MU, EARTH_RADIUS_EQ, EARTH_J2,
                                    EARTH_RADIUS_POLAR), "mars")


def on_mars(latitude_deg, height):
    """Position (m) at geodetic ``latitude_deg`` and ``height`` on Mars's ellipsoid, in the
    frame's xz plane, and the up there."""
    phi = math.radians(latitude_deg)
    e2 = 1.0 - (B / A) ** 2
    n = A / math.sqrt(1.0 - e2 * math.sin(phi) ** 2)
    r = np.array([(n + height) * math.cos(phi), 0.0, (n * (1.0 - e2) + height) * math.sin(phi)])
    return r, np.array([math.cos(phi), 0.0, math.sin(phi)])


def nose_along(direction):
    """A quaternion whose body x is ``direction``."""
    x = direction / np.linalg.norm(direction)
    y = np.cross((0.0, 0.0, 1.0), x) if abs(x[2]) < 0.9 else np.cross((1.0, 0.0, 0.0), x)
    y /= np.linalg.norm(y)
    return quat_from_matrix(np.column_stack((x, y, np.cross(x, y))))


def test_a_climb_at_45_deg_on_mars_reads_mars_vertical_and_ground():
    """10 km over Mars's ellipsoid at 45 deg latitude, climbing 5 m/s along the normal while
    turning with the ground, the nose up: height 10 km, vertical speed 5 m/s, no horizontal
    speed, pitch 90 deg (with WGS84's height and Earth's rate the height read -2 980 km and the
    ground's motion was 4.9 m/s off)."""
    r, up = on_mars(45.0, 10e3)
    v = np.cross((0.0, 0.0, OMEGA), r) + 5.0 * up
    view = StateView(0.0, r, v, nose_along(up), (0.0, 0.0, 0.0), None, MARS_P[1], MARS_P)
    assert view.geodetic[2] == pytest.approx(10e3, abs=1e-6)
    assert view.geodetic[0] == pytest.approx(math.radians(45.0), abs=1e-12)
    assert view.vertical_speed == pytest.approx(5.0, abs=1e-9)
    assert view.horizontal_speed == pytest.approx(0.0, abs=1e-9)
    assert math.degrees(view.euler[0]) == pytest.approx(90.0, abs=1e-6)


def test_surface_retrograde_about_mars_points_against_the_air_of_mars():
    """A lander 2 km over Mars at 20 deg latitude, coming down at 60 m/s and moving 40 m/s
    east over the ground: the surface-retrograde command points the nose along
    -(v - Omega x r) (Mars's rate; Earth's put it 4.5 deg off)."""
    r, up = on_mars(20.0, 2e3)
    east = np.array([0.0, 1.0, 0.0])
    over_ground = -60.0 * up + 40.0 * east
    v = np.cross((0.0, 0.0, OMEGA), r) + over_ground
    y = make_state(r, v, nose_along(up))
    code = AttitudeCommand(mode="surface_retrograde").code
    q = command_attitude(code, y, 0.0, y[6:10], MARS_P)
    nose = quat_rotate(q, np.array([1.0, 0.0, 0.0]))
    want = -over_ground / np.linalg.norm(over_ground)
    assert math.degrees(math.acos(min(1.0, float(nose @ want)))) < 1e-6


def test_where_and_how_fast_about_earth_is_the_frames_functions_to_the_bit():
    """The one compiled call for a place about Earth gives the bits of the functions it
    stands for, applied one after the other: the ECI position turned Earth-fixed
    (``eci_to_ecef``), its WGS84 geodetic coordinates (``ecef_to_geodetic``), the local
    east, north, up there (``enu_basis``) turned back to ECI (``ecef_to_eci``), and the
    velocity over the turning ground (``air_velocity`` with no wind), on random states
    from the pad to far out."""
    from rocketsim.frames.earth_fixed import ecef_to_eci, eci_to_ecef
    from rocketsim.frames.geodetic import ecef_to_geodetic, enu_basis
    from rocketsim.frames.local import air_velocity, where_and_how_fast

    rng = np.random.default_rng(3)
    for _ in range(300):
        r = rng.normal(size=3) * rng.uniform(6.3e6, 5.0e7)
        v = rng.normal(size=3) * rng.uniform(0.0, 1.1e4)
        t = float(rng.uniform(0.0, 1e5))
        lat, lon, h, enu, surface = where_and_how_fast(r, v, t)
        assert (lat, lon, h) == ecef_to_geodetic(eci_to_ecef(r, t))
        np.testing.assert_array_equal(enu, [ecef_to_eci(row, t) for row in enu_basis(lat, lon)])
        np.testing.assert_array_equal(surface, air_velocity(r, v, np.zeros(3)))
