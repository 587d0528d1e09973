"""Unit quaternions, scalar first ``(w, x, y, z)``, as compiled kernels.

Convention (docs/physics.md#frames): the attitude
quaternion ``q`` rotates *body axes into the frame* (the inertial frame in a
flight), so a vector with body-axes components ``v_b`` has frame components
``quat_rotate(q, v_b) = q ⊗ (0, v_b) ⊗ q*`` and ``quat_to_matrix(q) @ v_b``.
Composition follows the Hamilton product: if ``q_ab`` takes b-axes into a
and ``q_bc`` takes c-axes into b, then ``quat_multiply(q_ab, q_bc)`` takes
c-axes into a, and its matrix is ``M(q_ab) @ M(q_bc)``.

Every function is compiled with :func:`rocketsim.jit.njit` so the dynamics
kernels can call them; they work the same when called from Python on float64
numpy arrays. They take and return plain arrays of shape (4,), (3,) or (3, 3)
(:func:`hamilton_product` takes and returns components).
"""

from __future__ import annotations

import math

import numpy as np

from rocketsim.jit import njit


@njit(inline="always")     # a few operations: typed in its callers, no kernel of its own
def hamilton_product(aw, ax, ay, az, bw, bx, by, bz):
    """Hamilton product ``a (x) b`` of two quaternions given by their components, as a
    4-tuple (no array: for the hot kernels)."""
    return (aw * bw - ax * bx - ay * by - az * bz,
            aw * bx + ax * bw + ay * bz - az * by,
            aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw)


@njit(inline="always")     # a few operations: typed in its callers, no kernel of its own
def rotate_components(w, ux, uy, uz, vx, vy, vz):
    """The vector ``(vx, vy, vz)`` turned by the unit quaternion ``(w, ux, uy, uz)``, as a
    3-tuple (no array: for the hot kernels): ``v + 2w (u × v) + 2 u × (u × v)``, the
    vector part of ``q ⊗ (0, v) ⊗ q*``."""
    tx = 2.0 * (uy * vz - uz * vy)
    ty = 2.0 * (uz * vx - ux * vz)
    tz = 2.0 * (ux * vy - uy * vx)
    return (vx + w * tx + (uy * tz - uz * ty), vy + w * ty + (uz * tx - ux * tz),
            vz + w * tz + (ux * ty - uy * tx))


@njit(inline="always")     # a few operations: typed in its callers, no kernel of its own
def body_x_components(w, x, y, z):
    """The body x axis (a vehicle's nose) in frame components for the unit quaternion
    ``(w, x, y, z)``, as a 3-tuple (no array: for the hot kernels): the first column of
    :func:`quat_to_matrix`, ``(1 - 2 (y^2 + z^2), 2 (x y + w z), 2 (x z - w y))``."""
    return (1.0 - 2.0 * (y * y + z * z), 2.0 * (x * y + w * z), 2.0 * (x * z - w * y))


@njit
def quat_multiply(a, b):
    """Hamilton product ``a (x) b`` of two quaternions (4,) -> (4,)."""
    out = np.empty(4)
    out[0], out[1], out[2], out[3] = hamilton_product(a[0], a[1], a[2], a[3], b[0], b[1], b[2], b[3])
    return out


@njit
def quat_conjugate(q):
    """Conjugate ``(w, -x, -y, -z)``; the inverse rotation for a unit ``q``."""
    out = np.empty(4)
    out[0] = q[0]
    out[1] = -q[1]
    out[2] = -q[2]
    out[3] = -q[3]
    return out


@njit(inline="always")     # small: typed in its callers, no kernel of its own
def quat_normalize(q):
    """``q`` scaled to unit norm (a zero quaternion gives nan components)."""
    n = math.sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3])
    out = np.empty(4)
    for k in range(4):
        out[k] = q[k] / n
    return out


@njit
def quat_rotate(q, v):
    """Frame components of the body-axes vector ``v`` (3,), ``q`` body -> frame.

    Equal to the vector part of ``q ⊗ (0, v) ⊗ q*`` for a unit ``q``
    (:func:`rotate_components`).
    """
    out = np.empty(3)
    out[0], out[1], out[2] = rotate_components(q[0], q[1], q[2], q[3], v[0], v[1], v[2])
    return out


@njit
def quat_to_matrix(q):
    """Rotation matrix (3, 3) body -> frame of a unit quaternion ``q``."""
    w, x, y, z = q[0], q[1], q[2], q[3]
    m = np.empty((3, 3))
    m[0, 0], m[1, 0], m[2, 0] = body_x_components(w, x, y, z)
    m[0, 1] = 2.0 * (x * y - w * z)
    m[0, 2] = 2.0 * (x * z + w * y)
    m[1, 1] = 1.0 - 2.0 * (x * x + z * z)
    m[1, 2] = 2.0 * (y * z - w * x)
    m[2, 1] = 2.0 * (y * z + w * x)
    m[2, 2] = 1.0 - 2.0 * (x * x + y * y)
    return m


@njit
def quat_from_matrix(m):
    """Unit quaternion (4,) of a rotation matrix (3, 3), with ``w >= 0``.

    Shepperd's method (Shepperd 1978, J. Guidance Control 1(3) 223): take the
    square root of the largest of ``1 + trace``, ``1 + 2 m_ii - trace`` so the
    division that follows is well conditioned for every rotation.
    """
    tr = m[0, 0] + m[1, 1] + m[2, 2]
    out = np.empty(4)
    if tr >= m[0, 0] and tr >= m[1, 1] and tr >= m[2, 2]:
        s = 2.0 * math.sqrt(1.0 + tr)           # s = 4 w
        out[0] = 0.25 * s
        out[1] = (m[2, 1] - m[1, 2]) / s
        out[2] = (m[0, 2] - m[2, 0]) / s
        out[3] = (m[1, 0] - m[0, 1]) / s
    elif m[0, 0] >= m[1, 1] and m[0, 0] >= m[2, 2]:
        s = 2.0 * math.sqrt(1.0 + 2.0 * m[0, 0] - tr)   # s = 4 x
        out[0] = (m[2, 1] - m[1, 2]) / s
        out[1] = 0.25 * s
        out[2] = (m[0, 1] + m[1, 0]) / s
        out[3] = (m[0, 2] + m[2, 0]) / s
    elif m[1, 1] >= m[2, 2]:
        s = 2.0 * math.sqrt(1.0 + 2.0 * m[1, 1] - tr)   # s = 4 y
        out[0] = (m[0, 2] - m[2, 0]) / s
        out[1] = (m[0, 1] + m[1, 0]) / s
        out[2] = 0.25 * s
        out[3] = (m[1, 2] + m[2, 1]) / s
    else:
        s = 2.0 * math.sqrt(1.0 + 2.0 * m[2, 2] - tr)   # s = 4 z
        out[0] = (m[1, 0] - m[0, 1]) / s
        out[1] = (m[0, 2] + m[2, 0]) / s
        out[2] = (m[1, 2] + m[2, 1]) / s
        out[3] = 0.25 * s
    if out[0] < 0.0:
        for k in range(4):
            out[k] = -out[k]
    return quat_normalize(out)


@njit
def quat_from_axis_angle(axis, angle):
    """Quaternion of a right-handed rotation by ``angle`` (rad) about ``axis``.

    ``axis`` (3,) need not be unit length; it is normalised here.
    """
    n = math.sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2])
    s = math.sin(0.5 * angle) / n
    out = np.empty(4)
    out[0] = math.cos(0.5 * angle)
    out[1] = axis[0] * s
    out[2] = axis[1] * s
    out[3] = axis[2] * s
    return out
