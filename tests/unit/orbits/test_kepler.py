"""Universal-variable Kepler propagation against a worked example, a reference
integrator and the circular orbit.

References:
- Vallado, *Fundamentals of Astrodynamics and Applications*, 4th ed.,
  Example 2-4 (KEPLER): r0 = (1131.340, -2282.343, 6672.423) km,
  v0 = (-5.64305, 4.30333, 2.42879) km/s, 40 min later
  r = (-4219.7527, 4363.0292, -3958.7666) km,
  v = (3.689866, -1.916735, -6.112511) km/s.
- scipy's DOP853 integrating the two-body equations at rtol 1e-13: elliptic,
  parabolic and hyperbolic orbits, forwards and backwards.
- A circular orbit: the position turns at the mean motion (analytic).
"""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from rocketsim.orbits import propagate

MU = 398600.4418e9


def test_vallado_example_2_4():
    r0 = np.array([1131.340, -2282.343, 6672.423]) * 1e3
    v0 = np.array([-5.64305, 4.30333, 2.42879]) * 1e3
    r, v = propagate(MU, r0, v0, 40 * 60.0)
    np.testing.assert_allclose(r / 1e3, [-4219.7527, 4363.0292, -3958.7666], atol=0.5e-4)
    np.testing.assert_allclose(v / 1e3, [3.689866, -1.916735, -6.112511], atol=0.5e-6)


def _two_body(t, y):
    r = y[:3]
    return np.concatenate([y[3:], -MU * r / np.linalg.norm(r) ** 3])


def _reference(r0, v0, dt):
    sol = solve_ivp(_two_body, (0.0, dt), np.concatenate([r0, v0]), method="DOP853",
                    rtol=1e-13, atol=1e-9)
    return sol.y[:3, -1], sol.y[3:, -1]


def _orbit_state(rp, e, nu, rng):
    """State at true anomaly nu of an orbit of periapsis rp, random orientation."""
    p = rp * (1.0 + e)
    r = p / (1.0 + e * math.cos(nu))
    pos = np.array([r * math.cos(nu), r * math.sin(nu), 0.0])
    vel = math.sqrt(MU / p) * np.array([-math.sin(nu), e + math.cos(nu), 0.0])
    q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
    return q @ pos, q @ vel


CASES = [
    # (eccentricity, true anomaly at start, dt in units of sqrt(rp^3/mu))
    (0.0, 0.3, 7.0), (0.1, 2.0, 25.0), (0.7, -2.5, 40.0), (0.95, 3.0, -30.0),
    (1.0, -1.0, 6.0), (1.0, 0.5, -3.0), (1.0 - 1e-9, 0.2, 5.0), (1.0 + 1e-9, 0.2, 5.0),
    (1.5, -1.5, 10.0), (3.0, -1.2, 4.0), (8.0, 0.9, -2.0), (1.2, -1.0, 60.0),
    # In from 200 periapsis radii, round the centre and out again: far along
    # the hyperbola, where f r0 + g v0 would cancel (the anomaly form is used).
    (1.02, -2.9, 1500.0), (1.0001, -3.0, 3000.0),
]


@pytest.mark.parametrize("e, nu, dt_units", CASES)
def test_matches_reference_integrator(e, nu, dt_units):
    rng = np.random.default_rng(abs(hash((e, nu))) % 2**32)
    rp = 7000e3
    r0, v0 = _orbit_state(rp, e, nu, rng)
    dt = dt_units * math.sqrt(rp ** 3 / MU)
    r, v = propagate(MU, r0, v0, dt)
    r_ref, v_ref = _reference(r0, v0, dt)
    scale_r = max(np.linalg.norm(r_ref), rp)
    assert np.linalg.norm(r - r_ref) < 1e-9 * scale_r
    assert np.linalg.norm(v - v_ref) < 1e-9 * np.linalg.norm(v_ref)


def test_circular_orbit_turns_at_the_mean_motion_over_many_revolutions():
    a = 42164e3
    n = math.sqrt(MU / a ** 3)
    dt = np.linspace(0.0, 1000 * 2 * math.pi / n, 37)
    r, v = propagate(MU, [a, 0.0, 0.0], [0.0, a * n, 0.0], dt)
    angle = n * dt
    expected = a * np.stack([np.cos(angle), np.sin(angle), np.zeros_like(angle)], axis=-1)
    # 1000 revolutions: the phase is known to ~1000 * 2 pi * 1e-16 rad.
    np.testing.assert_allclose(r, expected, rtol=0, atol=1e-9 * a)
    np.testing.assert_allclose(np.linalg.norm(v, axis=-1), a * n, rtol=1e-12)


def test_forward_then_backward_returns_and_vectorised_equals_scalar():
    rng = np.random.default_rng(3)
    states = [_orbit_state(7000e3, e, nu, rng) for e, nu, _ in CASES]
    r0 = np.array([s[0] for s in states])
    v0 = np.array([s[1] for s in states])
    dt = rng.uniform(-2e4, 2e4, len(CASES))
    r, v = propagate(MU, r0, v0, dt)
    rb, vb = propagate(MU, r, v, -dt)
    np.testing.assert_allclose(rb, r0, rtol=0, atol=1e-9 * 7000e3 * 50)
    for i in range(len(CASES)):
        ri, vi = propagate(MU, r0[i], v0[i], dt[i])
        np.testing.assert_array_equal(ri, r[i])
        np.testing.assert_array_equal(vi, v[i])
