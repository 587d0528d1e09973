"""Sleep rails: the same 20 ms step on a cheaper derivative.

Physics model, "Rails: the same step, a cheaper derivative": a body whose
program sleeps, or that nobody flies, is advanced at the flight model's step
by RK4 of its position and velocity only
(:func:`rocketsim.dynamics.nbody.translational_rk4`):

- about Earth: Kepler plus J2, and on real sites point-mass drag below
  600 km (``C_D A/m`` in the field array, the day's air table) so a sleeping
  stage decays like an awake one; the third bodies are left out of the field
  (their tidal pull on a low orbit is below 1e-6 m/s^2);
- about the Moon and Mars: the full field with the other bodies held per 5 s,
  the very gravity an awake body feels, so the two stay bit-identical.

The attitude is not integrated. A held attitude stays fixed in its command
frame (:data:`HELD`: the inertial frame, body rates zero); a free body turns
by the exact torque-free motion of an axisymmetric body (:func:`turn_constants`,
``x`` the symmetry axis, ``I_yy = I_zz``), nutation included.
"""

from __future__ import annotations

import math

import numpy as np

from rocketsim._jit import njit
from rocketsim.constants import RAILS_FLOOR
from rocketsim.dynamics.derivative import radial_height
from rocketsim.dynamics.nbody import F_CENTER, F_MU, bodies_at, hold_time, translational_rk4
from rocketsim.dynamics.state import Q, W
from rocketsim.frames.quaternion import quat_rotate

FREE = 0      # torque-free rotation
HELD = 1      # attitude held fixed in an inertial command frame


@njit
def _product(a0, a1, a2, a3, b0, b1, b2, b3):
    """Hamilton product of two quaternions given by components (a tuple of four)."""
    return (a0 * b0 - a1 * b1 - a2 * b2 - a3 * b3, a0 * b1 + a1 * b0 + a2 * b3 - a3 * b2,
            a0 * b2 - a1 * b3 + a2 * b0 + a3 * b1, a0 * b3 + a1 * b2 - a2 * b1 + a3 * b0)


@njit
def spin_constants(w_x, inertia, dt):
    """The body-fixed part of :func:`turn_constants`: ``(b, c, s)``, the quaternion
    ``q_x(omega_s dt)`` (a tuple) and the cosine and sine of the rates' turn, for the
    roll rate ``w_x`` (rad/s). The torque-free map leaves ``w_x`` untouched, so these
    are the same bits at every step of a body on rails (computed once per batch)."""
    i1, it = inertia[0], inertia[1]
    spin = (it - i1) * w_x / it
    b = (math.cos(0.5 * spin * dt), math.sin(0.5 * spin * dt), 0.0, 0.0)
    return b, math.cos(spin * dt), -math.sin(spin * dt)


@njit
def precession_constant(y, inertia, dt):
    """The inertial part of :func:`turn_constants`: the quaternion ``q_H(Omega dt)``
    (a tuple) about the angular momentum of state ``y``, identity when it is zero."""
    i1, it = inertia[0], inertia[1]
    hx, hy, hz = quat_rotate(y[Q:Q + 4], np.array((i1 * y[W], it * y[W + 1], it * y[W + 2])))
    h = math.sqrt(hx * hx + hy * hy + hz * hz)
    if h == 0.0:
        return (1.0, 0.0, 0.0, 0.0)
    half = 0.5 * h / it * dt
    k = math.sin(half) / h
    return (math.cos(half), k * hx, k * hy, k * hz)


