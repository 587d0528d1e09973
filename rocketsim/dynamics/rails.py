"""Sleep rails: the same 20 ms step on a cheaper derivative.

docs/physics.md#sleep-rails, the same step on a cheaper derivative: a body whose
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
frame: :data:`HELD`, an inertial direction with no roll, body rates zero;
:data:`TRACK`, a frame that turns (prograde, surface prograde, normal and
radial and their opposites; pitch/heading in the local east-north-up axes;
any commanded roll, whose reference is the local vertical): after each step
the attitude is set exactly on the command of the new state
(:func:`command_attitude`) and the body rates to the frame's turn over the
step (:func:`turn_rate`). A free body turns by the exact torque-free motion of
an axisymmetric body (:func:`turn_constants`, ``x`` the symmetry axis,
``I_yy = I_zz``), nutation included.
"""

from __future__ import annotations

import math

import numpy as np

from rocketsim.jit import copy_into, njit
from rocketsim.constants import RAILS_FLOOR
from rocketsim.dynamics.derivative import radial_height
from rocketsim.dynamics.nbody import FIELD_CENTER, FIELD_MU, bodies_at, hold_time, translational_rk4
from rocketsim.layout import P_MU, P_POLAR_RADIUS, P_RADIUS, P_SPIN, Q, R, V, W
from rocketsim.frames.local import VERTICAL, where_and_how_fast
from rocketsim.frames.quaternion import (hamilton_product, quat_conjugate, quat_from_axis_angle,
                                         quat_from_matrix, quat_multiply, quat_normalize, quat_rotate,
                                         rotate_components)
from rocketsim.frames.vectors import compiled_cross

FREE = 0      # torque-free rotation
HELD = 1      # attitude held fixed in an inertial command frame
TRACK = 2     # attitude held in a command frame that turns, set on it at every step

# what a command's nose follows (the first entry of its code, :func:`command_code`)
DIRECTION, PITCH_HEADING, PROGRADE, SURFACE_PROGRADE, NORMAL, RADIAL, LINEAR_TANGENT = 0, 1, 2, 3, 4, 5, 6
_MODE_CODES = {"prograde": (PROGRADE, 1.0), "retrograde": (PROGRADE, -1.0),
               "surface_prograde": (SURFACE_PROGRADE, 1.0),
               "surface_retrograde": (SURFACE_PROGRADE, -1.0),
               "normal": (NORMAL, 1.0), "antinormal": (NORMAL, -1.0),
               "radial": (RADIAL, 1.0), "antiradial": (RADIAL, -1.0)}


def command_code(command) -> np.ndarray:
    """The numbers the rails read of an attitude command
    (:class:`rocketsim.flight.autopilot.AttitudeCommand`): ``(kind, sign, a, b, c, roll)``,
    ``kind`` :data:`DIRECTION` with the ECI unit vector ``(a, b, c)``,
    :data:`PITCH_HEADING` with pitch ``a`` and heading ``b`` (rad), a mode
    (:data:`PROGRADE` ... :data:`RADIAL`) with ``sign`` -1 for its opposite, or
    :data:`LINEAR_TANGENT` with the law's start time (s) in place of ``sign``, its
    ``tan`` of the pitch at that time ``a``, its rate ``b`` (1/s) and the cross-track
    share ``c`` (see :func:`nose_target`); ``roll`` rad, nan for none."""
    roll = math.nan if command.roll is None else float(command.roll)
    if command.direction is not None:
        code = (DIRECTION, 1.0, *command.direction, roll)
    elif command.law is not None:
        start, a, b, cross = command.law
        code = (LINEAR_TANGENT, start, a, b, cross, roll)
    elif command.mode is not None:
        code = (*_MODE_CODES[command.mode], 0.0, 0.0, 0.0, roll)
    else:
        code = (PITCH_HEADING, 1.0, command.pitch, command.heading, 0.0, roll)
    return np.array(code, dtype=float)


