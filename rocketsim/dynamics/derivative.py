"""The time derivative of a body's state: Newton and Euler in an inertial frame.

From EQUATIONS.md ("Equations of motion")::

    r' = v
    v' = g(r) + F/m
    q' = 1/2 q (x) (0, w)
    w' = I^-1 (tau - w x (I w)),   I = diag(Ixx, Iyy, Izz)

No Coriolis or centrifugal terms: the frame is inertial. The foundation's
rigid body carries no forces or torques but gravity (point mass + J2 of the
central body); later models add thrust, aerodynamics, RCS and contact to
``F`` and ``tau`` here, evaluated at every RK4 stage.
"""

import numpy as np

from rocketsim._jit import njit
from rocketsim.bodies.gravity import point_mass_j2
from rocketsim.dynamics.state import P_IXX, P_IYY, P_IZZ, P_J2, P_MU, P_RADIUS, Q, R, V, W
from rocketsim.frames.quaternion import quat_multiply


@njit
def derivative(t, y, p, dy):
    """Write ``dy/dt`` of state ``y`` at mission time ``t`` (s) into ``dy``."""
    ax, ay, az = point_mass_j2(y[R], y[R + 1], y[R + 2], p[P_MU], p[P_RADIUS], p[P_J2])
    dy[R] = y[V]
    dy[R + 1] = y[V + 1]
    dy[R + 2] = y[V + 2]
    dy[V] = ax
    dy[V + 1] = ay
    dy[V + 2] = az

    wx, wy, wz = y[W], y[W + 1], y[W + 2]
    dq = quat_multiply(y[Q:Q + 4], np.array((0.0, wx, wy, wz)))
    for k in range(4):
        dy[Q + k] = 0.5 * dq[k]

    ixx, iyy, izz = p[P_IXX], p[P_IYY], p[P_IZZ]
    # Euler: I w' = tau - w x (I w); tau = 0 for the foundation's rigid body
    hx, hy, hz = ixx * wx, iyy * wy, izz * wz
    dy[W] = -(wy * hz - wz * hy) / ixx
    dy[W + 1] = -(wz * hx - wx * hz) / iyy
    dy[W + 2] = -(wx * hy - wy * hx) / izz
    for k in range(13, y.shape[0]):
        dy[k] = 0.0
