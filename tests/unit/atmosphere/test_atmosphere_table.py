"""The 50 m table and its compiled lookup, against direct evaluation of the models.

Reference: the 1976 standard evaluated directly at each height
(:func:`us_standard_1976`, itself checked against the standard's tables and
the ``ussa1976`` package in test_atmosphere_ussa1976.py). Linear
interpolation of an exponential over 50 m rows has a worst relative error of
(dh/H)^2/8, 1.1e-5 for the smallest scale height below 600 km (5.5 km);
where the standard itself has a kink (the temperature gradient changes at
the layer bases) a row straddling it is off by up to (dh/4) x (change of
gradient): at the 11 km tropopause 12.5 m x 6.5 K/km = 0.081 K, 3.75e-4 of
216.65 K, and the same fraction of density. Measured worst: 3.1e-4 (density,
11.017 km).
"""

import numpy as np
import pytest

from rocketsim.atmosphere.day import standard_table
import pymap3d

from rocketsim.atmosphere.table import TOP, air_at, wind_earth_fixed
from rocketsim.atmosphere.ussa1976 import us_standard_1976


@pytest.fixture(scope="module")
def table():
    return standard_table()


def test_rows_are_50_m_from_below_sea_level_to_600_km(table):
    assert table.dh == 50.0
    assert table.h0 <= -500.0
    assert table.heights[-1] == pytest.approx(TOP)
    assert all(a.dtype == np.float64 for a in (table.density, table.wind_east))


def test_lookup_between_rows_matches_direct_evaluation(table):
    rng = np.random.default_rng(3)
    h = np.sort(np.concatenate((rng.uniform(0.0, TOP, 20_000),
                                rng.uniform(10_950.0, 11_100.0, 2_000))))   # across 11 km
    rho, p, t, a, we, wn = table.at(h)
    direct = us_standard_1976(h)
    np.testing.assert_allclose(rho, direct.density, rtol=3.8e-4)
    np.testing.assert_allclose(p, direct.pressure, rtol=3.8e-4)
    np.testing.assert_allclose(t, direct.temperature, rtol=3.8e-4)
    np.testing.assert_allclose(a, direct.speed_of_sound, rtol=3.8e-4)
    kinkless = np.abs(h - 11_019.0) > 100.0
    np.testing.assert_allclose(rho[kinkless], direct.density[kinkless], rtol=5e-5)
    smooth = (h > 1_000.0) & (h < 10_000.0)      # one layer: only the curvature error
    np.testing.assert_allclose(rho[smooth], direct.density[smooth], rtol=1.1e-5)
    assert not np.any(we) and not np.any(wn)


def test_no_air_above_600_km_and_clamped_below_the_table(table):
    rho, p, t, *_ = table.at([600_001.0, 900_000.0])
    assert np.all(rho == 0.0) and np.all(p == 0.0) and np.all(t > 900.0)
    below = table.at([table.h0 - 2_000.0])
    assert below[0][0] == table.density[0] and below[1][0] == table.pressure[0]
    assert all(np.isnan(v) for v in air_at(*table.arrays(), float("nan")))


def test_scalar_compiled_lookup_equals_the_vectorised_one(table):
    heights = np.array([-10.0, 0.0, 1234.5, 86_000.0, 599_999.0, 650_000.0])
    many = np.array(table.at(heights))
    for j, h in enumerate(heights):
        assert np.array_equal(np.array(air_at(*table.arrays(), h)), many[:, j])


@pytest.mark.parametrize("lat, lon", [(0.0, 0.0), (0.614, -1.703), (-1.2, 2.9)])
def test_wind_as_an_earth_fixed_vector(lat, lon):
    # Reference: pymap3d's ENU -> ECEF vector rotation (enu2uvw), an independent peer.
    expected = pymap3d.enu2uvw(3.0, -4.0, 0.0, lat, lon, deg=False)
    np.testing.assert_allclose(wind_earth_fixed(3.0, -4.0, lat, lon), expected, atol=1e-12)
