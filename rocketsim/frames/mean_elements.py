"""Kozai's first-order J2 mean elements <-> osculating elements.

Mean elements are the osculating elements less their short-period J2 terms,
those terms taken with zero average over the mean anomaly (Kozai, "The
motion of a close earth satellite", Astron. J. 64, 367, 1959; first order in
J2). They are the elements whose secular J2 rates (the nodal regression of
:mod:`rocketsim.bodies.sun_synchronous`, the apsidal and mean-motion rates)
describe the orbit's long-term motion; an osculating element carries on top
a twice-per-revolution ripple (for a circular orbit the osculating
semi-major axis is ``a + (3/2) J2 R^2/a sin^2 i cos 2u``, about 9 km at the
node of a 700 km sun-synchronous orbit, ``u`` the argument of latitude).

The short-period terms are computed by quadrature rather than from the
closed-form series: Gauss's variational equations (Vallado, *Fundamentals of
Astrodynamics and Applications*, 4th ed., eqs. 9-24) with the J2
acceleration in radial, along-track and cross-track axes

    a_R = -(k/2) (1 - 3 sin^2 i sin^2 u),   a_S = -k sin^2 i sin u cos u,
    a_W = -k sin i cos i sin u,              k = 3 mu J2 R^2 / r^4

are evaluated along the mean ellipse at :data:`SAMPLES` mean anomalies, their
orbit averages (the secular rates) removed, and the remainder integrated over
the mean anomaly as a Fourier series (FFT), so the periodic terms are exact to
rounding for the sampled ellipse. The mean longitude also takes the change of
the Keplerian mean motion with the rippling semi-major axis,
``-(3/2) (n/a) delta_a``. They are carried in the elements ``a, i, raan,
e cos w, e sin w, M + w``, regular for circular orbits. For a circular orbit
they reproduce Kozai's (and Brouwer's) closed forms for ``a`` and ``i``
(checked in the tests).

Units: m, rad; ``mu`` (m^3/s^2), ``radius`` (m, the J2 reference radius) and
``j2`` of the central body.
"""

from __future__ import annotations

import math
import struct

import numpy as np

from rocketsim.constants import EARTH_J2, EARTH_MU, EARTH_RADIUS_EQ
from rocketsim.frames.elements import (Elements, elements_to_state, mean_anomaly, state_to_elements,
                                       true_anomaly)

SAMPLES = 256          # mean anomalies per revolution for the short-period quadrature
_ITERATIONS = 8        # osculating -> mean fixed-point iterations (each gains a factor ~J2)
_TWO_PI = 2.0 * math.pi


def _regular(el: Elements) -> np.ndarray:
    """``(a, i, raan, e cos w, e sin w, M + w)`` of classical elements."""
    m = mean_anomaly(el.nu, el.e)
    return np.array([el.a, el.i, el.raan, el.e * math.cos(el.argp), el.e * math.sin(el.argp), m + el.argp])


def _classical(x: np.ndarray, mu: float) -> Elements:
    """Classical elements of ``(a, i, raan, e cos w, e sin w, M + w)``; ``argp = 0`` when circular."""
    a, i, raan, xi, zeta, lam = (float(v) for v in x)
    e = math.hypot(xi, zeta)
    argp = math.atan2(zeta, xi) if e > 0.0 else 0.0
    nu = float(true_anomaly(lam - argp, e))
    return Elements(a=a, e=e, i=i, raan=raan % _TWO_PI, argp=argp % _TWO_PI, nu=nu % _TWO_PI, mu=mu)


def _short_period(x: np.ndarray, mu: float, radius: float, j2: float) -> np.ndarray:
    """Short-period J2 terms (zero mean over the mean anomaly) of the regular elements,
    at the mean anomaly of the mean elements ``x``."""
    a, i, _, xi, zeta, lam = (float(v) for v in x)
    argp, terms = _periodic_terms(a, i, xi, zeta, mu, radius, j2)
    return np.real((terms * np.exp(1j * _HARMONICS * (lam - argp))).sum(axis=1))


_HARMONICS = np.fft.fftfreq(SAMPLES, 1.0 / SAMPLES)
_HARMONICS[0] = 1.0                                     # (the mean, removed by _series)
_HARMONICS.flags.writeable = False


_KEPT = 16              # ellipses whose series are kept (a guidance evaluates one at many points)
_SERIES: dict[bytes, tuple[float, np.ndarray]] = {}     # by the bits of the ellipse's figures


def _periodic_terms(a: float, i: float, xi: float, zeta: float, mu: float, radius: float,
                    j2: float) -> tuple[float, np.ndarray]:
    """:func:`_series` of the ellipse, kept for the last _KEPT ellipses (by the bits of
    their figures: a zero's sign can turn the argument of periapsis by 2 pi)."""
    key = struct.pack("7d", a, i, xi, zeta, mu, radius, j2)
    found = _SERIES.get(key)
    if found is None:
        if len(_SERIES) >= _KEPT:
            _SERIES.pop(next(iter(_SERIES)), None)
        found = _SERIES[key] = _series(a, i, xi, zeta, mu, radius, j2)
    return found


