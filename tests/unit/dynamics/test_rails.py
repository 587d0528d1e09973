"""Sleep rails against the awake flight model and against independent references.

References: the awake RK4 of the full derivative (``rocketsim.dynamics.rk4``)
and DOP853 (``rocketsim.dynamics.reference``, rtol 1e-13) for orbits; an
independent numpy drag model (the US 1976 table read through
``AtmosphereTable.at`` at the radial height) under DOP853 for the decay; the
analytic torque-free motion of an axisymmetric body (Landau & Lifshitz,
Mechanics, section 36: the symmetry axis turns on a cone of half-angle
``acos(I_1 w_1 / |H|)`` about the fixed angular momentum at ``|H| / I_t``)
and DOP853 of Euler's equations for the attitude.

The 24-hour LEO comparisons fly a headless 0.1 s step (the largest a headless
run accepts, docs/physics.md#integrator): 864 000 steps per integrator instead of 4.3 million
keeps this file inside its minute on two busy cores; rails and awake share
the step, so the comparison is the same.
"""

import datetime as dt

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from rocketsim.atmosphere.day import standard_table
from rocketsim.constants import (DEG, EARTH_J2, EARTH_MU, EARTH_OMEGA, EARTH_RADIUS_EQ,
                                 EARTH_RADIUS_POLAR, MARS_J2, MARS_MU, MARS_RADIUS_EQ, MOON_J2,
                                 MOON_MU, MOON_RADIUS)
from rocketsim.bodies.gravity import gravity
from rocketsim.dynamics import nbody, rails, soi
from rocketsim.dynamics.reference import integrate_reference
from rocketsim.dynamics.rk4 import advance
from rocketsim.layout import make_params, make_state
from rocketsim.frames.elements import elements_to_state
from rocketsim.frames.quaternion import quat_rotate
from rocketsim.timescales import Epoch

JD0 = Epoch.from_utc(dt.datetime(2026, 11, 26, 12, tzinfo=dt.timezone.utc)).jd_tt()
INERTIA = (2.0, 5.0, 5.0)
EARTH_P = make_params(1000.0, INERTIA, EARTH_MU, EARTH_RADIUS_EQ, EARTH_J2, EARTH_RADIUS_POLAR)
EARTH_FIELD = nbody.make_field("earth", JD0, bodies=())       # parking-orbit rails: Kepler + J2
NO_AIR = nbody.no_air()


def leo(altitude, inclination=51.6 * DEG, mu=EARTH_MU, radius=EARTH_RADIUS_EQ):
    r, v = elements_to_state(radius + altitude, 0.001, inclination, 0.3, 0.2, 0.0, mu)
    return make_state(r, v, (1.0, 0.0, 0.0, 0.0), (0.0, 0.0, 0.0))


def test_rails_and_awake_leo_24_h_same_path_and_dop853_within_1_m():
    h = 0.1
    n = round(86400 / h)
    y0 = leo(400e3)
    awake, _ = advance(y0, 0, h, n, EARTH_P)
    slept, taken = rails.advance_rails(y0, 0, h, n, EARTH_P, EARTH_FIELD, NO_AIR,
                                       EARTH_P[1:4], rails.FREE)
    assert taken == n
    # same derivative for position and velocity, same RK4 arithmetic: the same bits
    np.testing.assert_array_equal(slept[:6], awake[:6])
    reference = integrate_reference(y0, 0.0, n * h, EARTH_P, rtol=1e-13, atol=1e-9)
    assert np.linalg.norm(slept[:3] - reference[:3]) < 1.0


def reference_drag_orbit(y0, t1, drag, table):
    """DOP853 of point mass + J2 + drag written in numpy (independent of the rails)."""
    a_eq, b = EARTH_RADIUS_EQ, EARTH_RADIUS_POLAR

    def rhs(t, y):
        r, v = y[:3], y[3:]
        rho2 = r[0] ** 2 + r[1] ** 2
        height = np.linalg.norm(r) - a_eq * b / np.sqrt((b * b * rho2 + a_eq * a_eq * r[2] ** 2) / (r @ r))
        density = table.at(height)[0][0]
        v_air = v - np.cross([0.0, 0.0, EARTH_OMEGA], r)
        a = gravity(r) - 0.5 * density * np.linalg.norm(v_air) * drag * v_air
        return np.concatenate((v, a))
    solution = solve_ivp(rhs, (0.0, t1), y0[:6], method="DOP853", rtol=1e-12, atol=1e-6)
    return solution.y[:, -1]


def test_sleeping_stage_decays_like_the_reference_within_1_m():
    h = 0.1
    n = round(86400 / h)
    table = standard_table()
    drag = 2.2 * 10.0 / 2000.0                       # C_D A / m of a 2 t stage, m^2/kg
    fp = nbody.make_field("earth", JD0, bodies=(), drag=drag)
    y0 = leo(260e3)
    slept, taken = rails.advance_rails(y0, 0, h, n, EARTH_P, fp, table.arrays()[:8],
                                       EARTH_P[1:4], rails.FREE)
    assert taken == n
    reference = reference_drag_orbit(y0, n * h, drag, table)
    undragged, _ = rails.advance_rails(y0, 0, h, n, EARTH_P, EARTH_FIELD, NO_AIR,
                                       EARTH_P[1:4], rails.FREE)
    # the drag matters (kilometres along track in a day) and the rails follow it to 1 m
    assert np.linalg.norm(undragged[:3] - slept[:3]) > 10e3
    assert np.linalg.norm(slept[:3] - reference[:3]) < 1.0


