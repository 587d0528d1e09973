"""Classical orbital elements against textbook examples, Kepler's laws and an integrator.

References:
* Vallado, *Fundamentals of Astrodynamics and Applications*, 4th ed.,
  example 2-5 (RV2COE) and example 2-6 (COE2RV), mu = 398 600.4418 km^3/s^2.
  The book's printed digits differ from an exact float64 evaluation of the
  same formulas by up to 8 m in p, 24 m in position and 16 mm/s in velocity
  (independent implementations agree with ours, not with the last printed
  digit); those are the tolerances below, and the angles hold to the
  printed digits.
* Curtis, *Orbital Mechanics for Engineering Students*, 3rd ed., example 4.3
  (retrograde, RV -> elements) and example 4.7 (hyperbola, elements -> RV),
  mu = 398 600 km^3/s^2.
* Kepler's third law and the two-body geometry (periapsis p/(1+e),
  apoapsis p/(1-e), period 2 pi sqrt(a^3/mu)), and scipy's DOP853
  integrating the two-body problem for the time to apoapsis.
"""

import json
import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from rocketsim.constants import EARTH_MU, EARTH_RADIUS_EQ
from rocketsim.frames.elements import Elements, elements_to_state, state_to_elements, time_to_apoapsis

D = math.radians
KM = 1e3
MU_VALLADO = 398600.4418e9
MU_CURTIS = 398600.0e9


def _deg(x):
    return math.degrees(x)


def test_vallado_example_2_5_rv2coe():
    r = np.array([6524.834, 6862.875, 6448.296]) * KM
    v = np.array([4.901327, 5.533756, -1.976341]) * KM
    el = state_to_elements(r, v, MU_VALLADO)
    assert el.p / KM == pytest.approx(11067.790, abs=0.01)
    assert el.a / KM == pytest.approx(36127.343, abs=0.01)
    assert el.e == pytest.approx(0.832853, abs=1e-6)
    assert _deg(el.i) == pytest.approx(87.870, abs=1e-3)
    assert _deg(el.raan) == pytest.approx(227.898, abs=1e-3)
    assert _deg(el.argp) == pytest.approx(53.38, abs=0.01)
    assert _deg(el.nu) == pytest.approx(92.335, abs=1e-3)


def test_vallado_example_2_6_coe2rv():
    p, e = 11067.790 * KM, 0.83285
    r, v = elements_to_state(p / (1 - e * e), e, D(87.87), D(227.89), D(53.38), D(92.335), MU_VALLADO)
    np.testing.assert_allclose(r / KM, [6525.344, 6861.535, 6449.125], atol=0.03)
    np.testing.assert_allclose(v / KM, [4.902276, 5.533124, -1.975709], atol=2e-5)


def test_curtis_example_4_3_retrograde():
    r = np.array([-6045.0, -3490.0, 2500.0]) * KM
    v = np.array([-3.457, 6.618, 2.533]) * KM
    el = state_to_elements(r, v, MU_CURTIS)
    assert math.sqrt(el.p * MU_CURTIS) / 1e6 == pytest.approx(58310, abs=5)     # h, km^2/s
    assert _deg(el.i) == pytest.approx(153.2, abs=0.05)
    assert _deg(el.raan) == pytest.approx(255.3, abs=0.05)
    assert el.e == pytest.approx(0.1712, abs=5e-5)
    assert _deg(el.argp) == pytest.approx(20.07, abs=0.005)
    assert _deg(el.nu) == pytest.approx(28.45, abs=0.005)
    assert el.a / KM == pytest.approx(8788, abs=0.5)


def test_curtis_example_4_7_hyperbola():
    h, e = 80000.0e6, 1.4
    p = h * h / MU_CURTIS
    r, v = elements_to_state(p / (1 - e * e), e, D(30), D(40), D(60), D(30), MU_CURTIS)
    np.testing.assert_allclose(r / KM, [-4040, 4815, 3629], atol=0.5)
    # Curtis prints 4 significant figures
    assert v[0] / KM == pytest.approx(-10.39, abs=0.005)
    np.testing.assert_allclose(v[1:] / KM, [-4.772, 1.744], atol=5e-4)
    el = state_to_elements(r, v, MU_CURTIS)
    assert el.a < 0 and el.e == pytest.approx(1.4, abs=1e-12)
    assert el.apoapsis == math.inf and el.period == math.inf
    assert math.isnan(time_to_apoapsis(r, v, MU_CURTIS))


