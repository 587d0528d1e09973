"""Powered-descent landing guidance: when to light the landing burn, and where to point and how hard to push.

Re-solved from the navigation state at every guidance cycle, in the pad's
local frame (east, north, up; :class:`rocketsim.guidance.pad.Pad`), the height
being the clearance of the feet (``fc.clearance``: the radar's).

**Vertical channel: constant decelerations to a gate, then to the ground.** The
thrust's vertical acceleration that brings the fall ``v`` (m/s, down) to a speed
``v_1`` exactly ``h - h_1`` lower at a constant deceleration is (the kinematics
of uniform deceleration, ``v^2 - v_1^2 = 2 a (h - h_1)``)::

    a_up = (v^2 - v_1^2) / (2 (h - h_1)) + g

Above the gate (``h_1 = gate_height``) ``v_1`` is the speed from which the gentle
``terminal_deceleration`` reaches ``touch_speed`` at the ground; below it ``h_1 = 0``
and ``v_1 = touch_speed``. Flown exactly each stays constant; re-solved every
cycle it absorbs the errors of thrust, mass and drag as they show. A stage whose
least thrust outweighs it cannot hover, so the profile aims at the ground
itself, never above it, and slows gently over the last metres (the terminal
deceleration, above what the least thrust gives the empty stage) so that the
contact speed does not hang on the last tenth of a second.

**Ignition from the throttle margin.** The burn is lit when the throttle that
profile needs (``m a_up / T``, ``T`` the full thrust), reckoned from where the
stage will be when the engine has come up (``lead`` s on at the present rate of
fall: the ignition's dead time and half the spool-up), reaches ``plan``
(:func:`ignition_throttle`), below ``ceiling`` and once the drag no longer brakes
the fall harder than that profile would (a stage falling supersonic through the
thin upper air slows by itself: :func:`ignition_due`). ``1 - plan`` is the margin
kept for what the prediction missed: the burn can push that much harder, and
down to the engine's least throttle softer.

**Horizontal channel, in thick air: braking against the velocity.** While the
dynamic pressure is above ``divert_pressure`` the thrust leans against the
ground velocity (its vertical part the profile's), as the descent's prediction
flew it (:mod:`rocketsim.guidance.landing_point`): there, leaning the thrust
buys little, the body's normal force at the angle of attack pushing the other
way (measured on the shipped booster: docs/guidance.md).

**Horizontal channel, below it: Apollo's quadratic guidance to a gate above the pad.**
An acceleration command quadratic in time that meets a target position,
velocity and acceleration at the time to go ``T`` (A. R. Klumpp, "Apollo lunar
descent guidance", Automatica 10, 1974, eq. 7 and its derivation; Cherry's
E-guidance with the terminal acceleration targeted) is, at its start::

    a = a_T + 12 (r_T - r) / T^2 - 6 (v_T + v) / T

With the pad as ``r_T`` and ``v_T = a_T = 0`` horizontally it brings the stage
over the pad with no drift and no lean ``settle_time`` before the *gate*,
``gate_height`` above the ground; ``T`` is the time the vertical profile takes
to get there less ``settle_time`` (at least ``min_time_to_go``). From then on
(and through Apollo's P66, the vertical descent below the gate) the horizontal
channel only kills the drift and what is left of the offset, critically damped
with time constant ``terminal_time`` (slower than the autopilot's turn, so the
lean it asks for is flown), leaning at most ``settle_tilt``; below the gate it
only kills the drift (``-v / terminal_time``), leaning at most ``terminal_tilt``:
the stage touches down upright and still, a metre or two off rather than
sliding.

The thrust direction is the sum of both channels, its lean from the vertical
held within the phase's limit by shortening the horizontal part; the throttle is the mass times that acceleration over the full
thrust. :func:`command` gives both; :func:`cutoff_due` says when to cut the
engine (at ``cutoff_height`` of clearance: its tail-off finishes the job, or once
the stage has stopped falling near the ground).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Plan:
    """The landing burn's parameters (SI units, angles in rad)."""

    plan: float = 0.8                   # the throttle the burn is lit at (margin 1 - plan)
    touch_speed: float = 1.0            # m/s down at the contact
    gate_height: float = 25.0           # m of clearance: the vertical descent below it
    settle_time: float = 3.0            # s: the divert ends this long before the gate
    min_time_to_go: float = 2.0         # s: the quadratic guidance's shortest time to go
    max_tilt: float = math.radians(15.0)        # the divert's lean at most
    settle_tilt: float = math.radians(6.0)      # from the divert's end to the gate
    terminal_tilt: float = math.radians(3.0)    # below the gate
    terminal_time: float = 2.5          # s: the drift's time constant after the divert
    terminal_deceleration: float = 3.0  # m/s^2 below the gate
    cutoff_height: float = 0.2          # m of clearance
    ceiling: float = 8e3                # m: the burn is lit below this height only
    divert_pressure: float = 15e3       # Pa: the burn brakes against the velocity above this


def gate_speed(plan: Plan) -> float:
    """The fall (m/s) at the gate: what the terminal deceleration slows to ``touch_speed``
    over ``gate_height``."""
    return math.sqrt(plan.touch_speed ** 2 + 2.0 * plan.terminal_deceleration * plan.gate_height)