@njit
def turn_constants(y, inertia, dt):
    """The exact torque-free map over ``dt`` s from the attitude and rates of ``y``.

    ``inertia``: ``(I_xx, I_t, I_t)`` kg m^2 of a body symmetric about ``x``.
    With ``H`` the (fixed) angular momentum and ``I_t`` the transverse inertia,
    the body turns about ``H`` at ``Omega = |H|/I_t`` while spinning about its
    own ``x`` axis at ``omega_s = (I_t - I_xx) w_x / I_t``::

        q(t) = q_H(Omega t) (x) q(0) (x) q_x(omega_s t)

    and the transverse body rates turn at ``-omega_s`` (Landau & Lifshitz,
    Mechanics, section 36; Goldstein, Classical Mechanics, section 5.6).
    Returns ``(a, b, c, s)``: the quaternions ``q_H`` and ``q_x`` (tuples) and
    the cosine and sine of the rates' turn. ``q_H`` is rebuilt from each step's
    state (not once per batch), so batching never changes a bit.
    """
    b, c, s = spin_constants(y[W], inertia, dt)
    return precession_constant(y, inertia, dt), b, c, s


@njit
def apply_turn(y, a, b, c, s):
    """Turn the attitude and rates of ``y`` in place by :func:`turn_constants`."""
    p0, p1, p2, p3 = _product(a[0], a[1], a[2], a[3], y[Q], y[Q + 1], y[Q + 2], y[Q + 3])
    q0, q1, q2, q3 = _product(p0, p1, p2, p3, b[0], b[1], b[2], b[3])
    norm = math.sqrt(q0 * q0 + q1 * q1 + q2 * q2 + q3 * q3)
    y[Q] = q0 / norm
    y[Q + 1] = q1 / norm
    y[Q + 2] = q2 / norm
    y[Q + 3] = q3 / norm
    w1, w2 = y[W + 1], y[W + 2]
    y[W + 1] = w1 * c - w2 * s
    y[W + 2] = w1 * s + w2 * c


@njit
def turn_attitude(y, inertia, dt, mode):
    """Write the attitude of state ``y`` after ``dt`` s on rails (in place):
    held (rates zero) or torque-free."""
    if mode == HELD:
        y[W] = 0.0
        y[W + 1] = 0.0
        y[W + 2] = 0.0
        return
    a, b, c, s = turn_constants(y, inertia, dt)
    apply_turn(y, a, b, c, s)


@njit
def rails_step(y, t, h, p, s, fp, air, inertia, mode):
    """One rails step of ``h`` s from mission time ``t`` (a new state): RK4 of
    position and velocity in the field (bodies held at ``s``), the attitude
    exactly."""
    out = y.copy()
    translational_rk4(out, h, p, s, fp, air, np.empty(3))
    turn_attitude(out, inertia, h, mode)
    return out


def rails_floor(center: str) -> float:
    """Height (m) below which a body about ``center`` cannot stay on rails: 151 km
    where there is air (Earth, Mars), the surface on the Moon."""
    return 0.0 if center == "moon" else RAILS_FLOOR


@njit
def advance_rails(y, k0, h, n_steps, p, fp, air, inertia, mode, floor=RAILS_FLOOR):
    """Advance up to ``n_steps`` rails steps; returns ``(y, steps_taken)``.

    Step ``k`` starts at mission time ``(k0 + k) h``; other bodies in the field
    are held per 5 s bucket (as :func:`rocketsim.dynamics.nbody.advance_awake`).
    Bit-identical to calling :func:`rails_step` once per step.
    Stops early, after the step that took the body below ``floor`` (m over the
    central body's ellipsoid, :func:`rails_floor`): it must wake up.
    """
    y = y.copy()
    pos = np.empty(3)
    bucket = -1.0
    s = np.zeros((4, 3))
    third = False
    for k in range(4):
        if fp[F_MU + k] != 0.0 and k != int(fp[F_CENTER]):
            third = True
    spin, c, sn = spin_constants(y[W], inertia, h)
    for k in range(n_steps):
        t = (k0 + k) * h
        if third and hold_time(t) != bucket:
            bucket = hold_time(t)
            s = bodies_at(fp, bucket)[0]
        translational_rk4(y, h, p, s, fp, air, pos)
        if mode == HELD:
            turn_attitude(y, inertia, h, mode)
        else:
            apply_turn(y, precession_constant(y, inertia, h), spin, c, sn)
        if radial_height(y, p) < floor:
            return y, k + 1
    return y, n_steps