@pytest.mark.parametrize("center, mu, radius, j2, altitude", [
    ("moon", MOON_MU, MOON_RADIUS, MOON_J2, 100e3),
    ("mars", MARS_MU, MARS_RADIUS_EQ, MARS_J2, 300e3),
])
def test_rails_about_the_moon_and_mars_are_bit_identical_to_awake(center, mu, radius, j2,
                                                                   altitude):
    p = make_params(1000.0, INERTIA, mu, radius, j2, radius)
    fp = nbody.make_field(center, JD0, rotation=soi.frame_rotation(center, JD0))
    y0 = leo(altitude, 80 * DEG, mu, radius)
    n = round(7200 / 0.02)                           # two hours at 20 ms
    awake = nbody.advance_awake(y0, 0, 0.02, n, p, fp, NO_AIR)
    slept, taken = rails.advance_rails(y0, 0, 0.02, n, p, fp, NO_AIR, p[1:4], rails.FREE,
                                       rails.rails_floor(center))
    assert taken == n
    np.testing.assert_array_equal(slept[:6], awake[:6])
    # and the third bodies do act: a two-body conic drifts from it
    alone = nbody.make_field(center, JD0, rotation=soi.frame_rotation(center, JD0), bodies=())
    conic, _ = rails.advance_rails(y0, 0, 0.02, n, p, alone, NO_AIR, p[1:4], rails.FREE,
                                   rails.rails_floor(center))
    assert np.linalg.norm(conic[:3] - slept[:3]) > 0.1      # Moon: 100s of m; Mars: 0.4 m


def test_torque_free_rails_follow_the_analytic_cone_and_dop853():
    w0 = np.array([1.0, 0.3, -0.2])
    y0 = make_state((EARTH_RADIUS_EQ + 400e3, 0.0, 0.0), (0.0, 7670.0, 0.0),
                    (0.9, 0.1, -0.3, 0.2), w0)
    inertia = np.array(INERTIA)
    h = 0.02
    n = round(100.0 / h)
    y = y0.copy()
    h_body = inertia * w0
    h_dir0 = quat_rotate(y0[6:10], h_body)
    h_norm = np.linalg.norm(h_dir0)
    h_dir0 /= h_norm
    cone = np.arccos(inertia[0] * w0[0] / h_norm)
    rate = h_norm / inertia[1]
    x0 = quat_rotate(y0[6:10], np.array([1.0, 0.0, 0.0]))
    worst_h = worst_cone = 0.0
    for k in range(n):
        y = rails.rails_step(y, k * h, h, EARTH_P, np.zeros((4, 3)), EARTH_FIELD, NO_AIR, inertia,
                             rails.FREE)
        h_dir = quat_rotate(y[6:10], inertia * y[10:13])
        worst_h = max(worst_h, np.linalg.norm(h_dir / np.linalg.norm(h_dir) - h_dir0))
        x = quat_rotate(y[6:10], np.array([1.0, 0.0, 0.0]))
        worst_cone = max(worst_cone, abs(np.arccos(np.clip(x @ h_dir0, -1, 1)) - cone))
    assert worst_h < 1e-12                       # angular momentum direction fixed
    assert worst_cone < 1e-9                     # the nose stays on its cone
    # after 100 s the nose has turned about H by rate * t (Rodrigues)
    angle = rate * n * h
    expected = (x0 * np.cos(angle) + np.cross(h_dir0, x0) * np.sin(angle)
                + h_dir0 * (h_dir0 @ x0) * (1 - np.cos(angle)))
    np.testing.assert_allclose(x, expected, atol=1e-9)
    # and DOP853 of Euler's equations and the quaternion kinematics agrees
    p = EARTH_P.copy()
    reference = integrate_reference(y0, 0.0, n * h, p, rtol=1e-13, atol=1e-13)
    q_ref = reference[6:10] / np.linalg.norm(reference[6:10])
    assert min(np.linalg.norm(y[6:10] - q_ref), np.linalg.norm(y[6:10] + q_ref)) < 1e-9
    np.testing.assert_allclose(y[10:13], reference[10:13], atol=1e-9)


def test_held_attitude_stays_fixed_and_rails_stop_at_the_floor():
    y0 = leo(400e3)
    y0[10:13] = (0.01, 0.02, 0.0)
    held, _ = rails.advance_rails(y0, 0, 0.02, 500, EARTH_P, EARTH_FIELD, NO_AIR, EARTH_P[1:4],
                                  rails.HELD)
    np.testing.assert_array_equal(held[6:10], y0[6:10])
    np.testing.assert_array_equal(held[10:13], 0.0)
    low = leo(150e3)
    _, taken = rails.advance_rails(low, 0, 0.02, 500, EARTH_P, EARTH_FIELD, NO_AIR,
                                   EARTH_P[1:4], rails.FREE)
    assert taken == 1                            # below 151 km the body must wake


def test_batched_rails_are_bit_identical_to_single_steps():
    y0 = leo(400e3)
    y0[10:13] = (0.5, 0.1, -0.05)
    inertia = np.array(INERTIA)
    batched, _ = rails.advance_rails(y0, 0, 0.02, 300, EARTH_P, EARTH_FIELD, NO_AIR, inertia,
                                     rails.FREE)
    y = y0
    for k in range(300):
        y = rails.rails_step(y, k * 0.02, 0.02, EARTH_P, np.zeros((4, 3)), EARTH_FIELD, NO_AIR,
                             inertia, rails.FREE)
    np.testing.assert_array_equal(batched, y)