ORBITS = {
    # name: (a, e, i, raan, argp, nu), SI
    "inclined ellipse": (8000e3, 0.1, D(51.6), D(30), D(60), D(200)),
    "circular inclined": (6778e3, 0.0, D(51.6), D(120), 0.0, D(75)),
    "equatorial ellipse": (10000e3, 0.3, 0.0, 0.0, D(80), D(10)),
    "circular equatorial": (42164e3, 0.0, 0.0, 0.0, 0.0, D(300)),
    "retrograde equatorial ellipse": (9000e3, 0.2, math.pi, 0.0, D(45), D(100)),
    "retrograde circular equatorial": (7000e3, 0.0, math.pi, 0.0, 0.0, D(250)),
    "retrograde inclined": (7078e3, 0.001, D(98.2), D(300), D(90), D(5)),
    "polar": (7500e3, 0.05, D(90), D(10), D(350), D(359)),
    "hyperbola": (-20000e3, 1.5, D(28.5), D(200), D(100), D(-60) % (2 * math.pi)),
    "periapsis of a Molniya": (26600e3, 0.74, D(63.4), D(45), D(270), 0.0),
}


@pytest.mark.parametrize("name", ORBITS)
def test_round_trips(name):
    coe = ORBITS[name]
    r, v = elements_to_state(*coe, EARTH_MU)
    el = state_to_elements(r, v, EARTH_MU)
    # the elements come back (degenerate ones under the module's conventions)
    np.testing.assert_allclose([el.a, el.e], coe[:2], rtol=1e-11, atol=1e-12)
    for got, want in zip((el.i, el.raan, el.argp, el.nu), coe[2:]):
        assert math.remainder(got - want, 2 * math.pi) == pytest.approx(0.0, abs=2e-9)
    # and so does the state
    r2, v2 = elements_to_state(el.a, el.e, el.i, el.raan, el.argp, el.nu, EARTH_MU)
    # float64 rounding: measured <= 1e-8 m and 1e-11 m/s; held at 1 um, 1 nm/s
    np.testing.assert_allclose(r2, r, atol=1e-6)
    np.testing.assert_allclose(v2, v, atol=1e-9)


def test_nearly_degenerate_orbits_still_round_trip():
    # Tiny eccentricity or inclination just above the thresholds: the angles
    # are ill-defined individually, but the state must come back.
    for e, i in [(1e-10, D(51.6)), (0.01, 1e-10), (1e-10, 1e-10), (1e-13, D(10)), (0.2, 1e-14)]:
        r, v = elements_to_state(7000e3, e, i, D(33), D(44), D(55), EARTH_MU)
        el = state_to_elements(r, v, EARTH_MU)
        r2, v2 = elements_to_state(el.a, el.e, el.i, el.raan, el.argp, el.nu, EARTH_MU)
        np.testing.assert_allclose(r2, r, atol=1e-6)
        np.testing.assert_allclose(v2, v, atol=1e-9)
        assert el.true_longitude == pytest.approx(D(33 + 44 + 55), abs=1e-8)


def test_circular_and_equatorial_conventions():
    # circular: argp = 0, nu is the argument of latitude
    el = state_to_elements(*elements_to_state(6778e3, 0.0, D(51.6), D(120), D(30), D(45), EARTH_MU), EARTH_MU)
    assert el.argp == 0.0
    assert el.nu == pytest.approx(D(75), abs=1e-12) and el.arglat == pytest.approx(D(75), abs=1e-12)
    # equatorial prograde: raan = 0, argp is the longitude of periapsis
    el = state_to_elements(*elements_to_state(9000e3, 0.2, 0.0, D(100), D(20), D(10), EARTH_MU), EARTH_MU)
    assert el.raan == 0.0 and el.argp == pytest.approx(D(120), abs=1e-12)
    assert el.true_longitude == pytest.approx(D(130), abs=1e-12)
    # circular equatorial: only the true longitude survives, in nu
    r = np.array([0.0, -7000e3, 0.0])
    v = np.array([math.sqrt(EARTH_MU / 7000e3), 0.0, 0.0])
    el = state_to_elements(r, v, EARTH_MU)
    assert (el.raan, el.argp, el.i) == (0.0, 0.0, 0.0)
    assert el.nu == pytest.approx(D(270), abs=1e-12)
    assert el.true_longitude == pytest.approx(D(270), abs=1e-12)


