"""Ground contact: legs, engine bells and the body's ends as springs on the ellipsoid, compiled.

docs/physics.md#ground-contact (and docs/physics.md#integrator: within 2 m of
the ground the step is split into sub-steps of at most 5 ms so that stiff leg
springs and friction stay stable). Each contact point ``i`` is fixed in the body at
``(x, y, z)`` (m; x a station above the base). Its height ``h`` above the
central body's ellipsoid is measured along the radius (as
:func:`~rocketsim.dynamics.derivative.radial_height`); below the surface it
is pushed out along the ellipsoid's normal ``n`` and dragged by friction::

    N   = max(0, -k h - c v_n)                 (a spring and a damper that never pull)
    F_t = -mu N v_t / sqrt(|v_t|^2 + eps^2)    (Coulomb friction, regularised)

with ``v`` the point's velocity relative to the ground, which turns with the
body at ``omega_E`` about the inertial z axis, ``v_n = v.n`` and ``v_t`` the
rest. The damper and friction only take energy out; the spring stores it.
``eps`` (m/s, per point) regularises Coulomb's law: below it friction acts as
a damper of ``mu N / eps`` (default
:data:`~rocketsim.constants.FRICTION_REGULARISATION`).

A spring this stiff (a natural frequency of a few hundred rad/s) is what the
sub-steps are for: classical RK4 is stable for ``|lambda| h`` up to about 2.8
(2.78 on the real axis, 2.83 on the imaginary), so a 5 ms sub-step holds a
mode of 250 rad/s and a 20 ms step does not. Every mode counts: the rocking
of the body on its legs (``k r^2 / I``), and friction's damping ``mu N r^2 /
(eps I_roll)`` about the vertical, which for a squat vehicle with wide legs is
the stiffest of all; a vehicle file must keep each ``|lambda|`` below about
2 / 5 ms = 400 /s (this is why ``eps`` is a figure of the leg).
"""

from __future__ import annotations

import math

import numpy as np

from rocketsim.jit import njit
from rocketsim.frames.quaternion import body_x_components, rotate_components
from rocketsim.layout import P_POLAR_RADIUS, P_RADIUS, Q, R
from rocketsim.vehicle.aero import A_GROUND, NO_LOAD, with_force

# columns of AeroArrays.contact
K_X, K_Y, K_Z, K_STIFF, K_DAMP, K_MU, K_EPS = 0, 1, 2, 3, 4, 5, 6
N_CONTACT = 7


@njit
def point_height(px, py, pz, a, b):
    """Height (m) of the point ``(px, py, pz)`` (m) above the ellipsoid (a, b), along the radius."""
    rho2 = px * px + py * py
    z2 = pz * pz
    r2 = rho2 + z2
    return math.sqrt(r2) - a * b / math.sqrt((b * b * rho2 + a * a * z2) / r2)


def footprint(contact: np.ndarray) -> tuple[float, float]:
    """``(d, x_feet)`` (m) of a body standing on the contact points of its lowest
    station ``x_feet`` (its feet, else the base ring): ``d`` the distance from the body
    axis to the nearest edge of their convex hull in the body's y-z plane (``r cos(pi /
    n)`` for ``n`` feet on a ring of radius ``r``); 0 when the feet are fewer than
    three or in a line (no footprint)."""
    from scipy.spatial import ConvexHull, QhullError
    feet = contact[contact[:, K_X] <= contact[:, K_X].min() + 1e-9]
    try:
        hull = ConvexHull(feet[:, K_Y:K_Z + 1])
    except (QhullError, ValueError):
        return 0.0, float(feet[0, K_X])
    edge = float(-hull.equations[:, 2].max())       # unit normals: offset = -distance of the axis
    return max(edge, 0.0), float(feet[0, K_X])


def tip_over_angle(feet: tuple[float, float], x_cm: float) -> float:
    """The tilt (rad, body x from the vertical) past which a body on the
    :func:`footprint` ``feet`` with its centre of mass at station ``x_cm`` (m) falls
    over: ``atan2(d, x_cm - x_feet)``. Tilted further towards the nearest edge, the
    centre of mass stands outside the footprint and gravity turns the body on over
    it (docs/physics.md#ground-contact)."""
    d, x_feet = feet
    return math.atan2(d, x_cm - x_feet)


@njit
def axis_up(y):
    """Cosine of the angle between the body x axis of state ``y`` and the geocentric radial."""
    nx, ny, nz = body_x_components(y[Q], y[Q + 1], y[Q + 2], y[Q + 3])
    x, y_, z = y[R], y[R + 1], y[R + 2]
    return (nx * x + ny * y_ + nz * z) / math.sqrt(x * x + y_ * y_ + z * z)


