"""IAU WGCCRE 2015 orientation of the Moon and Mars against independent facts.

References:
* IAU WGCCRE 2009 report (Archinal et al. 2011), Mars pole
  alpha0 = 317.68143 - 0.1061 T, delta0 = 52.88650 - 0.0609 T (deg): the 2015
  model with its periodic terms must land on the same pole (Kuchynka et al.
  2014 refit the same spacecraft data); 0.41 deg / 1.55 deg apart without them.
* NASA Mars Fact Sheet (Williams, NSSDCA): obliquity to orbit 25.19 deg;
  length of the solar day 24.6597 h (88 775.2 s).
* Cassini's laws with the Moon's equator inclined I = 1.543 deg to the
  ecliptic (Eckhardt 1981; Explanatory Supplement 1992, 1 deg 32' 33").
* The Moon's optical librations: at most ~7.9 deg in longitude and ~6.9 deg
  in latitude, about a mean sub-Earth point at (0, 0) in the IAU "mean Earth"
  frame (Explanatory Supplement 1992, ch. 4; Meeus 1998, ch. 53).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from rocketsim.bodies import orientation
from rocketsim.constants import DAYS_PER_JULIAN_CENTURY, J2000_JD, MOON_J2, MOON_MU, MOON_RADIUS
from rocketsim.ephemeris import precession, solar_system
from rocketsim.timescales import calendar_jd


def _angle(a, b):
    return np.degrees(np.arccos(np.clip(np.sum(a * b, axis=-1), -1.0, 1.0)))


def test_rotation_is_orthonormal_with_pole_as_z():
    jds = np.linspace(calendar_jd(1960, 1, 1.0), calendar_jd(2090, 1, 1.0), 50)
    for body in orientation.BODIES:
        m = orientation.body_to_j2000(body, jds)
        eye = np.einsum("nij,nkj->nik", m, m)
        assert np.abs(eye - np.eye(3)).max() < 1e-14
        assert np.allclose(np.linalg.det(m), 1.0)
        assert np.allclose(m[:, :, 2], orientation.pole(body, jds), atol=1e-15)


def test_mars_2015_pole_agrees_with_the_2009_pole():
    for jd in (J2000_JD, calendar_jd(2030, 1, 1.0), calendar_jd(2060, 1, 1.0)):
        T = (jd - J2000_JD) / DAYS_PER_JULIAN_CENTURY
        alpha, delta, _ = orientation.pole_and_meridian("mars", jd)
        assert abs(math.degrees(alpha) - (317.68143 - 0.1061 * T)) < 0.01
        assert abs(math.degrees(delta) - (52.88650 - 0.0609 * T)) < 0.01


def test_mars_obliquity_to_its_orbit():
    jd = calendar_jd(2026, 1, 1.0)
    r, v = solar_system.state("mars", jd)
    normal = np.cross(r, v)
    normal /= np.linalg.norm(normal)
    assert abs(_angle(normal, orientation.pole("mars", jd)) - 25.19) < 0.02


def test_mars_solar_day():
    # Mean solar day from W and the Sun's direction: sample once per
    # sidereal day over ten Mars orbits (686.98 d each) and count how many
    # turns the sub-solar longitude gained (the Sun moves east along the
    # orbit): solar days = sidereal days - turns.
    start = calendar_jd(2026, 1, 1.0)
    sidereal_day = 360.0 / orientation.MARS_PM[1]                  # days
    n = round(10 * 686.98 / sidereal_day)
    jds = start + np.arange(n + 1) * sidereal_day
    sun, _ = solar_system.state("sun", jds, center="mars")
    body = np.einsum("nji,nj->ni", orientation.body_to_j2000("mars", jds), sun)
    lon = np.unwrap(np.arctan2(body[:, 1], body[:, 0]))
    turns = (lon[-1] - lon[0]) / (2 * math.pi)
    solar_day = (jds[-1] - jds[0]) / (n - turns) * 86400.0
    assert abs(solar_day - 88775.2) < 1.0


def test_moon_equator_is_inclined_1_54_deg_to_the_ecliptic():
    # Cassini's third law: the pole turns about the ecliptic pole at 1.543
    # deg. Over one 18.6-year cycle (every 1.3 days) the mean angle must be
    # 1.543 deg; the smaller libration terms move it by a few hundredths.
    jds = np.arange(calendar_jd(2025, 1, 1.0), calendar_jd(2043, 8, 1.0), 1.3)
    ecliptic_pole = np.array([precession.ecliptic_of_date_to_j2000(jd)[0][:, 2] for jd in jds])
    angle = _angle(ecliptic_pole, orientation.pole("moon", jds))
    assert abs(angle.mean() - 1.543) < 0.005
    assert np.abs(angle - 1.543).max() < 0.05


def test_moon_librations_about_the_mean_earth_direction():
    # One 18.6-year nodal cycle sampled every 0.37 day.
    jds = np.arange(calendar_jd(2025, 1, 1.0), calendar_jd(2043, 8, 1.0), 0.37)
    earth, _ = solar_system.state("earth", jds, center="moon")
    body = np.einsum("nji,nj->ni", orientation.body_to_j2000("moon", jds), earth)
    lon = np.degrees(np.arctan2(body[:, 1], body[:, 0]))
    lat = np.degrees(np.arcsin(body[:, 2] / np.linalg.norm(body, axis=1)))
    assert 7.0 < np.abs(lon).max() < 8.2
    assert 6.4 < np.abs(lat).max() < 7.0
    assert abs(lon.mean()) < 0.3 and abs(lat.mean()) < 0.3


def test_moon_j2_about_its_own_pole():
    # On the pole axis J2 weakens gravity: a = -mu/r^2 (1 - 3 J2 (R/r)^2);
    # on the equator it strengthens it: a = -mu/r^2 (1 + 3/2 J2 (R/r)^2).
    jd = calendar_jd(2026, 11, 26.5)
    r = 2.0 * MOON_RADIUS
    k = MOON_J2 * (MOON_RADIUS / r) ** 2
    pole = orientation.pole("moon", jd)
    a_pole = orientation.gravity_j2000("moon", r * pole, jd)
    assert np.allclose(a_pole, -MOON_MU / r**2 * (1 - 3 * k) * pole, rtol=1e-12, atol=0)
    equator = orientation.body_to_j2000("moon", jd)[:, 0]
    a_eq = orientation.gravity_j2000("moon", r * equator, jd)
    assert np.allclose(a_eq, -MOON_MU / r**2 * (1 + 1.5 * k) * equator, rtol=1e-12, atol=0)


def test_unknown_body_is_refused():
    with pytest.raises(ValueError, match="venus"):
        orientation.body_to_j2000("venus", J2000_JD)
