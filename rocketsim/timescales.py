"""Time scales: Julian dates, UTC -> UT1 -> TT, Delta T and Greenwich sidereal time.

Three scales matter to the simulator and their names are kept apart on
purpose (mixing UT1 and TT rotates the solar system by 0.29 deg):

* **UTC** – what a user writes in a scenario (``2026-11-26T12:00:00Z``).
* **UT1** – Earth's rotation angle; ``UT1 = UTC + DUT1`` (DUT1 is zero unless
  a scenario gives it; |DUT1| < 0.9 s).
* **TT** – the ephemerides' time; ``TT = UT1 + Delta T`` with Delta T from the
  polynomials of Espenak & Meeus (NASA, *Five Millennium Canon of Solar
  Eclipses*, 2006).

Julian dates are carried as *two* floats, the day (``jd_day``, ending in .5)
and the fraction-free seconds of that day, wherever precision matters; a
single float64 Julian date resolves about 40 microseconds, which is enough for
the ephemerides. Functions take arguments named for their scale
(``jd_ut1``, ``jd_tt``) and the :class:`Epoch` object hands out each scale by
name, so code never converts implicitly.
"""

from __future__ import annotations

import datetime as _dt
import math
from dataclasses import dataclass

from rocketsim.constants import (
    DAYS_PER_JULIAN_CENTURY,
    J2000_JD,
    SECONDS_PER_DAY,
)

_UNIX_EPOCH_JD = 2440587.5   # Julian date of 1970-01-01T00:00:00 UTC


def julian_date(moment: _dt.datetime) -> tuple[float, float]:
    """Julian date of a datetime as ``(jd_at_0h, seconds_of_day)``.

    ``moment`` is read in the scale it is given in (naive datetimes are taken
    as UTC; aware ones are converted to UTC). The first number ends in .5 (the
    Julian date of the preceding midnight), the second is seconds since then.
    """
    if moment.tzinfo is not None:
        moment = moment.astimezone(_dt.timezone.utc).replace(tzinfo=None)
    midnight = moment.replace(hour=0, minute=0, second=0, microsecond=0)
    days = (midnight - _dt.datetime(1970, 1, 1)).days
    seconds = (moment - midnight).total_seconds()
    return _UNIX_EPOCH_JD + days, seconds


def calendar_jd(year: int, month: int, day: float) -> float:
    """Julian date of a Gregorian calendar date, day may carry a fraction.

    Meeus, *Astronomical Algorithms* (2nd ed.), eq. 7.1 (Gregorian calendar).
    """
    if month <= 2:
        year -= 1
        month += 12
    a = year // 100
    b = 2 - a + a // 4
    return math.floor(365.25 * (year + 4716)) + math.floor(30.6001 * (month + 1)) + day + b - 1524.5


def decimal_year(jd: float) -> float:
    """Decimal year of a Julian date (Julian years from J2000.0)."""
    return 2000.0 + (jd - J2000_JD) / 365.25


def delta_t(year: float) -> float:
    """Delta T = TT - UT1 in seconds for a decimal year.

    Espenak & Meeus polynomials (NASA/TP-2006-214141, section "Polynomial
    expressions for Delta T"), valid -1999..+3000; outside 1600..2150 they
    are extrapolations with growing uncertainty. For 2005-2050:
    ``62.92 + 0.32217 u + 0.005589 u^2``, ``u = year - 2000``.
    """
    y = year
    if y < -500.0 or y >= 2150.0:
        u = (y - 1820.0) / 100.0
        return -20.0 + 32.0 * u * u
    if y < 500.0:
        u = y / 100.0
        return (10583.6 - 1014.41 * u + 33.78311 * u**2 - 5.952053 * u**3
                - 0.1798452 * u**4 + 0.022174192 * u**5 + 0.0090316521 * u**6)
    if y < 1600.0:
        u = (y - 1000.0) / 100.0
        return (1574.2 - 556.01 * u + 71.23472 * u**2 + 0.319781 * u**3
                - 0.8503463 * u**4 - 0.005050998 * u**5 + 0.0083572073 * u**6)
    if y < 1700.0:
        t = y - 1600.0
        return 120.0 - 0.9808 * t - 0.01532 * t**2 + t**3 / 7129.0
    if y < 1800.0:
        t = y - 1700.0
        return 8.83 + 0.1603 * t - 0.0059285 * t**2 + 0.00013336 * t**3 - t**4 / 1174000.0
    if y < 1860.0:
        t = y - 1800.0
        return (13.72 - 0.332447 * t + 0.0068612 * t**2 + 0.0041116 * t**3
                - 0.00037436 * t**4 + 0.0000121272 * t**5 - 0.0000001699 * t**6
                + 0.000000000875 * t**7)
    if y < 1900.0:
        t = y - 1860.0
        return (7.62 + 0.5737 * t - 0.251754 * t**2 + 0.01680668 * t**3
                - 0.0004473624 * t**4 + t**5 / 233174.0)
    if y < 1920.0:
        t = y - 1900.0
        return -2.79 + 1.494119 * t - 0.0598939 * t**2 + 0.0061966 * t**3 - 0.000197 * t**4
    if y < 1941.0:
        t = y - 1920.0
        return 21.20 + 0.84493 * t - 0.076100 * t**2 + 0.0020936 * t**3
    if y < 1961.0:
        t = y - 1950.0
        return 29.07 + 0.407 * t - t**2 / 233.0 + t**3 / 2547.0
    if y < 1986.0:
        t = y - 1975.0
        return 45.45 + 1.067 * t - t**2 / 260.0 - t**3 / 718.0
    if y < 2005.0:
        t = y - 2000.0
        return (63.86 + 0.3345 * t - 0.060374 * t**2 + 0.0017275 * t**3
                + 0.000651814 * t**4 + 0.00002373599 * t**5)
    if y < 2050.0:
        t = y - 2000.0
        return 62.92 + 0.32217 * t + 0.005589 * t**2
    return -20.0 + 32.0 * ((y - 1820.0) / 100.0) ** 2 - 0.5628 * (2150.0 - y)


