"""Cruise rails: RK4 through the full n-body field, sub-steps sized by the turn.

docs/physics.md#cruise-rails. With ``tau = |v|^2 / |v x a|`` the time the
path takes to turn through a radian:

- a sub-step lasts ``0.02 tau``, never less than 5 s, and is one classical
  RK4 step of position and velocity in the full field (the other bodies
  evaluated at every stage, :func:`rocketsim.dynamics.nbody.field_rk4_step`
  with ``live=True``);
- a cruise step covers at most 1 h, at most a 0.5 deg turn, at most half the
  time to any body's 2 000 km clearance shell or to a sphere-of-influence
  boundary (straight-line closing estimates), never past the program's next
  wake-up, and never an arc the central conic (walked at eight points, the
  other bodies moving on their tangents) shows dipping inside a shell;
- steps are whole multiples of the flight model's step ``h`` so mission time
  stays ``k h``.

When the shells leave less than 5 s the cruise ends (:data:`ENCOUNTER`): the
vehicle flies on at 20 ms before the encounter. When the SOI boundary is
less than two minimum sub-steps away the step is allowed across it and the
cruise ends with :data:`SOI` so the caller hands over
(:func:`rocketsim.dynamics.soi.handover`). The attitude turns by the exact
torque-free motion over each step (:func:`rocketsim.dynamics.rails.turn_attitude`).
"""

from __future__ import annotations

import math

import numpy as np

from rocketsim.jit import njit
from rocketsim.constants import (CRUISE_CLEARANCE, CRUISE_MAX_STEP, CRUISE_MAX_TURN,
                                 CRUISE_MIN_SUBSTEP, CRUISE_TURN_PER_SUBSTEP, EARTH_RADIUS_EQ,
                                 MARS_RADIUS_EQ, MOON_RADIUS, SUN_RADIUS)
from rocketsim.dynamics.nbody import (FIELD_CENTER, FIELD_MU, bodies_at, field_acceleration,
                                      field_rk4_step)
from rocketsim.dynamics.rails import FREE, turn_attitude
from rocketsim.dynamics.soi import SOI_BY_INDEX, central_body, central_params, handover
from rocketsim.layout import P_MU, R, V
from rocketsim.ephemeris.solar_system import BODIES
from rocketsim.orbits.kepler import _propagate_one

DONE = 0          # reached the requested end
ENCOUNTER = 1     # a clearance shell is less than a minimum sub-step away: fly at 20 ms
SOI = 2           # crossed a sphere of influence: hand over, then cruise on

RADII = np.array((SUN_RADIUS, EARTH_RADIUS_EQ, MOON_RADIUS, MARS_RADIUS_EQ))
PARENT_INDEX = np.array((-1, 0, 1, 0))     # sun, earth, moon (of Earth), mars
WALK_POINTS = 8


@njit
def turn_time(y, p, s, fp):
    """``tau = |v|^2 / |v x a|`` (s) with the field's acceleration at ``y``."""
    ax, ay, az = field_acceleration(y[R], y[R + 1], y[R + 2], s, fp, p)
    vx, vy, vz = y[V], y[V + 1], y[V + 2]
    cx = vy * az - vz * ay
    cy = vz * ax - vx * az
    cz = vx * ay - vy * ax
    return (vx * vx + vy * vy + vz * vz) / math.sqrt(cx * cx + cy * cy + cz * cz)


@njit
def _in_field(fp, k):
    return k == int(fp[FIELD_CENTER]) or fp[FIELD_MU + k] != 0.0


@njit
def _closing_time(rx, ry, rz, vx, vy, vz, distance):
    """Time (s) for the range ``|r|`` to fall by ``distance`` at its current rate
    (inf if it is opening)."""
    d = math.sqrt(rx * rx + ry * ry + rz * rz)
    closing = -(rx * vx + ry * vy + rz * vz) / d
    if closing <= 0.0:
        return np.inf
    return distance / closing


@njit
def step_limits(y, t, p, fp):
    """``(limit, sub, soi_time)``: the longest cruise step (s) the turn and the
    shells allow, the sub-step (s), and the time to the nearest SOI boundary
    (s, straight-line estimate). ``limit`` is 0 inside a clearance shell."""
    s, u = bodies_at(fp, t)
    tau = turn_time(y, p, s, fp)
    sub = max(CRUISE_TURN_PER_SUBSTEP * tau, CRUISE_MIN_SUBSTEP)
    limit = min(CRUISE_MAX_STEP, CRUISE_MAX_TURN * tau)
    c = int(fp[FIELD_CENTER])
    soi_time = np.inf
    for k in range(4):
        if not _in_field(fp, k):
            continue
        rx, ry, rz = y[R] - s[k, 0], y[R + 1] - s[k, 1], y[R + 2] - s[k, 2]
        vx, vy, vz = y[V] - u[k, 0], y[V + 1] - u[k, 1], y[V + 2] - u[k, 2]
        d = math.sqrt(rx * rx + ry * ry + rz * rz)
        gap = d - RADII[k] - CRUISE_CLEARANCE
        if gap <= 0.0:
            return 0.0, sub, soi_time
        limit = min(limit, 0.5 * _closing_time(rx, ry, rz, vx, vy, vz, gap))
        if PARENT_INDEX[k] == c:
            soi_time = min(soi_time, _closing_time(rx, ry, rz, vx, vy, vz, d - SOI_BY_INDEX[k]))
        elif k == c and math.isfinite(SOI_BY_INDEX[k]):
            soi_time = min(soi_time, _closing_time(rx, ry, rz, -vx, -vy, -vz, SOI_BY_INDEX[k] - d))
    return limit, sub, soi_time


