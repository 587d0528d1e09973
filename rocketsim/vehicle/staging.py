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
:func:`jettison_fairing` does the same for the fairing, which becomes a rigid
body (a thin shell), and :func:`deploy_payload` for the payload (a solid
cylinder).
"""

from __future__ import annotations

import numpy as np

from rocketsim.dynamics.state import N_STATE, Q, R, V, W
from rocketsim.frames.quaternion import quat_rotate
from rocketsim.vehicle.build import VehicleModel, build
from rocketsim.vehicle.engines import S_DRY, S_DRY_AT
from rocketsim.vehicle.mass_properties import shell, solid_cylinder


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
    upper = build(spec, k, air=air, fairing=whole.has_fairing)
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
        _copy_commands(whole, part, engine0, stage0)
        y_part[R:R + 3], y_part[V:V + 3] = moved(y, base + part.mass_properties(y_part)[1] - x_cm)
        parts.append((part, y_part))
        tank0 += part.n_tanks
        engine0 += part.n_engines
    return parts[0], parts[1]


def jettison_fairing(spec, model: VehicleModel, y: np.ndarray, first: int, air=None):
    """Drop the fairing of ``model`` (stages ``first..top`` of ``spec`` with its fairing).

    Returns ``((model_without, y_without), fairing)`` with ``fairing`` a dict of
    the fairing as a rigid body: ``mass`` (kg), ``inertia`` (Ixx, Iyy, Izz about
    its centre, kg m^2; a thin shell), ``position`` and ``velocity`` (of its
    centre, same frame as ``y``), ``attitude`` and ``rates`` (the stack's).
    """
    if not model.has_fairing or model.stage_names != [s.name for s in spec.stages[first:]]:
        raise ValueError("jettison_fairing() needs the model of stages first..top with its fairing")
    f = spec.fairing
    without = build(spec, first, air=air, fairing=False)
    return _release_top(spec, model, without, y, f.mass, shell(f.mass, 0.5 * f.diameter, f.length), f.length)


def deploy_payload(spec, model: VehicleModel, y: np.ndarray, first: int, air=None):
    """Release the payload of ``model`` (stages ``first..top`` of ``spec`` with its payload).

    Returns ``((model_without, y_without), payload)`` with ``payload`` a dict as
    :func:`jettison_fairing`'s (the payload a uniform solid cylinder on top of
    the top stage). The model left keeps the fairing if it still had one.
    """
    if spec.payload is None or model.stage_names != [s.name for s in spec.stages[first:]]:
        raise ValueError("deploy_payload() needs the model of stages first..top with its payload")
    p = spec.payload
    without = build(spec.model_copy(update={"payload": None}), first, air=air, fairing=model.has_fairing)
    return _release_top(spec, model, without, y, p.mass, solid_cylinder(p.mass, 0.5 * p.diameter, p.length),
                        p.length)


def _release_top(spec, model: VehicleModel, without: VehicleModel, y: np.ndarray, mass: float,
                 own: tuple[float, float], length: float):
    """Split a part of ``mass`` (kg), own inertias ``own`` (Ixx, Iyy = Izz, kg m^2)
    and ``length`` (m), standing on top of the top stage, from ``model`` in state
    ``y``; ``without`` is the model of what stays. Centre of mass and momentum
    are conserved (both parts moved along body x from the whole's centre)."""
    y_new = y.copy()
    _copy_commands(model, without, 0, 0)
    x_cm = model.mass_properties(y)[1]
    y_new[R:R + 3], y_new[V:V + 3] = moved(y, without.mass_properties(y_new)[1] - x_cm)
    top = float(model.stage_base[-1] + spec.stages[-1].length)
    r, v = moved(y, top + 0.5 * length - x_cm)
    part = {"mass": mass, "inertia": (own[0], own[1], own[1]), "position": r, "velocity": v,
            "attitude": y[Q:Q + 4].copy(), "rates": y[W:W + 3].copy()}
    return (without, y_new), part


def moved(y: np.ndarray, dx: float):
    """Position and velocity of the point ``dx`` (m) ahead of the centre of mass along body x."""
    offset = np.array([dx, 0.0, 0.0])
    return (y[R:R + 3] + quat_rotate(y[Q:Q + 4], offset),
            y[V:V + 3] + quat_rotate(y[Q:Q + 4], np.cross(y[W:W + 3], offset)))


def _copy_commands(source: VehicleModel, part: VehicleModel, engine0: int, stage0: int) -> None:
    """Engine commands and stage dry flags of ``part``, from ``source`` from engine/stage 0 on."""
    part.arrays.cmd[:] = source.arrays.cmd[engine0:engine0 + part.n_engines]
    for column in (S_DRY, S_DRY_AT):
        part.arrays.stage[:, column] = source.arrays.stage[stage0:stage0 + len(part.stage_names), column]