def hold_mode(code: np.ndarray) -> int:
    """:data:`HELD` for an inertial direction with no roll, else :data:`TRACK`."""
    return HELD if code[0] == DIRECTION and math.isnan(code[5]) else TRACK


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


@njit(borrows=True)
def precession_constant(y, inertia, dt):
    """The inertial part of :func:`turn_constants`: the quaternion ``q_H(Omega dt)``
    (a tuple) about the angular momentum of state ``y``, identity when it is zero."""
    i1, it = inertia[0], inertia[1]
    hx, hy, hz = rotate_components(y[Q], y[Q + 1], y[Q + 2], y[Q + 3], i1 * y[W], it * y[W + 1], it * y[W + 2])
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


@njit(borrows=True)
def apply_turn(y, a, b, c, s):
    """Turn the attitude and rates of ``y`` in place by :func:`turn_constants`."""
    p0, p1, p2, p3 = hamilton_product(a[0], a[1], a[2], a[3], y[Q], y[Q + 1], y[Q + 2], y[Q + 3])
    q0, q1, q2, q3 = hamilton_product(p0, p1, p2, p3, b[0], b[1], b[2], b[3])
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
def _unit(x, y, z):
    size = math.sqrt(x * x + y * y + z * z)
    return x / size, y / size, z / size


@njit
def nose_target(code, r, v, enu, surface, t):
    """The commanded nose direction (unit, ECI) of ``code`` (:func:`command_code`) for a
    body at ``r`` (m) moving at ``v`` (m/s) at mission time ``t`` (s), as the autopilot
    reads it: ``enu`` the rows east, north, up and ``surface`` the velocity relative to
    the ground (m/s, ECI axes) of :func:`rocketsim.frames.local.where_and_how_fast`.

    :data:`LINEAR_TANGENT` is linear-tangent steering (docs/physics.md#autopilot): the
    pitch above the plane normal to the radius ``theta = atan(a + b (t - t0))``, in the
    plane of ``r`` and ``v`` ahead along the velocity, tilted by ``c`` along the orbit
    normal ``r x v``: the unit vector along ``cos(theta) h + sin(theta) u + c n``
    (``u``, ``h``, ``n`` the units along ``r``, the velocity's part normal to it and
    ``r x v``)."""
    kind = int(code[0])
    out = np.empty(3)
    if kind == DIRECTION:
        copy_into(out, 0, code[2:5])
        return out
    if kind == LINEAR_TANGENT:
        ux, uy, uz = _unit(r[0], r[1], r[2])
        climb = v[0] * ux + v[1] * uy + v[2] * uz
        hx, hy, hz = _unit(v[0] - climb * ux, v[1] - climb * uy, v[2] - climb * uz)
        nx, ny, nz = _unit(r[1] * v[2] - r[2] * v[1], r[2] * v[0] - r[0] * v[2], r[0] * v[1] - r[1] * v[0])
        theta = math.atan(code[2] + code[3] * (t - code[1]))
        c, s, cross = math.cos(theta), math.sin(theta), code[4]
        out[0], out[1], out[2] = _unit(c * hx + s * ux + cross * nx, c * hy + s * uy + cross * ny,
                                       c * hz + s * uz + cross * nz)
        return out
    if kind == PITCH_HEADING:
        sin_heading, cos_heading = math.sin(code[3]), math.cos(code[3])
        cos_pitch, sin_pitch = math.cos(code[2]), math.sin(code[2])
        for i in range(3):
            out[i] = cos_pitch * (sin_heading * enu[0, i] + cos_heading * enu[1, i]) + sin_pitch * enu[2, i]
        return out
    if kind == PROGRADE:
        x, y, z = _unit(v[0], v[1], v[2])
    elif kind == SURFACE_PROGRADE:
        if surface[0] * surface[0] + surface[1] * surface[1] + surface[2] * surface[2] > 0.0:
            x, y, z = _unit(surface[0], surface[1], surface[2])
        else:
            x, y, z = enu[2, 0], enu[2, 1], enu[2, 2]
    elif kind == NORMAL:
        x, y, z = _unit(r[1] * v[2] - r[2] * v[1], r[2] * v[0] - r[0] * v[2], r[0] * v[1] - r[1] * v[0])
    else:
        x, y, z = _unit(r[0], r[1], r[2])
    out[0], out[1], out[2] = code[1] * x, code[1] * y, code[1] * z
    return out