def test_kepler_third_law_and_geometry():
    # A circular orbit 400 km up: v = sqrt(mu/r), T = 2 pi sqrt(r^3/mu).
    radius = EARTH_RADIUS_EQ + 400e3
    el = state_to_elements(np.array([radius, 0.0, 0.0]), np.array([0.0, 0.0, math.sqrt(EARTH_MU / radius)]))
    assert el.a == pytest.approx(radius, rel=1e-14)
    assert el.e < 1e-14
    assert el.i == pytest.approx(math.pi / 2, abs=1e-15)
    assert el.period == pytest.approx(2 * math.pi * math.sqrt(radius**3 / EARTH_MU), rel=1e-14)
    assert el.period / 60 == pytest.approx(92.56, abs=0.01)      # the familiar ~92.6 min LEO period
    # periapsis and apoapsis radii are |r| at nu = 0 and nu = pi
    a, e = 24400e3, 0.7
    rp, vp = elements_to_state(a, e, D(7), D(0), D(178), 0.0, EARTH_MU)
    ra, _ = elements_to_state(a, e, D(7), D(0), D(178), math.pi, EARTH_MU)
    el = state_to_elements(rp, vp, EARTH_MU)
    assert el.periapsis == pytest.approx(np.linalg.norm(rp), rel=1e-13)
    assert el.periapsis == pytest.approx(a * (1 - e), rel=1e-13)
    assert el.apoapsis == pytest.approx(np.linalg.norm(ra), rel=1e-13)
    assert el.apoapsis == pytest.approx(a * (1 + e), rel=1e-13)


def test_parabola():
    # Escape speed exactly: e = 1, a infinite, p = h^2/mu finite.
    radius = 7000e3
    r = np.array([radius, 0.0, 0.0])
    v = np.array([0.0, math.sqrt(2 * EARTH_MU / radius), 0.0])
    el = state_to_elements(r, v, EARTH_MU)
    assert el.e == pytest.approx(1.0, abs=1e-15)
    assert abs(el.a) > 1e15                     # inf, or huge from rounding in the energy
    assert el.p == pytest.approx(2 * radius, rel=1e-14)
    assert el.periapsis == pytest.approx(radius, rel=1e-14)
    assert el.apoapsis == math.inf
    assert Elements(a=math.inf, e=1.0, i=0.0, raan=0.0, argp=0.0, nu=0.0, p=2 * radius).periapsis == radius


def _two_body(t, y, mu):
    r = y[:3]
    return np.concatenate([y[3:], -mu * r / np.linalg.norm(r) ** 3])


@pytest.mark.parametrize("nu_deg", [0.0, 45.0, 179.0, 181.0, 300.0])
def test_time_to_apoapsis_against_an_integrator(nu_deg):
    a, e = 12000e3, 0.25
    r, v = elements_to_state(a, e, D(40), D(10), D(20), D(nu_deg), EARTH_MU)
    t = time_to_apoapsis(r, v, EARTH_MU)
    period = 2 * math.pi * math.sqrt(a**3 / EARTH_MU)
    assert 0.0 <= t < period
    sol = solve_ivp(_two_body, (0.0, t), np.concatenate([r, v]), method="DOP853",
                    rtol=1e-12, atol=1e-6, args=(EARTH_MU,))
    r_end, v_end = sol.y[:3, -1], sol.y[3:, -1]
    # at apoapsis the radius is a(1+e) and the radial velocity is zero
    assert np.linalg.norm(r_end) == pytest.approx(a * (1 + e), abs=1e-3)
    assert float(r_end @ v_end) / np.linalg.norm(r_end) == pytest.approx(0.0, abs=1e-6)
    if nu_deg == 0.0:
        assert t == pytest.approx(period / 2, rel=1e-14)


def test_as_dict_is_plain_json():
    el = state_to_elements(*elements_to_state(7000e3, 0.01, D(51.6), D(1), D(2), D(3), EARTH_MU), EARTH_MU)
    d = el.as_dict()
    assert set(d) >= {"a", "e", "i", "raan", "argp", "nu", "p", "periapsis", "apoapsis", "period",
                      "arglat", "true_longitude"}
    assert all(type(x) is float for x in d.values())
    assert json.loads(json.dumps(d)) == d
    assert d["arglat"] == pytest.approx(D(5), abs=1e-12)
