"""The solar-system state API: shapes, centres, vectorisation, and Mars's
oppositions 2025-2031 checked with an independent ephemeris.

References:
* Mars oppositions (published, e.g. the Astronomical Almanac / Meeus's
  tables of oppositions): 2025 January 16, 2027 February 19, 2029 March 25,
  2031 May 4.
* ERFA ``eraEpv00`` (Earth) and ``eraPlan94`` (Mars, Simon et al. 1994),
  used only in tests, for the elongation at each computed opposition.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from rocketsim.constants import ARCSEC
from rocketsim.ephemeris import elp2000, solar_system, vsop87
from rocketsim.timescales import calendar_jd

EPS0 = 84381.448 * ARCSEC    # J2000 mean obliquity (Lieske et al. 1977)
JD = calendar_jd(2026, 11, 26.5)


def _ecliptic_longitude(r):
    """J2000 ecliptic longitude of J2000 equatorial vectors (..., 3)."""
    r = np.asarray(r)
    return np.arctan2(r[..., 1] * math.cos(EPS0) + r[..., 2] * math.sin(EPS0), r[..., 0])


def _wrap(angle):
    return (angle + math.pi) % (2 * math.pi) - math.pi


def test_shapes_scalar_and_vector():
    r, v = solar_system.state("mars", JD)
    assert r.shape == (3,) and v.shape == (3,)
    jds = JD + np.arange(5) * 3.3
    rs, vs = solar_system.state("mars", jds, center="earth")
    assert rs.shape == (5, 3) and vs.shape == (5, 3)
    for k, jd in enumerate(jds):
        r1, v1 = solar_system.state("mars", jd, center="earth")
        assert np.array_equal(r1, rs[k]) and np.array_equal(v1, vs[k])


def test_centres_are_consistent():
    field = solar_system.states(JD, center="earth")
    assert set(field) == {"sun", "earth", "moon", "mars"}
    assert not field["earth"][0].any() and not field["earth"][1].any()
    r_sun, v_sun = solar_system.state("sun", JD, center="earth")
    r_earth, v_earth = vsop87.heliocentric_state("earth", JD)
    assert np.allclose(r_sun, -r_earth, rtol=0, atol=1e-3)
    assert np.allclose(field["sun"][0], r_sun, rtol=0, atol=1e-3)
    r_moon, v_moon = elp2000.geocentric_state(JD)
    assert np.allclose(field["moon"][0], r_moon, rtol=0, atol=1e-3)
    assert np.allclose(field["moon"][1], v_moon, rtol=0, atol=1e-9)
    # the Moon about the Sun is the Earth about the Sun plus the Moon about the Earth
    r_ms, v_ms = solar_system.state("moon", JD, center="sun")
    assert np.allclose(r_ms, r_earth + r_moon, rtol=0, atol=1e-3)
    assert np.allclose(v_ms, v_earth + v_moon, rtol=0, atol=1e-9)
    # swapping body and centre negates the vector
    a = solar_system.state("mars", JD, center="moon")
    b = solar_system.state("moon", JD, center="mars")
    assert np.allclose(a[0], -b[0], rtol=0, atol=1e-3) and np.allclose(a[1], -b[1], rtol=0, atol=1e-9)


def test_states_vectorised():
    jds = JD + np.linspace(0.0, 400.0, 7)
    field = solar_system.states(jds, center="mars")
    assert field["earth"][0].shape == (7, 3)
    r, _ = solar_system.state("earth", jds, center="mars")
    assert np.array_equal(field["earth"][0], r)


def test_magnitudes_are_physical():
    # Earth-Sun 0.983-1.017 au, Moon 356 000-407 000 km, Mars-Sun 1.38-1.67 au.
    jds = JD + np.linspace(0.0, 800.0, 41)
    field = solar_system.states(jds, center="sun")
    au = 1.495978707e11
    assert np.all(np.abs(np.linalg.norm(field["earth"][0], axis=1) / au - 1.0) < 0.0175)
    geo = field["moon"][0] - field["earth"][0]
    assert np.all((np.linalg.norm(geo, axis=1) > 356e6) & (np.linalg.norm(geo, axis=1) < 407e6))
    mars = np.linalg.norm(field["mars"][0], axis=1) / au
    assert np.all((mars > 1.38) & (mars < 1.67))


def test_unknown_body_is_refused():
    with pytest.raises(ValueError, match="venus"):
        solar_system.state("venus", JD)
    with pytest.raises(ValueError, match="pluto"):
        solar_system.states(JD, center="pluto")


def _opposition_offset(jd):
    field = solar_system.states(jd, center="earth")
    return _wrap(_ecliptic_longitude(field["mars"][0]) - _ecliptic_longitude(field["sun"][0]) - math.pi)


def test_mars_oppositions_2025_2031():
    erfa = pytest.importorskip("erfa")
    days = np.arange(calendar_jd(2025, 1, 1.0), calendar_jd(2032, 1, 1.0), 1.0)
    offset = _opposition_offset(days)
    crossings = np.flatnonzero((np.sign(offset[:-1]) != np.sign(offset[1:]))
                               & (np.abs(offset[:-1]) < 1.0))
    found = [brentq(_opposition_offset, days[i], days[i + 1], xtol=1e-7) for i in crossings]
    published = [calendar_jd(2025, 1, 16.0), calendar_jd(2027, 2, 19.0),
                 calendar_jd(2029, 3, 25.0), calendar_jd(2031, 5, 4.0)]
    assert len(found) == 4
    for jd, day in zip(found, published):
        assert day <= jd < day + 1.0                 # on the published day
        earth, _ = erfa.epv00(jd, 0.0)
        mars = erfa.plan94(jd, 0.0, 4)
        elongation = _ecliptic_longitude(mars["p"] - earth["p"]) - _ecliptic_longitude(-earth["p"])
        # 180.00 deg +- 0.04 deg at each computed opposition (docs/physics.md#ephemerides)
        # (measured with ERFA: 179.994, 179.999, 180.005, 179.998 deg).
        assert abs(math.degrees(elongation % (2 * math.pi)) - 180.0) < 0.04
