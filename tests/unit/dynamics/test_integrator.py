"""The fixed-step RK4 flight integrator against conservation laws, analytic
solutions and the Dormand-Prince reference (docs/physics.md#integrator)."""

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from rocketsim.constants import EARTH_MU, EARTH_RADIUS_EQ, EARTH_RADIUS_POLAR, GROUND_SUBSTEPS
from rocketsim.dynamics.reference import integrate_reference
from rocketsim.dynamics.rk4 import advance, rk4_step, step
from rocketsim.layout import Q, R, V, W, make_params, make_state
from rocketsim.frames.elements import elements_to_state
from rocketsim.frames.quaternion import quat_rotate

H = 0.02  # s, the flight model's step


def point_mass_params(inertia=(1.0, 1.0, 1.0)):
    return make_params(10.0, inertia, EARTH_MU, EARTH_RADIUS_EQ, 0.0, EARTH_RADIUS_POLAR)


def specific_energy(y):
    return 0.5 * np.dot(y[V:V + 3], y[V:V + 3]) - EARTH_MU / np.linalg.norm(y[R:R + 3])


def test_three_hour_coast_conserves_energy_and_angular_momentum():
    """Kepler problem invariants (analytic: exactly constant): relative drift
    of specific energy and of |r x v| after 3 h at 20 ms below 1e-10."""
    r, v = elements_to_state(EARTH_RADIUS_EQ + 415e3, 0.001, math.radians(51.6), 0.3, 0.2, 0.1, EARTH_MU)
    y0 = make_state(r, v)
    y1, taken = advance(y0, 0, H, int(3 * 3600 / H), point_mass_params())
    assert taken == int(3 * 3600 / H)
    e0, e1 = specific_energy(y0), specific_energy(y1)
    h0 = np.linalg.norm(np.cross(y0[R:R + 3], y0[V:V + 3]))
    h1 = np.linalg.norm(np.cross(y1[R:R + 3], y1[V:V + 3]))
    assert abs(e1 - e0) / abs(e0) < 1e-10
    assert abs(h1 - h0) / h0 < 1e-10


def radial_free_fall(r0, t):
    """Analytic radial fall from rest in a point-mass field (the degenerate
    Kepler ellipse, e.g. Vallado 4th ed. problem 2-x / the "cycloid"
    solution): r = r0 (1 + cos eta)/2, t = sqrt(r0^3 / (8 mu)) (eta + sin eta)."""
    scale = math.sqrt(r0 ** 3 / (8.0 * EARTH_MU))
    eta = brentq(lambda e: scale * (e + math.sin(e)) - t, 0.0, 1.0, xtol=1e-16, rtol=1e-15)
    return r0 * (1.0 + math.cos(eta)) / 2.0


def test_free_fall_in_vacuum_matches_the_analytic_solution():
    """Radial free fall from rest in a point-mass field, against the analytic fall
    ``t(r)`` of the radial Kepler problem: within 1e-6 m after 10 s."""
    r0 = EARTH_RADIUS_EQ + 100e3
    y0 = make_state([0.0, r0, 0.0], [0.0, 0.0, 0.0])
    y1, _ = advance(y0, 0, H, 500, point_mass_params())
    expected = radial_free_fall(r0, 10.0)
    assert r0 - expected > 400.0                       # it did fall ~470 m
    assert abs(np.linalg.norm(y1[R:R + 3]) - expected) < 1e-6
    assert np.max(np.abs(y1[[R, R + 2]])) < 1e-9       # straight down


def torque_free_invariants(y, inertia):
    """Inertial angular momentum R(q) I w and rotational energy 1/2 w.I w."""
    w = y[W:W + 3]
    momentum = quat_rotate(y[Q:Q + 4], np.asarray(inertia) * w)
    return momentum, 0.5 * float(np.dot(w, np.asarray(inertia) * w))


def test_torque_free_rigid_body_conserves_momentum_and_energy():
    """Euler's equations for a free asymmetric body conserve the inertial
    angular momentum vector and the kinetic energy exactly; over 100 s at
    20 ms both stay within 1e-10 relative."""
    inertia = (2.0, 3.0, 4.5)
    y0 = make_state([EARTH_RADIUS_EQ + 500e3, 0, 0], [0, 7600.0, 0], q=(0.9, 0.1, -0.3, 0.2),
                    w=(0.2, 0.1, -0.15))
    p = point_mass_params(inertia)
    y1, _ = advance(y0, 0, H, 5000, p)
    m0, t0 = torque_free_invariants(y0, inertia)
    m1, t1 = torque_free_invariants(y1, inertia)
    assert np.linalg.norm(m1 - m0) / np.linalg.norm(m0) < 1e-10
    assert abs(t1 - t0) / t0 < 1e-10
    assert np.max(np.abs(y1[W:W + 3] - y0[W:W + 3])) > 1e-3   # it did tumble


def test_unpowered_convergence_is_fourth_order():
    """Against the Dormand-Prince (DOP853, rtol 1e-13) reference: a body
    tumbling fast enough (|w| ~ 2.5 rad/s) that RK4's truncation error is far
    above rounding for steps of 0.1, 0.05 and 0.025 s. (A coasting orbit's
    error is at rounding level for any step <= 0.1 s, so it cannot show an
    order.) The observed order must be 4 +- 0.2."""
    inertia = (1.0, 2.0, 2.6)
    y0 = make_state([EARTH_RADIUS_EQ + 500e3, 0, 0], [0, 7600.0, 0], w=(1.5, -1.2, 1.6))
    p = point_mass_params(inertia)
    t_end = 4.0
    reference = integrate_reference(y0, 0.0, t_end, p, rtol=1e-13, atol=1e-14)
    errors = []
    for h in (0.1, 0.05, 0.025):
        y, _ = advance(y0, 0, h, round(t_end / h), p)
        errors.append(np.linalg.norm(y[Q:] - reference[Q:]))
    orders = [math.log2(errors[k] / errors[k + 1]) for k in range(2)]
    assert all(abs(order - 4.0) < 0.2 for order in orders), orders


@pytest.mark.parametrize("height, substeps", [(1.0, GROUND_SUBSTEPS), (3.0, 1)])
def test_steps_within_two_metres_of_the_ground_are_split_in_four(height, substeps):
    """docs/physics.md#integrator: within 2 m of the ground the step is split into
    four 5 ms sub-steps. Checked bit for bit against explicit sub-steps."""
    y0 = make_state([0.0, 0.0, EARTH_RADIUS_POLAR + height], [0.0, 0.0, -1.0])
    p = point_mass_params()
    expected = y0
    for k in range(substeps):
        expected = rk4_step(expected, k * H / substeps, H / substeps, p)
    assert np.array_equal(step(y0, 0.0, H, p), expected)