@njit
def _dot(a, b):
    total = 0.0
    for i in range(a.shape[0]):
        total += a[i] * b[i]
    return total


@njit
def target_attitude(nose, up, roll):
    """``(found, q)``: the attitude (quaternion body -> ECI, ``w >= 0``) with the nose along
    ``nose`` (unit, ECI) turned ``roll`` rad about it from the belly-to-the-ground
    reference below the local ``up`` (unit, ECI), as the autopilot's
    :func:`rocketsim.flight.autopilot.target_axes`; ``found`` false within 0.01 deg of
    the vertical (no reference: the autopilot then holds the nose only)."""
    sin_pitch = min(max(nose[0] * up[0] + nose[1] * up[1] + nose[2] * up[2], -1.0), 1.0)
    if abs(sin_pitch) >= VERTICAL:
        return False, np.empty(4)
    horizontal = nose - sin_pitch * up
    horizontal = horizontal / math.sqrt(_dot(horizontal, horizontal))
    z_ref = sin_pitch * horizontal - math.sqrt(1.0 - sin_pitch * sin_pitch) * up
    z_body = math.cos(roll) * z_ref + math.sin(roll) * compiled_cross(nose, z_ref)
    axes = np.empty((3, 3))
    copy_into(axes[:, 0], 0, nose)
    copy_into(axes[:, 1], 0, compiled_cross(z_body, nose))
    copy_into(axes[:, 2], 0, z_body)
    return True, quat_from_matrix(axes)


@njit
def command_attitude(code, y, t, q, p):
    """The attitude (quaternion body -> ECI) the command ``code`` (:func:`command_code`)
    holds for state ``y`` (parameters ``p``: the central body's ellipsoid and turn for the
    local vertical and the surface velocity) at mission time ``t`` (s), nearest the attitude ``q``: with a
    roll, the whole target attitude (sign as ``q``'s); without one, ``q`` turned by the
    smallest rotation that puts its nose on the commanded direction (the roll about the
    nose is left as it was: the autopilot only damps it)."""
    r, v = y[R:R + 3], y[V:V + 3]
    roll = code[5]
    kind = int(code[0])
    if kind == PITCH_HEADING or kind == SURFACE_PROGRADE or not math.isnan(roll):
        _, _, _, enu, surface = where_and_how_fast(r, v, t, p[P_SPIN], p[P_RADIUS], p[P_POLAR_RADIUS])
    else:
        enu, surface = np.empty((3, 3)), np.empty(3)
    nose = nose_target(code, r, v, enu, surface, t)
    if not math.isnan(roll):
        found, target = target_attitude(nose, enu[2], roll)
        if found:
            if _dot(target, q) < 0.0:
                target = -target
            return target
    now = quat_rotate(q, np.array((1.0, 0.0, 0.0)))
    axis = compiled_cross(now, nose)
    size = math.sqrt(_dot(axis, axis))
    if size == 0.0:
        return q.copy()
    return quat_normalize(quat_multiply(quat_from_axis_angle(axis, math.atan2(size, _dot(now, nose))), q))


@njit
def turn_rate(q0, q1, dt):
    """The body rates (rad/s, body axes) that turn the attitude ``q0`` into ``q1`` at a
    steady rate over ``dt`` s: the rotation vector of ``q0* (x) q1`` over ``dt`` (the
    same in either attitude's axes)."""
    d = quat_multiply(quat_conjugate(q0), q1)
    if d[0] < 0.0:
        d = -d
    size = math.sqrt(d[1] * d[1] + d[2] * d[2] + d[3] * d[3])
    if size == 0.0:
        return np.zeros(3)
    return d[1:] * (2.0 * math.atan2(size, d[0]) / (size * dt))