def gmst(jd_ut1_day: float, ut1_seconds: float = 0.0) -> float:
    """Greenwich mean sidereal time in radians, in [0, 2 pi).

    IAU 1982 (Aoki et al. 1982), the form in the Astronomical Almanac:
    ``GMST(0h UT1) = 24110.54841 + 8640184.812866 T + 0.093104 T^2 - 6.2e-6 T^3``
    seconds, ``T`` in Julian centuries of UT1 from J2000 at 0h, plus
    ``1.00273790935`` times the UT1 seconds of the day.

    ``jd_ut1_day`` is the Julian date (UT1) of 0h of the day (ending in .5);
    ``ut1_seconds`` the UT1 seconds since then. A whole Julian date in
    ``jd_ut1_day`` with ``ut1_seconds = 0`` also works, at float64 precision.
    """
    day0 = math.floor(jd_ut1_day - 0.5) + 0.5
    ut1_seconds = ut1_seconds + (jd_ut1_day - day0) * SECONDS_PER_DAY
    t = (day0 - J2000_JD) / DAYS_PER_JULIAN_CENTURY
    seconds = (24110.54841 + 8640184.812866 * t + 0.093104 * t * t - 6.2e-6 * t**3
               + 1.00273790935 * ut1_seconds)
    return (seconds % SECONDS_PER_DAY) / SECONDS_PER_DAY * 2.0 * math.pi


@dataclass(frozen=True)
class Epoch:
    """One instant, handed out in each time scale by name.

    Built from UTC (``Epoch.from_utc``); ``dut1`` is UT1 - UTC in seconds.
    Mission time ``t`` (seconds since this epoch) is added with
    :meth:`jd_tt` / :meth:`jd_ut1`, which return single-float Julian dates.
    """

    utc: _dt.datetime
    jd_utc_day: float
    utc_seconds: float
    dut1: float
    delta_t: float

    @classmethod
    def from_utc(cls, utc: _dt.datetime, dut1: float = 0.0) -> "Epoch":
        if utc.tzinfo is None:
            utc = utc.replace(tzinfo=_dt.timezone.utc)
        day, seconds = julian_date(utc)
        dt = delta_t(decimal_year(day + seconds / SECONDS_PER_DAY))
        return cls(utc, day, seconds, dut1, dt)

    def jd_ut1(self, t: float = 0.0) -> float:
        """Julian date, UT1, ``t`` seconds after the epoch."""
        return self.jd_utc_day + (self.utc_seconds + self.dut1 + t) / SECONDS_PER_DAY

    def jd_tt(self, t: float = 0.0) -> float:
        """Julian date, TT, ``t`` seconds after the epoch."""
        return self.jd_utc_day + (self.utc_seconds + self.dut1 + self.delta_t + t) / SECONDS_PER_DAY

    def gmst(self, t: float = 0.0) -> float:
        """Greenwich mean sidereal time (rad) ``t`` seconds after the epoch."""
        return gmst(self.jd_utc_day, self.utc_seconds + self.dut1 + t)

    def utc_at(self, t: float) -> _dt.datetime:
        """UTC datetime ``t`` seconds after the epoch (leap seconds ignored)."""
        return self.utc + _dt.timedelta(seconds=t)
