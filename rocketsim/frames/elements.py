"""Classical orbital elements <-> inertial state vector.

Elements are those of Vallado, *Fundamentals of Astrodynamics and
Applications* (4th ed., sec. 2.5-2.6, algorithms 9 and 10): semi-major axis
``a`` (m; negative for a hyperbola, infinite for a parabola), eccentricity
``e``, inclination ``i``, right ascension (longitude) of the ascending node
``raan``, argument of periapsis ``argp`` and true anomaly ``nu`` (rad), all
measured in the frame of ``r`` and ``v`` (ECI for Earth: equator and ``x``).

Degenerate orbits get fixed conventions so that a round trip
``elements_to_state(*state_to_elements(r, v, mu))`` always returns the state:

* circular (``e < CIRCULAR_ECCENTRICITY``): ``argp = 0``, so ``nu`` is the argument of
  latitude (from the ascending node);
* equatorial (``sin i < SIN_I_EQUATORIAL``): ``raan = 0``, the node line is
  the ``x`` axis, so ``argp`` is the longitude of periapsis (measured in the
  direction of motion) and ``argp + nu`` the true longitude;
* circular and equatorial: ``raan = argp = 0`` and ``nu`` is the true
  longitude.

Angles ``raan``, ``argp``, ``nu`` are returned in [0, 2 pi); ``i`` in [0, pi].
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass

import numpy as np

from rocketsim.jit import njit
from rocketsim.constants import EARTH_MU

CIRCULAR_ECCENTRICITY = 1e-11        # below this eccentricity an orbit is treated as circular
SIN_I_EQUATORIAL = 1e-11  # below this sin(i) an orbit is treated as equatorial
_TWO_PI = 2.0 * math.pi


@njit(inline="always")
def _wrap(angle):
    """Angle in [0, 2 pi)."""
    w = angle % _TWO_PI
    return 0.0 if w >= _TWO_PI else w


@dataclass(frozen=True)
class Elements:
    """Classical orbital elements, SI units (m, rad) about a body of parameter ``mu``.

    ``p`` (semi-latus rectum, m) is carried because it stays finite for a
    parabola, whose ``a`` is infinite; left as nan it is computed from
    ``a (1 - e^2)``.
    """

    a: float
    e: float
    i: float
    raan: float
    argp: float
    nu: float
    mu: float = EARTH_MU
    p: float = math.nan

    def __post_init__(self):
        if math.isnan(self.p):
            object.__setattr__(self, "p", self.a * (1.0 - self.e * self.e))

    @property
    def periapsis(self) -> float:
        """Periapsis radius (m), ``p / (1 + e)``."""
        return self.p / (1.0 + self.e)

    @property
    def apoapsis(self) -> float:
        """Apoapsis radius (m), ``p / (1 - e)``; infinite unless elliptic."""
        return self.p / (1.0 - self.e) if self.e < 1.0 else math.inf

    @property
    def period(self) -> float:
        """Orbital period (s), ``2 pi sqrt(a^3 / mu)``; infinite unless elliptic."""
        return _TWO_PI * math.sqrt(self.a**3 / self.mu) if self.e < 1.0 else math.inf

    @property
    def arglat(self) -> float:
        """Argument of latitude ``u = argp + nu`` (rad, [0, 2 pi)), from the node."""
        return _wrap(self.argp + self.nu)

    @property
    def true_longitude(self) -> float:
        """True longitude ``raan + argp + nu`` (rad, [0, 2 pi)).

        Measured from ``x`` to the node along the equator, then along the orbit
        (for a retrograde orbit this is not the geometric angle from ``x``).
        """
        return _wrap(self.raan + self.argp + self.nu)

    def as_dict(self) -> dict[str, float]:
        """All elements and derived quantities as plain floats (SI).

        ``apoapsis`` and ``period`` are ``inf`` for open orbits, and ``a`` for
        a parabola; ``json.dumps`` writes them as ``Infinity``.
        """
        d = {k: float(v) for k, v in asdict(self).items()}
        d.update(
            periapsis=float(self.periapsis),
            apoapsis=float(self.apoapsis),
            period=float(self.period),
            arglat=float(self.arglat),
            true_longitude=float(self.true_longitude),
        )
        return d


# inlined (numba IR) into elements_tuple, its one compiled caller: no kernel of its own
@njit(inline="always")
def _angle_about(u0, u1, u2, w0, w1, w2, a0, a1, a2):
    """Angle (rad) from ``u`` to ``w``, positive right-handed about unit ``axis`` ``a``:
    ``atan2(a . (u x w), u . w)``."""
    c0 = u1 * w2 - u2 * w1
    c1 = u2 * w0 - u0 * w2
    c2 = u0 * w1 - u1 * w0
    return math.atan2(a0 * c0 + a1 * c1 + a2 * c2, u0 * w0 + u1 * w1 + u2 * w2)


@njit(inline="always")
def elements_tuple(r, v, mu):
    """``(a, e, i, raan, argp, nu, p)`` of the state ``r`` (m), ``v`` (m/s), compiled.

    Vallado's RV2COE (algorithm 9) with every angle taken by ``atan2`` in the
    orbit plane, so it is well conditioned near 0 and pi, and the conventions
    of this module for circular and equatorial orbits. The compiled core of
    :func:`state_to_elements`, for kernels and telemetry. Written on components
    (the products and sums of ``np.dot`` and ``np.cross`` on 3-vectors, in their
    order, so the same bits): numba compiles no array routine for it.
    """
    r0, r1, r2 = r[0], r[1], r[2]
    v0, v1, v2_ = v[0], v[1], v[2]
    rn = math.sqrt(r0 * r0 + r1 * r1 + r2 * r2)
    v2 = v0 * v0 + v1 * v1 + v2_ * v2_
    h0 = r1 * v2_ - r2 * v1                   # h = r x v
    h1 = r2 * v0 - r0 * v2_
    h2 = r0 * v1 - r1 * v0
    hn = math.sqrt(h0 * h0 + h1 * h1 + h2 * h2)
    hh0, hh1, hh2 = h0 / hn, h1 / hn, h2 / hn
    c = v2 - mu / rn
    rv = r0 * v0 + r1 * v1 + r2 * v2_
    e0 = (c * r0 - rv * v0) / mu              # the eccentricity vector
    e1 = (c * r1 - rv * v1) / mu
    e2 = (c * r2 - rv * v2_) / mu
    e = math.sqrt(e0 * e0 + e1 * e1 + e2 * e2)
    p = hn * hn / mu
    energy = 0.5 * v2 - mu / rn
    a = -mu / (2.0 * energy) if energy != 0.0 else math.inf
    i = math.atan2(math.hypot(h0, h1), h2)

    n0, n1, n2 = -h1, h0, 0.0                 # z x h
    node_n = math.sqrt(n0 * n0 + n1 * n1 + n2 * n2)
    if node_n < SIN_I_EQUATORIAL * hn:
        raan = 0.0
        nh0, nh1, nh2 = 1.0, 0.0, 0.0
    else:
        nh0, nh1, nh2 = n0 / node_n, n1 / node_n, n2 / node_n
        raan = math.atan2(nh1, nh0)
    if e < CIRCULAR_ECCENTRICITY:
        argp = 0.0
        ph0, ph1, ph2 = nh0, nh1, nh2
    else:
        ph0, ph1, ph2 = e0 / e, e1 / e, e2 / e
        argp = _angle_about(nh0, nh1, nh2, ph0, ph1, ph2, hh0, hh1, hh2)
    nu = _angle_about(ph0, ph1, ph2, r0, r1, r2, hh0, hh1, hh2)
    return a, e, i, _wrap(raan), _wrap(argp), _wrap(nu), p


def state_to_elements(r, v, mu: float = EARTH_MU) -> Elements:
    """Classical elements of the state ``r`` (m), ``v`` (m/s) about a body of ``mu`` (m^3/s^2).

    See :func:`elements_tuple` for the method and the conventions.
    """
    a, e, i, raan, argp, nu, p = elements_tuple(np.asarray(r, dtype=float), np.asarray(v, dtype=float),
                                                float(mu))
    return Elements(a=a, e=e, i=i, raan=raan, argp=argp, nu=nu, mu=mu, p=p)


def _perifocal_to_inertial(i: float, raan: float, argp: float) -> np.ndarray:
    """Matrix ``R3(-raan) R1(-i) R3(-argp)`` whose columns are P, Q, W in inertial axes."""
    co, so = math.cos(raan), math.sin(raan)
    cw, sw = math.cos(argp), math.sin(argp)
    ci, si = math.cos(i), math.sin(i)
    return np.array([
        [co * cw - so * sw * ci, -co * sw - so * cw * ci, so * si],
        [so * cw + co * sw * ci, -so * sw + co * cw * ci, -co * si],
        [sw * si, cw * si, ci],
    ])


def elements_to_state(a, e, i, raan, argp, nu, mu: float = EARTH_MU):
    """Inertial ``(r, v)`` (m, m/s) of classical elements (m, rad) about ``mu`` (m^3/s^2).

    Vallado's COE2RV (algorithm 10). ``a`` is negative for a hyperbola; the
    parabola (``a`` infinite) is not accepted here. For the degenerate
    orbits pass the conventions of this module (see its docstring).
    """
    p = a * (1.0 - e * e)
    cn, sn = math.cos(nu), math.sin(nu)
    radius = p / (1.0 + e * cn)
    r_pqw = np.array([radius * cn, radius * sn, 0.0])
    s = math.sqrt(mu / p)
    v_pqw = np.array([-s * sn, s * (e + cn), 0.0])
    m = _perifocal_to_inertial(i, raan, argp)
    return m @ r_pqw, m @ v_pqw


def time_to_apoapsis(r, v, mu: float = EARTH_MU) -> float:
    """Time (s) until the next apoapsis of the state ``r`` (m), ``v`` (m/s); nan unless elliptic.

    Kepler's equation: ``t = (pi - M) / n`` wrapped to one period, with ``M``
    the mean anomaly. For a circular orbit it is the time to ``nu = pi``
    under this module's convention (half a revolution past the node).
    """
    el = state_to_elements(r, v, mu)
    if not el.e < 1.0:
        return math.nan
    n = math.sqrt(mu / el.a**3)
    return _wrap(math.pi - mean_anomaly(el.nu, el.e)) / n


def mean_anomaly(nu: float, e: float) -> float:
    """Mean anomaly (rad, in (-pi, pi]) of the true anomaly ``nu`` (rad) of an
    ellipse of eccentricity ``e``: the eccentric anomaly, then Kepler's equation."""
    half = 0.5 * nu
    ecc_anom = 2.0 * math.atan2(math.sqrt(1.0 - e) * math.sin(half), math.sqrt(1.0 + e) * math.cos(half))
    return ecc_anom - e * math.sin(ecc_anom)


def true_anomaly(mean_anom, e):
    """True anomaly (rad) of the mean anomaly ``mean_anom`` (rad; scalar or array) of an
    ellipse of eccentricity ``e``: Kepler's equation solved by Newton's method (30 passes at
    most; once a pass leaves every anomaly as it was, bit for bit, so would the rest)."""
    ecc = np.array(mean_anom, dtype=float) + e * np.sin(mean_anom)
    for _ in range(30):
        passed = ecc - (ecc - e * np.sin(ecc) - mean_anom) / (1.0 - e * np.cos(ecc))
        if passed.tobytes() == ecc.tobytes():
            break
        ecc = passed
    return 2.0 * np.arctan2(np.sqrt(1.0 + e) * np.sin(0.5 * ecc), np.sqrt(1.0 - e) * np.cos(0.5 * ecc))