@njit
def settle(y, code, t, mode, p):
    """Put state ``y`` (in place) exactly on the command ``code`` at mission time ``t``
    (s) as it goes on rails: the settled residual is dropped; in mode :data:`HELD` the
    body rates are zeroed (mode :data:`TRACK` sets them at each step)."""
    copy_into(y, Q, command_attitude(code, y, t, y[Q:Q + 4], p))
    if mode == HELD:
        y[W:W + 3] = 0.0


@njit
def hold_offsets(code, y, t, dt, p):
    """``(error, turn)`` of a body holding ``code`` (:func:`command_code`), state ``y`` at
    mission time ``t`` (s), both body axes: the rotation vector (rad) from its attitude
    onto :func:`command_attitude`, and the command frame's turn rate (rad/s) over ``dt``
    s along the Kepler arc about the central body of ``p`` (the frame's rate, not the path, is
    wanted: the rails settle test compares it to the body rates to 1e-4 rad/s)."""
    q = y[Q:Q + 4].copy()
    target = command_attitude(code, y, t, q, p)
    error = turn_rate(q, target, 1.0)
    ahead = y[:W + 3].copy()
    r = y[R:R + 3]
    k = -p[P_MU] / _dot(r, r) ** 1.5
    for i in range(3):
        ahead[R + i] = y[R + i] + dt * y[V + i] + 0.5 * dt * dt * k * y[R + i]
        ahead[V + i] = y[V + i] + dt * k * y[R + i]
    return error, turn_rate(target, command_attitude(code, ahead, t + dt, target, p), dt)


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
def advance_rails(y, k0, h, n_steps, p, fp, air, inertia, mode, floor=RAILS_FLOOR, code=None):
    """Advance up to ``n_steps`` rails steps; returns ``(y, steps_taken)``.

    Step ``k`` starts at mission time ``(k0 + k) h``; other bodies in the field
    are held per 5 s bucket (as :func:`rocketsim.dynamics.nbody.advance_awake`).
    Bit-identical to calling :func:`rails_step` once per step (mode :data:`FREE`
    or :data:`HELD`). In mode :data:`TRACK` (``code`` the command,
    :func:`command_code`) each step ends with the attitude on the command of the
    new state and the rates at the frame's turn over the step (:func:`turn_rate`).
    Stops early, after the step that took the body below ``floor`` (m over the
    central body's ellipsoid, :func:`rails_floor`): it must wake up.
    """
    y = y.copy()
    pos = np.empty(3)
    bucket = -1.0
    s = np.zeros((4, 3))
    third = False
    for k in range(4):
        if fp[FIELD_MU + k] != 0.0 and k != int(fp[FIELD_CENTER]):
            third = True
    spin, c, sn = spin_constants(y[W], inertia, h)
    for k in range(n_steps):
        t = (k0 + k) * h
        if third and hold_time(t) != bucket:
            bucket = hold_time(t)
            s = bodies_at(fp, bucket)[0]
        translational_rk4(y, h, p, s, fp, air, pos)
        if code is not None and mode == TRACK:
            before = y[Q:Q + 4].copy()
            copy_into(y, Q, command_attitude(code, y, (k0 + k + 1) * h, before, p))
            copy_into(y, W, turn_rate(before, y[Q:Q + 4], h))
        elif mode == HELD:
            turn_attitude(y, inertia, h, mode)
        else:
            apply_turn(y, precession_constant(y, inertia, h), spin, c, sn)
        # |r| - a bounds the height over the ellipsoid from below: the exact height only within
        # a metre of the floor by that bound (a margin far above either's rounding)
        if math.sqrt(y[R] * y[R] + y[R + 1] * y[R + 1] + y[R + 2] * y[R + 2]) - p[P_RADIUS] < floor + 1.0 \
                and radial_height(y, p) < floor:
            return y, k + 1
    return y, n_steps
