"""Staging as data: a stack split into two complete vehicles at a stage boundary.

The events that decide *when* to separate belong to the flight computer and
the world (issue 6); this module only says *what* each part is afterwards.
Splitting the stack below stage ``k`` gives the lower part (stages
``0..k-1``, stations unchanged) and the upper part (stages ``k..top`` with
payload and fairing, stations from its own base). Each part gets:

* its runtime model (:func:`~rocketsim.vehicle.build.build`), so its own mass
  properties;
* its slice of the propellant masses and engine clocks, and its engines'
  commands and its stages' dry flags;
* its centre-of-mass position and velocity: the whole stack's, moved along the
  body x axis by the offset of the part's centre of mass,
  ``r_i = r + R(q) d_i`` and ``v_i = v + R(q) (w x d_i)`` with
  ``d_i = (x_cm,i - x_cm, 0, 0)`` in body axes; attitude and rates unchanged.

So the parts' mass-weighted positions and momenta add up to the stack's,
exactly up to rounding (no separation impulse: springs or pushers are events).
"""

from __future__ import annotations

import numpy as np

from rocketsim.dynamics.state import N_STATE, Q, R, V, W
from rocketsim.frames.quaternion import quat_rotate
from rocketsim.vehicle.build import VehicleModel, build
from rocketsim.vehicle.engines import S_DRY, S_DRY_AT


def separate(spec, whole: VehicleModel, y: np.ndarray, k: int, air=None):
    """Split ``whole`` (built from ``spec`` with all its stages) in state ``y`` below stage ``k``.

    Returns ``((lower, y_lower), (upper, y_upper))``. ``air``: the atmosphere
    table for the parts (default: the US Standard Atmosphere 1976).
    """
    if whole.stage_names != [s.name for s in spec.stages]:
        raise ValueError("separate() needs the model of the whole stack")
    if not 0 < k < len(spec.stages):
        raise ValueError(f"no stage boundary below stage {k}")
    lower = build(spec, 0, k - 1, air=air)
    upper = build(spec, k, air=air)
    x_cm = whole.mass_properties(y)[1]
    parts = []
    tank0 = engine0 = 0
    for part, base, stage0 in ((lower, 0.0, 0), (upper, float(whole.stage_base[k]), k)):
        y_part = np.empty(part.n_state)
        y_part[Q:W + 3] = y[Q:W + 3]
        tanks = slice(N_STATE + tank0, N_STATE + tank0 + part.n_tanks)
        clocks = slice(N_STATE + whole.n_tanks + engine0, N_STATE + whole.n_tanks + engine0 + part.n_engines)
        y_part[part.tanks] = y[tanks]
        y_part[part.clocks] = y[clocks]
        part.arrays.cmd[:] = whole.arrays.cmd[engine0:engine0 + part.n_engines]
        for column in (S_DRY, S_DRY_AT):
            part.arrays.stage[:, column] = whole.arrays.stage[stage0:stage0 + len(part.stage_names), column]
        offset = np.array([base + part.mass_properties(y_part)[1] - x_cm, 0.0, 0.0])
        w = y[W:W + 3]
        y_part[R:R + 3] = y[R:R + 3] + quat_rotate(y[Q:Q + 4], offset)
        y_part[V:V + 3] = y[V:V + 3] + quat_rotate(y[Q:Q + 4], np.cross(w, offset))
        parts.append((part, y_part))
        tank0 += part.n_tanks
        engine0 += part.n_engines
    return parts[0], parts[1]
