"""Powered-descent landing guidance: when to light the landing burn, and where to point and how hard to push.

Re-solved from the navigation state at every guidance cycle, in the pad's
local frame (east, north, up; :class:`rocketsim.guidance.pad.Pad`), the height
being the clearance of the feet (``fc.clearance``: the radar's).

**Vertical channel: a constant deceleration to the ground.** The thrust's
vertical acceleration that brings the fall ``v`` (m/s, down) to the contact
speed ``v_td`` exactly at the ground from the clearance ``h`` at a constant
deceleration is (the kinematics of uniform deceleration, ``v^2 - v_td^2 = 2 a h``)::

    a_up = (v^2 - v_td^2) / (2 h) + g

Flown exactly it stays constant; re-solved every cycle it absorbs the errors of
thrust, mass and drag as they show. A stage whose least thrust outweighs it
cannot hover, and once it has stopped above the ground it cannot come down
softly: so the profile aims at the ground itself, and its deceleration stays the
one planned at ignition down to the contact (a gentler last segment would ask the
engine, slewing its throttle at a finite rate, for a step it cannot follow, and
leave the stage stopped metres up).

**Ignition from the throttle margin.** The burn is lit when the throttle that
profile needs (``m a_up`` of the full thrust ``T``: :func:`throttle_for`), reckoned from where the
stage will be when the engine has come up (``lead`` s on at the present rate of
fall: the ignition's dead time and half the spool-up), reaches ``plan``
(:func:`ignition_throttle`), below ``ceiling`` and once the drag no longer brakes
the fall harder than that profile would (a stage falling supersonic through the
thin upper air slows by itself: :func:`ignition_due`). ``1 - plan`` is the margin
kept for what the prediction missed: the burn can push that much harder, and
down to the engine's least throttle softer.

**From a sideways acceleration to a lean.** Thrust along the nose and the air
on the body: with the nose ``delta`` (rad, sideways) from the airflow's reverse
``b``, the stage's sideways acceleration is ``a_up (b + delta) - K q delta / m``,
the thrust's (``a_up`` its vertical part over the mass) less the body's normal
force at that angle of attack, about ``K q`` per radian (``normal_area``; with the
gimbals' push that holds the angle, fitted on the shipped booster's landing
burns: docs/guidance.md). So the lean that gives ``a`` is
``delta = (a - a_up b) / (a_up - K q / m)``: in thick air (``K q / m > a_up``, about
9 kPa here) the nose leans away from where the stage must go, as in the
descent, and thinner, towards it (in still thin air ``a / a_up``, the thrust's lean
alone); the divisor is kept at least ``least_authority a_up`` in size where the two
nearly cancel, ``delta`` within the bending load ``q_alpha / q`` and the lean from
the vertical within the phase's limit.

**Horizontal channel: Apollo's quadratic guidance to a gate above the pad.**
An acceleration command quadratic in time that meets a target position,
velocity and acceleration at the time to go ``T`` (A. R. Klumpp, "Apollo lunar
descent guidance", Automatica 10, 1974, eq. 7 and its derivation; Cherry's
E-guidance with the terminal acceleration targeted) is, at its start::

    a = a_T + 12 (r_T - r) / T^2 - 6 (v_T + v) / T

With the pad as ``r_T`` and ``v_T = a_T = 0`` horizontally it brings the stage
over the pad with no drift and no lean at the *gate*, ``gate_height`` above the
ground; ``T`` is the time the vertical profile takes to get there, at least
``min_time_to_go``: there the law's gains (``12 / T^2``, ``6 / T``, a damped loop
of about ``sqrt(12) / T`` rad/s) stop growing, so that the loop stays several
times slower than the autopilot that turns the thrust (1 rad/s), whose lag
(``lag`` s) the law also leads: it is re-solved from the state predicted that far
on at the sideways push the engines give now. Below the gate (Apollo's P66, the
vertical descent) the horizontal channel only kills the drift, at the constant
deceleration that brings it to nothing at the contact: ``-v / t_go``, ``t_go`` the
time the vertical profile takes to the ground (the horizontal twin of the vertical
channel, re-solved every cycle: flown exactly, ``v / t_go`` stays constant, the
drift falling linearly to zero); like the law above the gate it leads the autopilot's
``lag``: ``v`` is the drift predicted that far on and ``t_go`` the time left from
there, at least ``terminal_time`` (the command stays finite
at the contact: over that last time the drift decays by ``1/e``; as long as the
autopilot's lag, so that the command does not outrun the nose and reverse the
drift), leaning at most ``terminal_tilt``:
the stage touches down upright and still, a metre or two off rather than sliding.

The thrust direction is the sum of both channels, its lean from the vertical
held within the phase's limit by shortening the horizontal part.

**The throttle.** A rocket engine's thrust in the air is its vacuum thrust, which
the throttle scales, less the ambient pressure on its nozzle's exit, which it does
not: ``T(u) = u T_vac - p A_e`` (docs/physics.md#propulsion). So the throttle that
gives the force ``F`` is ``u = (F + L) / (T + L)`` with ``T`` the full thrust here and
``L = p A_e`` the pressure's loss (:func:`throttle_for`): ``F / T`` alone asks a
throttled engine for less than it needs (5 % at sea level at 60 % throttle on a
Merlin), a shortfall the vertical profile then makes up late, near the ground. :func:`command` gives both; :func:`cutoff_due` says when to cut the
engine (at ``cutoff_height`` of clearance: its tail-off finishes the job, or once
the stage has stopped falling near the ground).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from rocketsim.jit import njit


@dataclass(frozen=True)
class Plan:
    """The landing burn's parameters (SI units, angles in rad)."""

    plan: float = 0.8                   # the throttle the burn is lit at (margin 1 - plan)
    touch_speed: float = 1.0            # m/s down at the contact
    gate_height: float = 30.0           # m of clearance: the vertical descent below it
    min_time_to_go: float = 10.0        # s: the quadratic guidance's shortest time to go
    lag: float = 1.0                    # s: the autopilot's lag, the state is predicted this far on
    max_tilt: float = math.radians(15.0)        # the divert's lean at most
    terminal_tilt: float = math.radians(5.0)    # below the gate
    terminal_time: float = 1.0          # s: the drift's shortest time to go below the gate
    cutoff_height: float = 0.2          # m of clearance
    ceiling: float = 8e3                # m: the burn is lit below this height only
    normal_area: float = 65.0           # m^2 per rad: the body's normal force under thrust over q
    least_authority: float = 0.3        # share of the thrust's push per radian counted on at least
    q_alpha: float = math.radians(80e3)         # the bending load (Pa rad) at most


