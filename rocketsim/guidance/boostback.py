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

each at most MAX_PASS_STEP long; warm-started from the last cycle's ``v_go`` a
pass keeps up with the burn. :func:`cutoff_due` says when the engines must be
commanded off: when what is left to gain is what the thrust gives in half a
guidance step and the tail-off (a linear decay: half of its duration at full
thrust), measured along the thrust: the part of ``v_go`` across it, which the stage
cannot turn to in time, is left to the later phases. Units SI; vectors in one frame (the caller's: Earth-fixed for the
landing point).
"""

from __future__ import annotations

from typing import Callable

import numpy as np

DV_STEP = 1.0             # m/s: the finite-difference step of the Jacobian
MAX_PASS_STEP = 500.0     # m/s: the longest correction of one pass


def velocity_to_gain(miss: Callable[[np.ndarray], np.ndarray], v, axes, guess=None, passes: int = 2) -> np.ndarray:
    """``v_go`` (m/s, 3): the change of the velocity ``v`` (m/s) along the two directions
    ``axes`` (2 x 3, unit rows) that brings ``miss(v)`` (a 2-vector, m) to zero, from
    ``v + guess`` after ``passes`` Newton passes (see the module)."""
    v = np.asarray(v, dtype=float)
    axes = np.asarray(axes, dtype=float)
    trial = v + (np.zeros(3) if guess is None else np.asarray(guess, dtype=float))
    for _ in range(passes):
        m0 = np.asarray(miss(trial), dtype=float)
        jacobian = np.empty((2, 2))
        for k in range(2):
            jacobian[:, k] = (np.asarray(miss(trial + DV_STEP * axes[k]), dtype=float) - m0) / DV_STEP
        correction = -np.linalg.solve(jacobian, m0) @ axes
        size = float(np.linalg.norm(correction))
        if size > MAX_PASS_STEP:
            correction *= MAX_PASS_STEP / size
        trial = trial + correction
    return trial - v


def cutoff_due(to_gain, thrust_direction, acceleration: float, step: float, tail_off: float) -> bool:
    """Whether engines giving ``acceleration`` (m/s^2) along ``thrust_direction`` (unit) must
    be commanded off now with ``to_gain`` (m/s, a vector, the same axes) left: when its part
    along the thrust is at most what half a guidance ``step`` (s) and the ``tail_off`` (s,
    linear to zero: half of it at full thrust) give. The part across the thrust, which the
    stage can no longer turn to in time, is left to the later phases."""
    along = float(np.dot(to_gain, thrust_direction))
    return along <= acceleration * 0.5 * (step + tail_off)
