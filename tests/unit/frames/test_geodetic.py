"""WGS84 geodetic <-> Earth-fixed against Vallado's worked examples, pymap3d and NIMA.

References:
* Vallado, *Fundamentals of Astrodynamics and Applications*, 4th ed.:
  example 7-1 (site at 39.007 deg N, 104.883 deg W, 2 187 m ->
  r = (-1275.1219, -4797.9890, 3994.2975) km) and example 3-3
  (r = (6524.834, 6862.875, 6448.296) km -> 34.352496 deg, 46.4464 deg,
  5 085.22 km).
* pymap3d (a peer library used only in tests, pure Python, its own WGS84):
  geodetic2ecef, ecef2geodetic, enu2uvw.
* NIMA TR8350.2 (WGS84), table 3.4: normal gravity at the equator
  9.780 325 3359 m/s^2 and at the poles 9.832 184 9378 m/s^2.
"""

import math

import numpy as np
import pymap3d
import pytest

from numba import njit   # uncached on purpose: numba's disk cache misses edits to inlined callees
from rocketsim.constants import EARTH_RADIUS_EQ, EARTH_RADIUS_POLAR
from rocketsim.frames.geodetic import (
    ecef_to_geodetic,
    ecef_to_geodetic_njit,
    enu_basis,
    geodetic_to_ecef,
    normal_gravity,
)

D = math.radians
LATS = [-90.0, -89.9999, -60.0, -45.1, -30.0, -1e-7, 0.0, 1e-7, 30.0, 45.0, 60.0, 89.9999, 90.0]
LONS = [-180.0, -135.0, -90.0, -45.0, 0.0, 45.0, 90.0, 135.0, 179.9999]
HEIGHTS = [-1000.0, 0.0, 1.0, 1000.0, 1e4, 1e5, 4e5, 1e6]


def _grid():
    lat, lon, h = np.meshgrid(np.radians(LATS), np.radians(LONS), HEIGHTS, indexing="ij")
    return lat.ravel(), lon.ravel(), h.ravel()


def test_vallado_example_7_1_site_position():
    r = geodetic_to_ecef(D(39.007), D(-104.883), 2187.0)
    # Vallado quotes 0.1 m (4 decimals of km)
    np.testing.assert_allclose(r / 1e3, [-1275.1219, -4797.9890, 3994.2975], atol=1e-4)


def test_vallado_example_3_3_geodetic_latitude():
    lat, lon, h = ecef_to_geodetic(np.array([6524.834, 6862.875, 6448.296]) * 1e3)
    # to the example's digits: 6 decimals of a degree, 4, and 10 m
    assert math.degrees(lat) == pytest.approx(34.352496, abs=1e-6)
    assert math.degrees(lon) == pytest.approx(46.4464, abs=1e-4)
    assert h / 1e3 == pytest.approx(5085.22, abs=0.01)


def test_poles_and_equator_in_closed_form():
    # On the axis the height is |z| - b; on the equator sqrt(x^2+y^2) - a.
    for z_sign in (1.0, -1.0):
        for h in (-1000.0, 0.0, 1e6):
            lat, lon, hh = ecef_to_geodetic(np.array([0.0, 0.0, z_sign * (EARTH_RADIUS_POLAR + h)]))
            assert lat == z_sign * math.pi / 2
            assert hh == pytest.approx(h, abs=1e-6)
    lat, lon, h = ecef_to_geodetic(np.array([0.0, -(EARTH_RADIUS_EQ + 5.0), 0.0]))
    assert (lat, math.degrees(lon)) == (0.0, -90.0)
    assert h == pytest.approx(5.0, abs=1e-6)


def test_forward_matches_pymap3d():
    lat, lon, h = _grid()
    ours = geodetic_to_ecef(lat, lon, h)
    x, y, z = pymap3d.geodetic2ecef(lat, lon, h, deg=False)
    np.testing.assert_allclose(ours, np.stack([x, y, z], axis=-1), atol=1e-6)


def test_inverse_matches_pymap3d():
    lat, lon, h = _grid()
    r = geodetic_to_ecef(lat, lon, h)
    lat_p, lon_p, h_p = pymap3d.ecef2geodetic(r[:, 0], r[:, 1], r[:, 2], deg=False)
    lat_o, lon_o, h_o = ecef_to_geodetic(r)
    np.testing.assert_allclose(h_o, h_p, atol=1e-3)
    np.testing.assert_allclose(lat_o, lat_p, atol=1e-3 / EARTH_RADIUS_EQ)