def profile_acceleration(height: float, fall: float, gravity: float, plan: Plan) -> float:
    """The thrust's vertical acceleration (m/s^2) that brings a ``fall`` (m/s, down) to
    ``plan.touch_speed`` at the ground ``height`` m below at a constant deceleration, against
    ``gravity`` (m/s^2)."""
    return (fall * fall - plan.touch_speed ** 2) / (2.0 * max(height, 1e-3)) + gravity


def gate_speed(height: float, fall: float, plan: Plan) -> float:
    """The fall (m/s) at the gate on the profile flown from ``height``, ``fall``."""
    slowing = (fall * fall - plan.touch_speed ** 2) / (2.0 * max(height, 1e-3))
    return math.sqrt(plan.touch_speed ** 2 + 2.0 * max(slowing, 0.0) * plan.gate_height)


def contact_time(height: float, fall: float, slowing: float, plan: Plan) -> float:
    """The time (s) the vertical profile takes from ``height`` (m) and ``fall`` (m/s, down) to
    the contact at ``plan.touch_speed``, slowing at ``slowing`` (m/s^2; none or less: at the
    present rate of fall)."""
    if slowing > 0.0 and fall > plan.touch_speed:
        return (fall - plan.touch_speed) / slowing
    return height / max(fall, plan.touch_speed)


@njit(inline="always")     # a line of arithmetic: typed in its compiled callers (the landing point's)
def throttle_for(force: float, thrust: float, loss: float = 0.0) -> float:
    """The throttle that gives ``force`` (N) from an engine of full ``thrust`` (N) here, the
    ambient pressure taking ``loss`` (N, ``p A_e``) off at any throttle (see the module)."""
    return (force + loss) / (thrust + loss)


def ignition_throttle(height: float, fall: float, mass: float, thrust: float, gravity: float,
                      lead: float, plan: Plan, loss: float = 0.0) -> float:
    """The throttle of ``thrust`` (N, full; ``loss`` N of it the ambient pressure's) the
    profile needs if lit ``lead`` s from now, falling on at ``fall`` (m/s) meanwhile, for
    ``mass`` (kg) at ``height`` (m)."""
    later = height - fall * lead
    if later <= 0.0:
        return math.inf
    return throttle_for(mass * profile_acceleration(later, fall, gravity, plan), thrust, loss)