@njit
def conic_clear(y, t, dt, p, fp):
    """True when the central conic from ``y`` over ``dt`` s stays outside every
    body's clearance shell at :data:`WALK_POINTS` points (other bodies on their
    tangents ``s + u tau``)."""
    s, u = bodies_at(fp, t)
    r_out = np.empty(3)
    v_out = np.empty(3)
    for j in range(1, WALK_POINTS + 1):
        tau = dt * j / WALK_POINTS
        if _propagate_one(p[P_MU], y[R:R + 3], y[V:V + 3], tau, r_out, v_out) < 0:
            return False
        for k in range(4):
            if not _in_field(fp, k):
                continue
            dx = r_out[0] - s[k, 0] - u[k, 0] * tau
            dy = r_out[1] - s[k, 1] - u[k, 1] * tau
            dz = r_out[2] - s[k, 2] - u[k, 2] * tau
            if math.sqrt(dx * dx + dy * dy + dz * dz) < RADII[k] + CRUISE_CLEARANCE:
                return False
    return True


@njit
def outside_soi(y, t, fp):
    """True when ``y`` has left the central body's sphere or entered a child's."""
    c = int(fp[FIELD_CENTER])
    r = math.sqrt(y[R] ** 2 + y[R + 1] ** 2 + y[R + 2] ** 2)
    if r > SOI_BY_INDEX[c]:
        return True
    s = bodies_at(fp, t)[0]
    for k in range(4):
        if PARENT_INDEX[k] == c and _in_field(fp, k):
            d = math.sqrt((y[R] - s[k, 0]) ** 2 + (y[R + 1] - s[k, 1]) ** 2
                          + (y[R + 2] - s[k, 2]) ** 2)
            if d < SOI_BY_INDEX[k]:
                return True
    return False


@njit
def plan_step(y, k, h, k_end, p, fp):
    """``(steps, substeps, reason)`` of the next cruise step from step ``k``.

    ``steps``: whole flight-model steps of ``h`` s the cruise step covers (0
    with ``reason`` :data:`ENCOUNTER` when it cannot start); ``substeps``: RK4
    sub-steps it is divided into.
    """
    t = k * h
    limit, sub, soi_time = step_limits(y, t, p, fp)
    if soi_time < 2.0 * CRUISE_MIN_SUBSTEP:
        limit = min(limit, soi_time + CRUISE_MIN_SUBSTEP)
    else:
        limit = min(limit, 0.5 * soi_time)
    if limit < CRUISE_MIN_SUBSTEP:
        return 0, 1, ENCOUNTER
    n = min(int(math.floor(limit / h)), k_end - k)
    while not conic_clear(y, t, n * h, p, fp):
        n = n // 2
        if n * h < CRUISE_MIN_SUBSTEP and n < k_end - k:
            return 0, 1, ENCOUNTER
    return n, max(1, int(math.ceil(n * h / sub))), DONE


@njit
def cruise_step(y, t, dt, substeps, p, fp, air, inertia):
    """One cruise step of ``dt`` s from mission time ``t`` in ``substeps`` RK4
    sub-steps of the full field; the attitude turns torque-free over ``dt``."""
    sub = dt / substeps
    s = np.zeros((4, 3))
    for j in range(substeps):
        y = field_rk4_step(y, t + j * sub, sub, p, s, fp, air, False, True)
    turn_attitude(y, inertia, dt, FREE)
    return y


@njit
def advance_cruise(y, k0, h, k_end, p, fp, air, inertia):
    """Cruise from step ``k0`` towards step ``k_end`` (mission time ``k h``).

    Returns ``(y, k, reason, n_cruise_steps)``: the state at step ``k`` where
    the cruise stopped, why (:data:`DONE` at ``k_end``, :data:`ENCOUNTER`,
    :data:`SOI`), and how many cruise steps it took.
    """
    k = k0
    count = 0
    while k < k_end:
        n, substeps, reason = plan_step(y, k, h, k_end, p, fp)
        if reason != DONE:
            return y, k, reason, count
        y = cruise_step(y, k * h, n * h, substeps, p, fp, air, inertia)
        k += n
        count += 1
        if outside_soi(y, k * h, fp):
            return y, k, SOI, count
    return y, k, DONE, count


def cruise_through(y, k0: int, h: float, k_end: int, p, fp, air, inertia, gmst0: float = 0.0):
    """Cruise from step ``k0`` to ``k_end``, handing over at every sphere of influence.

    Each :data:`SOI` stop re-centres the state, the parameters' central
    gravity and the field on the new body (:func:`rocketsim.dynamics.soi.handover`)
    and the cruise goes on. Returns ``(y, k, p, fp, reason, handovers)``:
    where and why it stopped (:data:`DONE` or :data:`ENCOUNTER`), the
    parameters and field it ended in, and ``(k, body)`` for every handover.
    """
    handovers = []
    k = k0
    while True:
        new = central_body(y[R:R + 3], fp, k * h)
        if new != BODIES[int(fp[FIELD_CENTER])]:
            r, v, fp = handover(y[R:R + 3], y[V:V + 3], fp, k * h, new, gmst0)
            y = y.copy()
            y[R:R + 3] = r
            y[V:V + 3] = v
            p = central_params(p, new)
            handovers.append((k, new))
        y, k, reason, _ = advance_cruise(y, k, h, k_end, p, fp, air, inertia)
        if reason != SOI:
            return y, k, p, fp, reason, handovers
