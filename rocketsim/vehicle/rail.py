"""A launch rail: the vehicle slides along a straight rail fixed to the ground, compiled.

docs/physics.md#launch-rail. The rail starts where the vehicle's centre of mass
stands at launch, ``x0`` (Earth-fixed, m), and points along the unit vector
``u`` (Earth-fixed: the rail's inclination above the horizon towards its
heading). The ground turns at ``omega`` (the central body's spin about the
frame's z), so in the inertial frame the rail's point and axis are
``R(t) x0`` and ``R(t) u``. On the rail the vehicle keeps its attitude in the
turning frame (its body rates are the ground's turn, and no torque acts) and
moves only along the rail: its travel ``s = (r - R x0) . R u`` obeys

    s'' = (a - omega x (omega x r)) . R u

with ``a`` the acceleration every force and gravity would give the free
body (thrust, drag and weight along the rail; the rest is the rail's normal
force, which also takes the Coriolis term, perpendicular to the rail), and
the inertial acceleration is then

    r'' = s'' R u + 2 s' omega x R u + omega x (omega x r).

The rail's foot holds the vehicle: at or below its start (``s <= 0``, to
:data:`RAIL_FOOT`) the travel never accelerates backwards (``s'' >= 0``; a
vehicle sliding back down is stopped over :data:`RAIL_STOP_TIME`). The vehicle leaves the rail when its
travel reaches the rail's length less the height of its last (aft) rail button
above its base (the base stands at the rail's foot); the integrator cuts
the step at that instant (:func:`rocketsim.dynamics.rk4.step`) and records it
with the speed along the rail in the array.

``rail`` (:data:`N_RAIL`,): the columns below; ``RL_ON`` is 0 for a vehicle
without a rail (or after it has left).
"""

from __future__ import annotations

import math

import numpy as np

from rocketsim.jit import njit
from rocketsim.layout import R, V

RL_ON = 0           # 1 while on the rail
RL_TRAVEL = 1       # m, travel along the rail until the last button leaves it
RL_X0 = 2           # m, Earth-fixed start of the centre of mass (3 columns)
RL_U = 5            # Earth-fixed unit vector along the rail (3 columns)
RL_OFF_AT = 8       # s, mission time the vehicle left the rail (nan before)
RL_OFF_SPEED = 9    # m/s, speed along the rail at that instant
N_RAIL = 10
RAIL_STOP_TIME = 0.01   # s: a vehicle sliding back below the rail's start is stopped this fast
# m: the foot holds the vehicle this far above its start too, so the rounding of a
# position that turns with the ground (~1e-9 m at Earth's radius) never lets it fall
RAIL_FOOT = 1e-6


def no_rail() -> np.ndarray:
    """The rail array of a vehicle that has none."""
    rail = np.zeros(N_RAIL)
    rail[RL_OFF_AT] = math.nan
    return rail


@njit(borrows=True)
def rail_axes(t, spin, rail):
    """``(x0, u)``: the rail's start and unit axis in the inertial frame at mission time ``t``."""
    c = math.cos(spin * t)
    s = math.sin(spin * t)
    x0 = (c * rail[RL_X0] - s * rail[RL_X0 + 1], s * rail[RL_X0] + c * rail[RL_X0 + 1], rail[RL_X0 + 2])
    u = (c * rail[RL_U] - s * rail[RL_U + 1], s * rail[RL_U] + c * rail[RL_U + 1], rail[RL_U + 2])
    return x0, u


@njit(borrows=True)
def rail_travel(y, t, spin, rail):
    """``(s, s')``: travel (m) along the rail and its rate (m/s, relative to the ground)."""
    x0, u = rail_axes(t, spin, rail)
    s = (y[R] - x0[0]) * u[0] + (y[R + 1] - x0[1]) * u[1] + (y[R + 2] - x0[2]) * u[2]
    rate = (y[V] + spin * y[R + 1]) * u[0] + (y[V + 1] - spin * y[R]) * u[1] + y[V + 2] * u[2]
    return s, rate


@njit(borrows=True, inline="always")
def constrain_to_rail(t, y, dy, spin, rail):
    """Replace the free acceleration ``dy[V:V+3]`` (m/s^2, inertial) by the motion along the
    rail (module docstring) and hold the body rates (``dy[W]`` is the caller's)."""
    x0, u = rail_axes(t, spin, rail)
    s = (y[R] - x0[0]) * u[0] + (y[R + 1] - x0[1]) * u[1] + (y[R + 2] - x0[2]) * u[2]
    rate = (y[V] + spin * y[R + 1]) * u[0] + (y[V + 1] - spin * y[R]) * u[1] + y[V + 2] * u[2]
    w2 = spin * spin
    cx, cy = -w2 * y[R], -w2 * y[R + 1]                 # omega x (omega x r)
    along = (dy[V] - cx) * u[0] + (dy[V + 1] - cy) * u[1] + dy[V + 2] * u[2]
    if s <= RAIL_FOOT and along < 0.0:
        along = -rate / RAIL_STOP_TIME if rate < 0.0 else 0.0
    dy[V] = along * u[0] - 2.0 * rate * spin * u[1] + cx
    dy[V + 1] = along * u[1] + 2.0 * rate * spin * u[0] + cy
    dy[V + 2] = along * u[2]