def contact_heights(y, p, vehicle) -> np.ndarray:
    """Height (m) of each contact point of ``vehicle`` above its ground (the ellipsoid, or
    the flat ground ``aero.ref[A_GROUND]`` above it), along the radius."""
    aero = vehicle.arrays.aero
    return contact_point_heights(y, p, aero.contact, vehicle.mass_properties(y)[1], aero.ref[A_GROUND])


@njit
def contact_point_heights(y, p, contact, x_cm, ground=0.0):
    """Height (m) of each contact point (rows of ``contact``, body stations from the
    base, m) above the ground ``ground`` m over the ellipsoid of ``p``, along the radius,
    for state ``y`` whose centre of mass sits at station ``x_cm`` (m)."""
    out = np.empty(contact.shape[0])
    for i in range(contact.shape[0]):
        out[i] = _contact_point_height(y, p, contact, i, x_cm, ground)
    return out


@njit(borrows=True, inline="always")
def lowest_contact_height(y, p, contact, x_cm, ground=0.0):
    """The least of :func:`contact_point_heights` (m; inf without contact points)."""
    lowest = math.inf
    for i in range(contact.shape[0]):
        lowest = min(lowest, _contact_point_height(y, p, contact, i, x_cm, ground))
    return lowest


@njit(inline="always")     # small: typed in its callers, no kernel of its own
def _contact_point_height(y, p, contact, i, x_cm, ground):
    """Height (m) of contact point ``i`` above the ground (see :func:`contact_point_heights`)."""
    o = rotate_components(y[Q], y[Q + 1], y[Q + 2], y[Q + 3], contact[i, K_X] - x_cm, contact[i, K_Y],
                          contact[i, K_Z])
    return point_height(y[R] + o[0], y[R + 1] + o[1], y[R + 2] + o[2], p[P_RADIUS], p[P_POLAR_RADIUS]) - ground


@njit(borrows=True, inline="always")
def contact_forces(y, x_cm, a, b, spin, contact, ground=0.0):
    """Force (N, body axes) and moment (N m about the centre of mass) of the ground.

    ``y`` the state (inertial position, velocity, attitude ``q`` body ->
    inertial, body rates), ``a``/``b`` the ellipsoid's radii (m), ``spin`` the
    ground's rotation rate about inertial z (rad/s), ``ground`` the height (m) of a flat
    ground above the ellipsoid (0: the ellipsoid itself; its normal is the ellipsoid's).
    """
    load = NO_LOAD
    qw, ux, uy, uz = y[6], y[7], y[8], y[9]
    wx, wy, wz = y[10], y[11], y[12]
    for i in range(contact.shape[0]):
        bx = contact[i, K_X] - x_cm
        by = contact[i, K_Y]
        bz = contact[i, K_Z]
        # the point in inertial axes: r + q b
        ox, oy, oz = rotate_components(qw, ux, uy, uz, bx, by, bz)
        px = y[0] + ox
        py = y[1] + oy
        pz = y[2] + oz
        h = point_height(px, py, pz, a, b) - ground
        if h >= 0.0:
            continue
        # velocity of the point relative to the turning ground: v + q (w x b) - spin z x p
        cx = wy * bz - wz * by
        cy = wz * bx - wx * bz
        cz = wx * by - wy * bx
        tx = 2.0 * (uy * cz - uz * cy)
        ty = 2.0 * (uz * cx - ux * cz)
        tz = 2.0 * (ux * cy - uy * cx)
        vx = y[3] + cx + qw * tx + (uy * tz - uz * ty) + spin * py
        vy = y[4] + cy + qw * ty + (uz * tx - ux * tz) - spin * px
        vz = y[5] + cz + qw * tz + (ux * ty - uy * tx)
        # ellipsoid normal
        nx = px / (a * a)
        ny = py / (a * a)
        nz = pz / (b * b)
        nn = math.sqrt(nx * nx + ny * ny + nz * nz)
        nx /= nn
        ny /= nn
        nz /= nn
        vn = vx * nx + vy * ny + vz * nz
        normal = -contact[i, K_STIFF] * h - contact[i, K_DAMP] * vn
        if normal <= 0.0:
            continue
        sx = vx - vn * nx
        sy = vy - vn * ny
        sz = vz - vn * nz
        eps = contact[i, K_EPS]
        slip = math.sqrt(sx * sx + sy * sy + sz * sz + eps * eps)
        k = -contact[i, K_MU] * normal / slip
        gx = normal * nx + k * sx
        gy = normal * ny + k * sy
        gz = normal * nz + k * sz
        # back to body axes: q* g
        ex, ey, ez = rotate_components(qw, -ux, -uy, -uz, gx, gy, gz)
        load = with_force(load, bx, by, bz, ex, ey, ez)
    return load