def ignition_due(height: float, fall: float, mass: float, thrust: float, gravity: float, drag: float,
                 lead: float, plan: Plan, loss: float = 0.0) -> float:
    """How far the landing burn is from its ignition (lit when this reaches 0 or above):
    the least of ``ignition_throttle - plan.plan`` and, while the ``drag`` (m/s^2, its
    deceleration now) less gravity still brakes the fall harder than the profile would,
    ``(v^2 / 2h) - (drag - g)`` over ``g``, and ``(ceiling - h) / ceiling`` (the rule of
    :func:`rocketsim.guidance.landing_point.fall`)."""
    due = ignition_throttle(height, fall, mass, thrust, gravity, lead, plan, loss) - plan.plan
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
            dynamic_pressure: float, air_velocity, plan: Plan = Plan(), pushing=(0.0, 0.0),
            loss: float = 0.0) -> tuple[np.ndarray, float]:
    """``(direction, throttle)``: the thrust's direction (unit, east, north, up) and the
    throttle of ``thrust`` (N, full) for a stage at ``offset`` (m, east, north of the pad),
    moving at ``velocity`` (m/s, east, north, up over the ground) and ``air_velocity``
    (m/s, the same axes, relative to the air) ``height`` m above the ground, of ``mass``
    (kg) against ``gravity`` (m/s^2), meeting ``dynamic_pressure`` (Pa), its engines
    ``pushing`` it sideways now (m/s^2, east, north: the thrust over the mass along the
    nose's lean), ``loss`` (N) of their full thrust the ambient pressure's."""
    fall = -float(velocity[2])
    up = max(profile_acceleration(height, fall, gravity, plan), 0.0)
    # where the stage will be when the lean asked now is flown: the autopilot's lag
    push = np.asarray(pushing, dtype=float)
    drift = np.asarray(velocity[:2], dtype=float) + push * plan.lag
    horizontal = np.asarray(offset[:2], dtype=float) + (np.asarray(velocity[:2], dtype=float)
                                                        + 0.5 * push * plan.lag) * plan.lag
    if height > plan.gate_height:
        time_to_go = (height - plan.gate_height) / max(fall, 1e-3)
        slowing = up - gravity
        if fall > 0.0 and slowing > 0.0:
            time_to_go = (fall - gate_speed(height, fall, plan)) / slowing
        wanted = quadratic_acceleration(horizontal, drift, max(time_to_go, plan.min_time_to_go))
        tilt = plan.max_tilt
    else:
        wanted = -drift / max(contact_time(height, fall, up - gravity, plan) - plan.lag, plan.terminal_time)
        tilt = plan.terminal_tilt
    # the nose's sideways part ``n`` that gives it: the thrust along the nose less the body's
    # normal force at its angle of attack ``n - b`` (``b`` the airflow's reverse), which pushes
    # the other way: ``up n - k (n - b) = wanted``, ``k = normal_area q / m``
    air = np.asarray(air_velocity, dtype=float)
    airspeed = float(np.linalg.norm(air))
    back = -air[:2] / airspeed if airspeed > 1.0 else np.zeros(2)
    k = plan.normal_area * dynamic_pressure / mass
    gain = up - k
    floor = plan.least_authority * up
    if abs(gain) < floor:
        gain = math.copysign(floor, gain)
    side = up * (np.asarray(wanted, dtype=float) - k * back) / gain
    # the angle of attack within the bending load, the lean within the phase's
    alpha = side / max(up, 1e-9) - back
    largest = plan.q_alpha / max(dynamic_pressure, 1.0)
    size = float(np.linalg.norm(alpha))
    if size > largest:
        side = up * (back + alpha * (largest / size))
    size = float(np.linalg.norm(side))
    cap = up * math.tan(tilt)
    if size > cap:
        side = side * (cap / size)
    vector = np.array((side[0], side[1], up))
    total = float(np.linalg.norm(vector))
    if total == 0.0:
        return np.array((0.0, 0.0, 1.0)), 0.0
    return vector / total, throttle_for(mass * total, thrust, loss)


def cutoff_due(height: float, fall: float, plan: Plan = Plan()) -> bool:
    """Whether to cut the engine: at ``plan.cutoff_height`` of clearance, or once the stage
    rises (``fall`` < 0) within 3 m of the ground."""
    return height <= plan.cutoff_height or (fall < 0.0 and height < 3.0)