def profile_acceleration(height: float, fall: float, gravity: float, plan: Plan) -> float:
    """The thrust's vertical acceleration (m/s^2) of the profile: above the gate, the
    constant deceleration that brings a ``fall`` (m/s, down) to :func:`gate_speed` at the
    gate; below it, the one that brings it to ``touch_speed`` at the ground; against
    ``gravity`` (m/s^2), ``height`` m above the ground."""
    if height > plan.gate_height:
        return (fall * fall - gate_speed(plan) ** 2) / (2.0 * (height - plan.gate_height)) + gravity
    return (fall * fall - plan.touch_speed ** 2) / (2.0 * max(height, 1e-3)) + gravity


def ignition_throttle(height: float, fall: float, mass: float, thrust: float, gravity: float,
                      lead: float, plan: Plan) -> float:
    """The throttle of ``thrust`` (N, full) the profile needs if lit ``lead`` s from now,
    falling on at ``fall`` (m/s) meanwhile, for ``mass`` (kg) at ``height`` (m)."""
    later = height - fall * lead
    if later <= 0.0:
        return math.inf
    return mass * profile_acceleration(later, fall, gravity, plan) / thrust


def ignition_due(height: float, fall: float, mass: float, thrust: float, gravity: float, drag: float,
                 lead: float, plan: Plan) -> float:
    """How far the landing burn is from its ignition (lit when this reaches 0 or above):
    the least of ``ignition_throttle - plan.plan`` and, while the ``drag`` (m/s^2, its
    deceleration now) less gravity still brakes the fall harder than the profile would,
    ``(v^2 / 2h) - (drag - g)`` over ``g``, and ``(ceiling - h) / ceiling`` (the rule of
    :func:`rocketsim.guidance.landing_point.fall`)."""
    due = ignition_throttle(height, fall, mass, thrust, gravity, lead, plan) - plan.plan
    braking = (fall * fall / (2.0 * max(height, 1e-3)) - (drag - gravity)) / gravity
    return min(due, braking, (plan.ceiling - height) / plan.ceiling)


def quadratic_acceleration(offset, velocity, time_to_go: float, target_acceleration=0.0):
    """Klumpp's command (m/s^2) at the start of a quadratic-acceleration path from ``offset``
    (m, from the target) and ``velocity`` (m/s) to the target at rest with
    ``target_acceleration`` in ``time_to_go`` s (arrays of any matching shape)."""
    offset = np.asarray(offset, dtype=float)
    velocity = np.asarray(velocity, dtype=float)
    return target_acceleration - 12.0 * offset / time_to_go ** 2 - 6.0 * velocity / time_to_go


def command(offset, velocity, height: float, mass: float, thrust: float, gravity: float,
            dynamic_pressure: float, plan: Plan = Plan()) -> tuple[np.ndarray, float]:
    """``(direction, throttle)``: the thrust's direction (unit, east, north, up) and the
    throttle of ``thrust`` (N, full) for a stage at ``offset`` (m, east, north of the pad),
    moving at ``velocity`` (m/s, east, north, up over the ground) ``height`` m above the
    ground, of ``mass`` (kg) against ``gravity`` (m/s^2), meeting ``dynamic_pressure`` (Pa)."""
    fall = -float(velocity[2])
    horizontal = np.asarray(offset[:2], dtype=float)
    drift = np.asarray(velocity[:2], dtype=float)
    up = max(profile_acceleration(height, fall, gravity, plan), 0.0)
    if dynamic_pressure > plan.divert_pressure and fall > 0.0:
        # braking against the velocity, as the descent's prediction flew it
        cap = math.tan(plan.max_tilt)
        side = drift / fall
        size = float(np.linalg.norm(side))
        side = -up * (side if size <= cap else side * (cap / size))
    else:
        time_to_go = 0.0                    # to the gate, on the vertical profile
        slowing = up - gravity
        if height > plan.gate_height and fall > 0.0:
            time_to_go = (fall - gate_speed(plan)) / slowing if slowing > 0.0 else \
                (height - plan.gate_height) / fall
        if time_to_go - plan.settle_time > plan.min_time_to_go:
            side = quadratic_acceleration(horizontal, drift, time_to_go - plan.settle_time)
            tilt = plan.max_tilt
        elif height > plan.gate_height:
            tau = plan.terminal_time
            side = -2.0 * drift / tau - horizontal / tau ** 2
            tilt = plan.settle_tilt
        else:
            side = -drift / plan.terminal_time
            tilt = plan.terminal_tilt
        size = float(np.linalg.norm(side))
        cap = up * math.tan(tilt)
        if size > cap:
            side = side * (cap / size)
    wanted = np.array((side[0], side[1], up))
    total = float(np.linalg.norm(wanted))
    if total == 0.0:
        return np.array((0.0, 0.0, 1.0)), 0.0
    return wanted / total, mass * total / thrust


def cutoff_due(height: float, fall: float, plan: Plan = Plan()) -> bool:
    """Whether to cut the engine: at ``plan.cutoff_height`` of clearance, or once the stage
    rises (``fall`` < 0) within 3 m of the ground."""
    return height <= plan.cutoff_height or (fall < 0.0 and height < 3.0)
