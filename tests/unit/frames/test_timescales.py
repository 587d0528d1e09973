"""Time scales against published worked examples and tables.

References:
* Meeus, *Astronomical Algorithms*, 2nd ed. (Willmann-Bell 1998): examples
  7.a (Julian date), the table of Julian dates in chapter 7, examples 12.a
  and 12.b (mean sidereal time at Greenwich).
* Espenak & Meeus, *Five Millennium Canon of Solar Eclipses* (NASA/TP-2006-
  214141) and the NASA eclipse web site's "Historical values of Delta T"
  table (values from Morrison & Stephenson 2004 and the observed record).
* IERS Bulletin A / USNO: observed Delta T at 2020.0 = 69.36 s.
"""

import datetime as dt
import math

import pytest

from rocketsim.constants import SECONDS_PER_DAY
from rocketsim.timescales import Epoch, calendar_jd, decimal_year, delta_t, gmst, julian_date


def _seconds_of_day(angle_rad):
    """Sidereal time as seconds of a sidereal day (24 h = 2 pi)."""
    return angle_rad / (2.0 * math.pi) * SECONDS_PER_DAY


def _hms(h, m, s):
    return 3600.0 * h + 60.0 * m + s


# --- Julian dates ------------------------------------------------------------

def test_meeus_example_7a_sputnik():
    # Meeus ex. 7.a: 1957 October 4.81 (launch of Sputnik 1) = JD 2436116.31.
    assert calendar_jd(1957, 10, 4.81) == pytest.approx(2436116.31, abs=1e-9)


@pytest.mark.parametrize("year, month, day, jd", [
    # Meeus, ch. 7, table of Gregorian dates and their Julian days.
    (2000, 1, 1.5, 2451545.0),
    (1999, 1, 1.0, 2451179.5),
    (1987, 1, 27.0, 2446822.5),
    (1987, 6, 19.5, 2446966.0),
    (1988, 1, 27.0, 2447187.5),
    (1988, 6, 19.5, 2447332.0),
    (1900, 1, 1.0, 2415020.5),
    (1600, 1, 1.0, 2305447.5),
    (1600, 12, 31.0, 2305812.5),
])
def test_meeus_chapter_7_table(year, month, day, jd):
    assert calendar_jd(year, month, day) == jd


def test_julian_date_of_datetime_is_two_part():
    # 2000-01-01T12:00 UTC is JD 2451545.0 (Meeus table above): day part
    # 2451544.5 (the preceding midnight) plus 43 200 s.
    day, seconds = julian_date(dt.datetime(2000, 1, 1, 12, 0, 0))
    assert (day, seconds) == (2451544.5, 43200.0)
    # Meeus ex. 7.a again, from a datetime: 1957-10-04 0.81 d = 19:26:24 UTC.
    day, seconds = julian_date(dt.datetime(1957, 10, 4, 19, 26, 24, tzinfo=dt.timezone.utc))
    assert day + seconds / SECONDS_PER_DAY == pytest.approx(2436116.31, abs=1e-9)
    # An aware datetime in another zone is converted to UTC first.
    plus2 = dt.timezone(dt.timedelta(hours=2))
    assert julian_date(dt.datetime(2000, 1, 1, 14, 0, 0, tzinfo=plus2)) == (2451544.5, 43200.0)


def test_decimal_year_of_j2000():
    # J2000.0 is 2000 January 1.5 = JD 2451545.0; a Julian year is 365.25 d.
    assert decimal_year(2451545.0) == 2000.0
    assert decimal_year(2451545.0 + 365.25 * 20) == pytest.approx(2020.0, abs=1e-12)


# --- Greenwich mean sidereal time -------------------------------------------

def test_meeus_example_12a_gmst_at_0h():
    # Meeus ex. 12.a: 1987 April 10, 0h UT (JD 2446895.5): 13h 10m 46.3668s.
    # Meeus quotes 4 decimals of a second; we hold half a unit of the last one.
    got = _seconds_of_day(gmst(2446895.5))
    assert got == pytest.approx(_hms(13, 10, 46.3668), abs=5e-5)