def _series(a: float, i: float, xi: float, zeta: float, mu: float, radius: float,
            j2: float) -> tuple[float, np.ndarray]:
    """``(argp, terms)``: the argument of periapsis of the mean ellipse ``a, i, e cos w,
    e sin w`` and the Fourier coefficients over ``M + w - argp`` (a row for each of the
    regular elements ``a, i, raan, e cos w, e sin w, M + w``, a column for each harmonic,
    numpy's FFT order) of their short-period terms: the shape of the ellipse alone sets
    them."""
    e = math.hypot(xi, zeta)
    argp = math.atan2(zeta, xi) if e > 0.0 else 0.0
    m = _TWO_PI * np.arange(SAMPLES) / SAMPLES
    f = true_anomaly(m, e)
    eta = math.sqrt(1.0 - e * e)
    p = a * eta * eta
    h = math.sqrt(mu * p)
    n = math.sqrt(mu / a**3)
    r = p / (1.0 + e * np.cos(f))
    u = argp + f
    su, cu, si, ci = np.sin(u), np.cos(u), math.sin(i), math.cos(i)
    k = 3.0 * mu * j2 * radius**2 / r**4
    acc_r = -0.5 * k * (1.0 - 3.0 * si * si * su * su)
    acc_s = -k * si * si * su * cu
    acc_w_per_si = -k * ci * su                         # a_W / sin i, regular at i = 0
    sf, cf = np.sin(f), np.cos(f)
    da = 2.0 * a * a / h * (e * sf * acc_r + p / r * acc_s)
    de = (p * sf * acc_r + ((p + r) * cf + r * e) * acc_s) / h
    di = r * cu * si * acc_w_per_si / h
    draan = r * su * acc_w_per_si / h
    e_dw = (-p * cf * acc_r + (p + r) * sf * acc_s) / h - e * ci * draan     # e dw/dt
    cw, sw = math.cos(argp), math.sin(argp)
    dxi = de * cw - e_dw * sw
    dzeta = de * sw + e_dw * cw
    dlam = (-2.0 * eta * r * acc_r - e / (1.0 + eta) * (p * cf * acc_r - (p + r) * sf * acc_s)) / h \
        - ci * draan

    def periodic(rate):
        coeff = np.fft.fft(rate) / SAMPLES / (1j * _HARMONICS * n)
        coeff[0] = 0.0
        return coeff

    a_coeff = periodic(da)
    dlam = dlam - 1.5 * n / a * np.real(np.fft.ifft(a_coeff * SAMPLES))   # mean motion of the ripple
    terms = np.array([a_coeff] + [periodic(rate) for rate in (di, draan, dxi, dzeta, dlam)])
    terms.flags.writeable = False
    return argp, terms


def mean_to_osculating(mean: Elements, radius: float = EARTH_RADIUS_EQ, j2: float = EARTH_J2) -> Elements:
    """Osculating elements of Kozai mean elements ``mean`` (its ``nu`` the mean ellipse's
    true anomaly) about a body of ``mean.mu``, J2 reference ``radius`` (m) and ``j2``."""
    x = _regular(mean)
    return _classical(x + _short_period(x, mean.mu, radius, j2), mean.mu)


def osculating_to_mean(osculating: Elements, radius: float = EARTH_RADIUS_EQ,
                       j2: float = EARTH_J2) -> Elements:
    """Kozai mean elements of the osculating elements (the inverse of
    :func:`mean_to_osculating`, by fixed-point iteration to rounding)."""
    target = _regular(osculating)
    x = target.copy()
    for _ in range(_ITERATIONS):
        step = target - _short_period(x, osculating.mu, radius, j2)
        step[5] = x[5] + math.remainder(step[5] - x[5], _TWO_PI)
        step[2] = x[2] + math.remainder(step[2] - x[2], _TWO_PI)
        x = step
    return _classical(x, osculating.mu)


def mean_elements_of_state(r, v, mu: float = EARTH_MU, radius: float = EARTH_RADIUS_EQ,
                           j2: float = EARTH_J2) -> Elements:
    """Kozai mean elements of the inertial state ``r`` (m), ``v`` (m/s)."""
    return osculating_to_mean(state_to_elements(r, v, mu), radius, j2)


def state_of_mean_elements(mean: Elements, radius: float = EARTH_RADIUS_EQ, j2: float = EARTH_J2):
    """Inertial ``(r, v)`` (m, m/s) of Kozai mean elements."""
    osc = mean_to_osculating(mean, radius, j2)
    return elements_to_state(osc.a, osc.e, osc.i, osc.raan, osc.argp, osc.nu, osc.mu)
