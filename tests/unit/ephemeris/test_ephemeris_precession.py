"""IAU 1976 precession (Lieske et al. 1977) and the ecliptic-of-date turn.

References:
* Meeus, *Astronomical Algorithms*, 2nd ed. (1998), example 21.b: theta
  Persei, J2000 alpha = 2h44m11.986s, delta = +49d13'42.48", proper motion
  +0.03425 s/yr, -0.0895"/yr, precessed rigorously to 2028 November 13.19 TD
  (JD 2462088.69): alpha = 2h46m11.331s, delta = +49d20'54.54".
* Lieske et al. 1977, general precession in longitude
  p_A = 5029.0966" T + 1.11113" T^2 - 0.000006" T^3.
* ERFA ``eraPmat76`` (the same IAU 1976 matrix), used only in tests.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from rocketsim.constants import ARCSEC, AU, DAYS_PER_JULIAN_CENTURY, J2000_JD
from rocketsim.ephemeris import precession, vsop87
from rocketsim.timescales import calendar_jd

EPS0 = 84381.448 * ARCSEC     # mean obliquity at J2000 (Lieske et al. 1977)


def test_meeus_example_21b_theta_persei():
    jd = 2462088.69
    years = (jd - J2000_JD) / 365.25                     # 28.86705 yr
    alpha0 = math.radians((2 + 44 / 60 + (11.986 + 0.03425 * years) / 3600) * 15)
    delta0 = math.radians(49 + 13 / 60 + (42.48 - 0.0895 * years) / 3600)
    u = np.array([math.cos(delta0) * math.cos(alpha0), math.cos(delta0) * math.sin(alpha0),
                  math.sin(delta0)])
    x, y, z = precession.precession_matrix(jd) @ u
    alpha = math.degrees(math.atan2(y, x)) / 15 * 3600     # seconds of time
    delta = math.degrees(math.asin(z)) * 3600               # arcseconds
    assert abs(alpha - (2 * 3600 + 46 * 60 + 11.331)) < 0.001
    assert abs(delta - (49 * 3600 + 20 * 60 + 54.54)) < 0.01


def test_matches_erfa_pmat76():
    erfa = pytest.importorskip("erfa")
    for jd in (calendar_jd(1950, 1, 1.0), calendar_jd(2026, 6, 1.0), calendar_jd(2100, 1, 1.0)):
        assert np.abs(precession.precession_matrix(jd) - erfa.pmat76(jd, 0.0)).max() < 1e-14


def test_ecliptic_of_date_turn_at_j2000_is_the_obliquity_rotation():
    # At J2000 the turn is only ecliptic -> equator by eps_0 = 23d26'21.448".
    m, _ = precession.ecliptic_of_date_to_j2000(J2000_JD)
    c, s = math.cos(EPS0), math.sin(EPS0)
    assert np.allclose(m, [[1, 0, 0], [0, c, -s], [0, s, c]], atol=1e-15)


def test_correction_is_about_036_deg_by_2026():
    # docs/physics.md#ephemerides: by 2026 the equinox-of-date -> J2000 correction is
    # 0.36 deg, some 950 000 km at the Earth. It is the general precession in
    # longitude p_A (Lieske 1977) for a body on the ecliptic.
    jd = calendar_jd(2026, 1, 1.0)
    T = (jd - J2000_JD) / DAYS_PER_JULIAN_CENTURY
    p_a = (5029.0966 * T + 1.11113 * T**2) * ARCSEC
    (lon_of_date, _, radius), _ = vsop87.heliocentric_lbr("earth", jd)
    r, _ = vsop87.heliocentric_state("earth", jd)
    lon_j2000 = math.atan2(r[1] * math.cos(EPS0) + r[2] * math.sin(EPS0), r[0])
    shift = (lon_of_date - lon_j2000 + math.pi) % (2 * math.pi) - math.pi
    assert abs(shift - p_a) < 2 * ARCSEC
    assert abs(math.degrees(shift) - 0.36) < 0.01            # 0.3632 deg
    assert 0.9e9 < shift * radius * AU < 1.0e9               # ~950 000 km


def test_rate_of_the_turn_is_its_derivative():
    # dM/dt against a centred difference of M (1 day step).
    jd = calendar_jd(2040, 3, 3.0)
    _, dm = precession.ecliptic_of_date_to_j2000(jd)
    fd = (precession.ecliptic_of_date_to_j2000(jd + 1.0)[0]
          - precession.ecliptic_of_date_to_j2000(jd - 1.0)[0]) / 2.0
    assert np.abs(dm - fd).max() < 1e-13 and np.abs(dm).max() > 1e-8
