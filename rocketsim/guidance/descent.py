"""Descent steering: the lean that flies the predicted landing point onto the target.

A predictor-corrector (the scheme of numerical predictor-corrector entry
guidance: P. Lu, "Predictor-corrector entry guidance for low-lifting
vehicles", J. Guidance, Control, and Dynamics 31(4), 2008, sec. II: predict
the rest of the flight with the present control held, correct the control by
Newton's method on the miss). The control is a two-component *lean*
(east, north), held in the prediction to the end of the phase:

* in the **entry burn**, the horizontal share of the thrust: the engines push
  along ``-v_a / |v_a| + lean`` (:data:`rocketsim.guidance.landing_point.ENTRY_LEAN_E`);
* in the **aerodynamic descent**, the share (a vector, at most 1 long) of the
  largest lean the body falling tail first may take, the lift it gives pushing
  along it (:data:`rocketsim.guidance.landing_point.LEAN_E`), the grid fins holding
  the angle of attack.

:func:`solve_lean` takes one Newton step on ``miss(lean)`` (east and north of the
predicted landing point about the target, m) with the 2 x 2 Jacobian by forward
differences, and keeps the lean within a limit (its length). One step per
guidance cycle, from the last cycle's lean, keeps up with a miss that changes as
the flight goes (the prediction is re-made from the navigation state each time).

Turning a lean into an attitude (ECI unit vectors, what ``fc.point_at`` takes):

* :func:`thrust_direction`: ``-v_a / |v_a| + lean``, normalised;
* :func:`lean_attitude`: a body falling tail first, its nose a small angle ``alpha``
  from ``-v_a``, feels its normal force on the side away from the nose (the
  crossflow and the base's lift outweigh the axial force's tilt: measured on the
  shipped booster, docs/guidance.md), so to push towards ``d`` it leans its nose away
  from ``d``; ``alpha`` is the share's length times the largest lean allowed, the
  least of ``q_alpha / q`` (the bending load the structure takes, with a margin:
  docs/physics.md#structural-limits) and an angle.

**The entry burn's end: one condition, solved for.** The entry burn ends at an
airspeed, and the prediction ends it at the same one. The lowest airspeed the
burn is flown down to (a heating and loads choice) is the aim, but a stage short of
propellant must stop it earlier, to keep what the landing burn needs.
:func:`entry_end_speed` finds the lowest airspeed, at or above that aim, at which
the propellant predicted at touchdown (``kept(speed)``: the entry burn ended there,
the landing burn flown as planned, less a stated margin) is not short: the root of
``kept`` by Brent's method (R. P. Brent, *Algorithms for Minimization without
Derivatives*, Prentice-Hall 1973, ch. 4; :func:`scipy.optimize.brentq`). ``kept``
rises with the speed (a burn ended earlier burns less; the air brakes the faster
fall before the landing burn), and the root moves smoothly with the state, so a
prediction made with it moves smoothly too; ending the burn on whichever of an
airspeed or a propellant floor comes first would make the predicted point jump
where the two cross (a kink no Newton step on the lean follows).
"""

from __future__ import annotations

import math
from typing import Callable

import numpy as np
from scipy.optimize import brentq

LEAN_STEP = 0.01            # the finite-difference step of the lean (a share: thrust or L/D)


def solve_lean(miss: Callable[[np.ndarray], np.ndarray], lean, limit: float,
               step: float = LEAN_STEP) -> tuple[np.ndarray, np.ndarray]:
    """``(lean, miss)``: one Newton step from ``lean`` (2,) on ``miss(lean)`` (2, m), the new
    lean at most ``limit`` long, and the miss at the old lean."""
    lean = np.asarray(lean, dtype=float)
    m0 = np.asarray(miss(lean), dtype=float)
    jacobian = np.empty((2, 2))
    for k in range(2):
        trial = lean.copy()
        trial[k] += step
        jacobian[:, k] = (np.asarray(miss(trial), dtype=float) - m0) / step
    try:
        new = lean - np.linalg.solve(jacobian, m0)
    except np.linalg.LinAlgError:       # no authority (out of the air): hold the lean
        new = lean
    size = float(np.linalg.norm(new))
    if size > limit:
        new *= limit / size
    return new, m0


def thrust_direction(back, lean) -> np.ndarray:
    """The thrust direction (unit) of a burn against the air: ``back`` (unit, the
    air-relative velocity's reverse) plus ``lean`` (the horizontal share, same axes)."""
    d = np.asarray(back, dtype=float) + np.asarray(lean, dtype=float)
    return d / np.linalg.norm(d)


def lean_attitude(back, push, alpha: float) -> np.ndarray:
    """The nose (unit) of a body falling tail first that leans ``alpha`` (rad) from
    ``back`` (unit, the air-relative velocity's reverse) so that its lift pushes it
    along ``push`` (any length, the same axes; the part across ``back`` counts)."""
    back = np.asarray(back, dtype=float)
    across = np.asarray(push, dtype=float)
    across = across - (across @ back) * back
    size = float(np.linalg.norm(across))
    if size == 0.0 or alpha <= 0.0:
        return back
    return math.cos(alpha) * back - math.sin(alpha) * across / size


class LeanTrim:
    """An integral trim of a commanded lean: the autopilot turns the nose by a torque in
    proportion to its error (docs/physics.md#autopilot: no integral action), and a body
    falling tail first pushes back on a lean with its own aerodynamic stability, so it
    holds only part of the lean asked (measured on the shipped booster: about 25 kPa deg
    of ``q alpha`` subsonic whatever was asked). The trim adds to the lean wanted the
    integral of what the nose falls short of it, ``b += (wanted - flown) dt / time_constant``,
    ``b`` at most ``limit`` (rad) long, and commands ``wanted + b``. Leans are sideways
    vectors of the nose from the airflow's reverse (rad, any two horizontal axes)."""

    def __init__(self, time_constant: float, limit: float):
        self.time_constant = time_constant
        self.limit = limit
        self.bias = np.zeros(2)
        self._last = None

    def command(self, wanted, flown, time: float) -> np.ndarray:
        """The lean to command at mission ``time`` (s) for the lean ``wanted`` when the nose
        holds ``flown`` now."""
        wanted = np.asarray(wanted, dtype=float)
        if self._last is not None:
            dt = max(time - self._last, 0.0)
            self.bias = self.bias + (wanted - np.asarray(flown, dtype=float)) * dt / self.time_constant
            size = float(np.linalg.norm(self.bias))
            if size > self.limit:
                self.bias *= self.limit / size
        self._last = time
        return wanted + self.bias


SPEED_TOLERANCE = 0.05      # m/s: the entry burn's end speed is solved to this


def entry_end_speed(kept: Callable[[float], float], lowest: float, highest: float,
                    guess: float | None = None, width: float = 10.0) -> float:
    """The entry burn's end airspeed (m/s): ``lowest`` when the propellant ``kept(lowest)``
    (kg beyond the margin, at touchdown) is not short, else the root of ``kept`` up to
    ``highest`` (``highest`` itself when even ending there leaves it short: the landing
    cannot keep its margin). ``guess`` (the last cycle's answer) tries the bracket
    ``guess -+ width`` first (see the module)."""
    if kept(lowest) >= 0.0:
        return lowest
    if guess is not None:
        low, high = max(lowest, guess - width), min(highest, guess + width)
        if low < high and kept(low) < 0.0 <= kept(high):
            return float(brentq(kept, low, high, xtol=SPEED_TOLERANCE))
    if kept(highest) < 0.0:
        return highest
    return float(brentq(kept, lowest, highest, xtol=SPEED_TOLERANCE))
