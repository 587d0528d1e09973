"""Boost-back targeting: the velocity to gain that puts the predicted landing point on the target.

Velocity-to-be-gained guidance (R. H. Battin, *An Introduction to the
Mathematics and Methods of Astrodynamics*, AIAA 1987, sec. 14.6-14.7: the
required velocity and ``v_go = v_req - v``; the burn steers along ``v_go`` and
ends when it is gained). Here the required velocity is that of a stage at its
present position whose predicted landing point (any predictor: through the
day's air with the planned entry and landing burns,
:class:`rocketsim.guidance.landing_point.LandingPoint`) is the target moved by
a chosen aim-off. The landing point's miss ``m(v)`` (east and north, m, about
the target) is two conditions; the change of velocity is sought in a plane
spanned by two given directions (a boost-back's: the local horizontal, so that
the burn turns the flight back rather than diving it into the ground), by Newton
passes

    dv = -B J^-1 m(v),    J = dm/dv B (2 x 2, forward differences of DV_STEP along
                          the plane's axes B, 3 x 2)

each at most MAX_PASS_STEP long and halved while it does not shrink the miss (a
predicted landing point is smooth in the velocity only piecewise: a burn that ends on
the propellant left, or a landing burn that runs its tanks dry, bends it); warm-started from the last cycle's ``v_go`` a
pass keeps up with the burn. The burn takes time, and the stage flies on
meanwhile: :func:`after_burn` gives the state at the burn's end for a velocity
change ``dv`` gained at a constant ``acceleration`` along it in a uniform
gravity field (the field at the start; the rotating frame's terms are left to the
next cycle's re-solution), ``t_b = |dv| / a``::

    r_b = r + (v + dv / 2) t_b + g t_b^2 / 2,    v_b = v + dv + g t_b

so that the miss of the state at the burn's end is what ``v_go`` is solved for, and its
direction holds still as the burn goes on (an impulsive ``v_go`` turns as gravity and
the flight change the state, and a stage that turns to follow it is left spinning at
cut-off). :func:`cutoff_due` says when the engines must be
commanded off: when what is left to gain is what the thrust gives in half a
guidance step and the tail-off (a linear decay: half of its duration at full
thrust), measured along the thrust: the part of ``v_go`` across it, which the stage
cannot turn to in time, is left to the later phases. Units SI; vectors in one frame (the caller's: Earth-fixed for the
landing point).
"""

from __future__ import annotations

import math
from typing import Callable

import numpy as np

from rocketsim.frames.vectors import cross

DV_STEP = 1.0             # m/s: the finite-difference step of the Jacobian
MAX_PASS_STEP = 500.0     # m/s: the longest correction of one pass
HALVINGS = 3              # halvings of a pass's step that does not shrink the miss


def velocity_to_gain(miss: Callable[[np.ndarray], np.ndarray], v, axes, guess=None, passes: int = 2) -> np.ndarray:
    """``v_go`` (m/s, 3): the change of the velocity ``v`` (m/s) along the two directions
    ``axes`` (2 x 3, orthonormal rows) that brings ``miss(v)`` (a 2-vector, m) to zero, from
    ``v`` plus ``guess``'s part in their plane, after ``passes`` Newton passes, each step
    halved (up to HALVINGS times) while it does not shrink the miss (see the module)."""
    v = np.asarray(v, dtype=float)
    axes = np.asarray(axes, dtype=float)
    # the guess (the last cycle's v_go) in today's plane: the plane turns as the stage flies
    trial = v + (np.zeros(3) if guess is None else axes.T @ (axes @ np.asarray(guess, dtype=float)))
    m0 = np.asarray(miss(trial), dtype=float)
    for _ in range(passes):
        jacobian = np.empty((2, 2))
        for k in range(2):
            jacobian[:, k] = (np.asarray(miss(trial + DV_STEP * axes[k]), dtype=float) - m0) / DV_STEP
        correction = -np.linalg.solve(jacobian, m0) @ axes
        size = float(np.linalg.norm(correction))
        if size > MAX_PASS_STEP:
            correction *= MAX_PASS_STEP / size
        for _ in range(HALVINGS + 1):
            m1 = np.asarray(miss(trial + correction), dtype=float)
            if m1 @ m1 < m0 @ m0:
                break
            correction *= 0.5
        else:
            break                       # no step along the Newton direction helps: stay
        trial, m0 = trial + correction, m1
    return trial - v


def burn_plane(r, along, dip: float) -> np.ndarray:
    """The plane (2 x 3, orthonormal rows) a boost-back's ``v_go`` is sought in at the position
    ``r`` (m): the local horizontal across ``along`` (any vector with a horizontal part: the
    burn's direction over the ground), and ``along``'s horizontal direction tilted ``dip``
    (rad) below the horizontal. A dip trades the burn's horizontal work for a lower apex:
    a shorter, slower fall into the air, which the entry and landing burns pay less to
    stop."""
    r = np.asarray(r, dtype=float)
    up = r / float(np.linalg.norm(r))
    h = np.asarray(along, dtype=float)
    h = h - (h @ up) * up
    h /= float(np.linalg.norm(h))
    return np.array((cross(up, h), math.cos(dip) * h - math.sin(dip) * up))


def after_burn(r, v, dv, acceleration: float, mu: float):
    """``(r_b, v_b, t_b)``: position (m), velocity (m/s) and duration (s) at the end of a burn
    that changes the velocity ``v`` (m/s) at position ``r`` (m) by ``dv`` (m/s) at a constant
    ``acceleration`` (m/s^2) along it, under the point-mass gravity ``mu`` (m^3/s^2) at
    ``r`` (see the module)."""
    r = np.asarray(r, dtype=float)
    dv = np.asarray(dv, dtype=float)
    t = float(np.linalg.norm(dv)) / acceleration
    cube = float(r @ r) ** 1.5
    # component by component: numpy's operations in numpy's order, without three-element arrays
    (rx, ry, rz), (vx, vy, vz), (dx, dy, dz) = r.tolist(), np.asarray(v, dtype=float).tolist(), dv.tolist()
    gx, gy, gz = -mu * rx / cube, -mu * ry / cube, -mu * rz / cube
    return (np.array((rx + (vx + 0.5 * dx) * t + 0.5 * gx * t * t, ry + (vy + 0.5 * dy) * t + 0.5 * gy * t * t,
                      rz + (vz + 0.5 * dz) * t + 0.5 * gz * t * t)),
            np.array((vx + dx + gx * t, vy + dy + gy * t, vz + dz + gz * t)), t)


def cutoff_due(to_gain, thrust_direction, acceleration: float, step: float, tail_off: float) -> bool:
    """Whether engines giving ``acceleration`` (m/s^2) along ``thrust_direction`` (unit) must
    be commanded off now with ``to_gain`` (m/s, a vector, the same axes) left: when its part
    along the thrust is at most what half a guidance ``step`` (s) and the ``tail_off`` (s,
    linear to zero: half of it at full thrust) give. The part across the thrust, which the
    stage can no longer turn to in time, is left to the later phases."""
    along = float(np.dot(to_gain, thrust_direction))
    return along <= acceleration * 0.5 * (step + tail_off)