def test_round_trip_under_a_millimetre_on_the_grid():
    lat, lon, h = _grid()
    r = geodetic_to_ecef(lat, lon, h)
    lat2, lon2, h2 = ecef_to_geodetic(r)
    assert np.max(np.abs(h2 - h)) < 1e-3
    assert np.max(np.abs(lat2 - lat)) * (EARTH_RADIUS_EQ + 1e6) < 1e-3
    away = np.abs(np.abs(lat) - math.pi / 2) > 1e-9      # longitude is arbitrary on the axis
    dlon = np.angle(np.exp(1j * (lon2 - lon)))[away]
    assert np.max(np.abs(dlon) * np.cos(lat[away]) * (EARTH_RADIUS_EQ + 1e6)) < 1e-3
    assert np.max(np.linalg.norm(geodetic_to_ecef(lat2, lon2, h2) - r, axis=1)) < 1e-3


def test_round_trip_random_points():
    rng = np.random.default_rng(2026)
    n = 20000
    lat = np.arcsin(rng.uniform(-1.0, 1.0, n))
    lon = rng.uniform(-math.pi, math.pi, n)
    h = rng.uniform(-1000.0, 1e6, n)
    r = geodetic_to_ecef(lat, lon, h)
    lat2, lon2, h2 = ecef_to_geodetic(r)
    assert np.max(np.abs(h2 - h)) < 1e-3
    assert np.max(np.linalg.norm(geodetic_to_ecef(lat2, lon2, h2) - r, axis=1)) < 1e-3


def test_shapes_and_njit_agree():
    r = geodetic_to_ecef(np.radians([10.0, -20.0]), np.radians([30.0, 40.0]), np.array([100.0, 2e5]))
    assert r.shape == (2, 3)
    assert geodetic_to_ecef(0.1, 0.2, 3.0).shape == (3,)
    lat, lon, h = ecef_to_geodetic(r)
    assert lat.shape == (2,)
    assert ecef_to_geodetic(r.reshape(1, 2, 3))[2].shape == (1, 2)
    assert isinstance(ecef_to_geodetic(r[0])[0], float)
    assert ecef_to_geodetic(r[1]) == ecef_to_geodetic_njit(*r[1])
    assert (lat[1], lon[1], h[1]) == ecef_to_geodetic_njit(*r[1])

    @njit(cache=False)
    def height_in_kernel(x, y, z):           # a compiled caller, as the dynamics uses it
        return ecef_to_geodetic_njit(x, y, z)[2]

    assert height_in_kernel(*r[1]) == h[1]


def test_enu_basis_matches_pymap3d_and_the_ellipsoid_normal():
    for lat_d, lon_d in [(0.0, 0.0), (28.5, -80.6), (-45.0, 170.0), (89.9999, 10.0), (90.0, 0.0)]:
        lat, lon = D(lat_d), D(lon_d)
        m = enu_basis(lat, lon)
        np.testing.assert_allclose(m @ m.T, np.eye(3), atol=1e-15)
        assert np.linalg.det(m) == pytest.approx(1.0, abs=1e-15)      # right-handed
        for row, enu in zip(m, np.eye(3)):
            np.testing.assert_allclose(row, pymap3d.enu2uvw(*enu, lat, lon, deg=False), atol=1e-15)
        # "up" is the direction in which the geodetic height grows
        r0 = geodetic_to_ecef(lat, lon, 0.0)
        np.testing.assert_allclose(geodetic_to_ecef(lat, lon, 1.0) - r0, m[2], atol=1e-8)


def test_somigliana_normal_gravity_at_equator_and_poles():
    assert normal_gravity(0.0) == pytest.approx(9.7803253359, abs=1e-10)
    assert normal_gravity(math.pi / 2) == pytest.approx(9.8321849378, abs=1e-9)
    assert normal_gravity(-math.pi / 2) == pytest.approx(9.8321849378, abs=1e-9)
    g = normal_gravity(np.radians([0.0, 45.0, 90.0]))
    assert g.shape == (3,) and np.all(np.diff(g) > 0)