def test_meeus_example_12b_gmst_at_19h21m():
    # Meeus ex. 12.b: 1987 April 10, 19:21:00 UT: 8h 34m 57.0896s.
    got = _seconds_of_day(gmst(2446895.5, _hms(19, 21, 0)))
    assert got == pytest.approx(_hms(8, 34, 57.0896), abs=5e-5)
    # The same instant as one Julian date (2446896.30625) at float64 precision.
    got_single = _seconds_of_day(gmst(2446896.30625))
    assert got_single == pytest.approx(_hms(8, 34, 57.0896), abs=5e-5)


def test_epoch_gmst_matches_meeus_12b():
    epoch = Epoch.from_utc(dt.datetime(1987, 4, 10, 19, 0, 0))
    # 21 minutes of mission time later is Meeus's instant (UT1 = UTC here).
    assert _seconds_of_day(epoch.gmst(21 * 60.0)) == pytest.approx(_hms(8, 34, 57.0896), abs=5e-5)


# --- Delta T -----------------------------------------------------------------

@pytest.mark.parametrize("year, table, tol", [
    # NASA eclipse site, "Historical values of Delta T" (Espenak & Meeus):
    # whole seconds before 1955, tenths after. The polynomials are fits to
    # these, so they agree within the table's rounding plus the fit error.
    (1700, 9.0, 0.5),
    (1750, 13.0, 0.5),
    (1800, 14.0, 0.5),
    (1850, 7.0, 0.5),
    (1900, -3.0, 0.5),
    (1950, 29.0, 0.5),
    (1955, 31.1, 0.15),
    (1960, 33.2, 0.15),
    (1965, 35.7, 0.15),
    (1970, 40.2, 0.15),
    (1975, 45.5, 0.15),
    (1980, 50.5, 0.15),
    (1985, 54.3, 0.15),
    (1990, 56.9, 0.15),
    (1995, 60.8, 0.15),
    (2000, 63.8, 0.15),
    (2005, 64.7, 0.15),
])
def test_delta_t_matches_espenak_meeus_table(year, table, tol):
    assert delta_t(float(year)) == pytest.approx(table, abs=tol)


def test_delta_t_2020_vs_observed():
    # Espenak & Meeus predict 2005-2050 with 62.92 + 0.32217 u + 0.005589 u^2
    # (u = year - 2000): 71.60 s at 2020.0. The observed value (IERS/USNO) was
    # 69.36 s: the prediction is 2.2 s high, a known limit of the 2006 fit
    # that moves the ephemerides by ~1 arcsec of lunar longitude. This test
    # records both figures so a change of model shows up here.
    assert delta_t(2020.0) == pytest.approx(71.60, abs=0.005)
    assert delta_t(2020.0) - 69.36 == pytest.approx(2.24, abs=0.01)


@pytest.mark.parametrize("boundary", [1700, 1800, 1860, 1900, 1920, 1941, 1961, 1986, 2005, 2050, 2150])
def test_delta_t_pieces_meet(boundary):
    # Espenak & Meeus chose the pieces to join within a fraction of a second
    # (their polynomials section); a wrong coefficient breaks the join.
    jump = delta_t(boundary - 1e-9) - delta_t(float(boundary))
    assert abs(jump) < 0.2


def test_epoch_scales_differ_by_dut1_and_delta_t():
    utc = dt.datetime(2026, 11, 26, 12, 0, 0, tzinfo=dt.timezone.utc)
    epoch = Epoch.from_utc(utc, dut1=-0.1)
    # UT1 = UTC + DUT1; TT = UT1 + Delta T (Espenak & Meeus at the epoch's year).
    jd_utc = epoch.jd_utc_day + epoch.utc_seconds / SECONDS_PER_DAY
    assert (epoch.jd_ut1() - jd_utc) * SECONDS_PER_DAY == pytest.approx(-0.1, abs=1e-4)
    tt_minus_ut1 = (epoch.jd_tt(100.0) - epoch.jd_ut1(100.0)) * SECONDS_PER_DAY
    assert tt_minus_ut1 == pytest.approx(delta_t(decimal_year(jd_utc)), abs=1e-4)
    assert epoch.delta_t == pytest.approx(62.92 + 0.32217 * 26.9 + 0.005589 * 26.9**2, abs=0.01)
    # Mission time advances every scale together.
    assert (epoch.jd_tt(86400.0) - epoch.jd_tt(0.0)) == pytest.approx(1.0, abs=1e-9)
    assert epoch.utc_at(3600.0) == utc + dt.timedelta(hours=1)
