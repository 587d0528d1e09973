"""Staging as data: a stack split into two complete vehicles at a stage boundary.

The events that decide *when* to separate belong to the flight computer and
the world (:mod:`rocketsim.sim`); this module only says *what* each part is afterwards.
Splitting the stack below stage ``k`` gives the lower part (stages
``0..k-1``, stations unchanged) and the upper part (stages ``k..top`` with
payload and fairing, stations from its own base). Each part gets:

* its runtime model (:func:`~rocketsim.vehicle.build.build`), so its own mass
  properties;
* its slice of the propellant masses and engine clocks, and its engines'
  commands, its stages' dry flags, its parachutes' deployments and its solid
  motors' ignitions (a motor the program lit stays lit);
* its centre-of-mass position and velocity: the whole stack's, moved along the
  body x axis by the offset of the part's centre of mass,
  ``r_i = r + R(q) d_i`` and ``v_i = v + R(q) (w x d_i)`` with
  ``d_i = (x_cm,i - x_cm, 0, 0)`` in body axes; attitude and rates unchanged.

So the parts' mass-weighted positions and momenta add up to the stack's,
exactly up to rounding (no separation impulse: springs or pushers are events).
:func:`jettison_fairing` does the same for the fairing, which opens into two
rigid bodies (half cylindrical shells pushed apart along the body's y axis, in
opposite directions, so their centre of mass and momentum are those of the
fairing), and :func:`deploy_payload` for the payload (a solid cylinder). Each
rigid part carries its tumbling drag's mean area and length
(:mod:`rocketsim.vehicle.tumbling`).
"""

from __future__ import annotations

import numpy as np

from rocketsim.layout import N_STATE, Q, R, V, W
from rocketsim.frames.quaternion import quat_rotate
from rocketsim.vehicle.build import VehicleModel, build
from rocketsim.vehicle.engines import S_DRY, S_DRY_AT
from rocketsim.vehicle.aero import A_GROUND
from rocketsim.vehicle.mass_properties import solid_cylinder
from rocketsim.vehicle.motors import M_IGNITION
from rocketsim.vehicle.parachutes import CH_DEPLOYED
from rocketsim.vehicle.tumbling import cylinder_area, half_shell_area


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
    tank0 = engine0 = motor0 = chute0 = 0
    for part, base, stage0 in ((lower, 0.0, 0), (upper, float(whole.stage_base[k]), k)):
        y_part = np.empty(part.n_state)
        y_part[Q:W + 3] = y[Q:W + 3]
        tanks = slice(N_STATE + tank0, N_STATE + tank0 + part.n_tanks)
        clocks = slice(N_STATE + whole.n_tanks + engine0, N_STATE + whole.n_tanks + engine0 + part.n_engines)
        y_part[part.tanks] = y[tanks]
        y_part[part.clocks] = y[clocks]
        y_part[part.motors] = y[whole.motors][motor0:motor0 + part.n_motors]
        part.arrays.motor[:, M_IGNITION] = whole.arrays.motor[motor0:motor0 + part.n_motors, M_IGNITION]
        part.arrays.aero.ref[A_GROUND] = whole.arrays.aero.ref[A_GROUND]
        n_chutes = part.arrays.chute.shape[0]
        part.arrays.chute[:, CH_DEPLOYED] = whole.arrays.chute[chute0:chute0 + n_chutes, CH_DEPLOYED]
        chute0 += n_chutes
        _copy_commands(whole, part, engine0, stage0)
        y_part[R:R + 3], y_part[V:V + 3] = moved(y, base + part.mass_properties(y_part)[1] - x_cm)
        parts.append((part, y_part))
        tank0 += part.n_tanks
        engine0 += part.n_engines
        motor0 += part.n_motors
    return parts[0], parts[1]


def jettison_fairing(spec, model: VehicleModel, y: np.ndarray, first: int, air=None):
    """Drop the fairing of ``model`` (stages ``first..top`` of ``spec`` with its fairing).

    Returns ``((model_without, y_without), (half_1, half_2))``, each half a dict of
    a rigid body (:func:`_release_top`): half the fairing's mass, the inertia of a
    half cylindrical shell about its own centre (:func:`half_shell`; the nose is
    taken as part of the cylinder), its centre ``2 R / pi`` off the axis along the
    body's ``+y`` (``half_1``) or ``-y`` (``half_2``), moving away from the axis at
    half the fairing's ``separation_speed`` (m/s, the halves' relative speed).
    """
    if not model.has_fairing or model.stage_names != [s.name for s in spec.stages[first:]]:
        raise ValueError("jettison_fairing() needs the model of stages first..top with its fairing")
    f = spec.fairing
    without = build(spec, first, air=air, fairing=False)
    radius = 0.5 * f.diameter
    inertia, offset = half_shell(0.5 * f.mass, radius, f.length)
    area = half_shell_area(radius, f.length)
    (kept, y_kept), halves = _release_top(spec, model, without, y, f.length, [
        (0.5 * f.mass, inertia, sign * offset, sign * 0.5 * f.separation_speed, area) for sign in (1.0, -1.0)])
    return (kept, y_kept), tuple(halves)


def deploy_payload(spec, model: VehicleModel, y: np.ndarray, first: int, air=None):
    """Release the payload of ``model`` (stages ``first..top`` of ``spec`` with its payload).

    Returns ``((model_without, y_without), payload)`` with ``payload`` a dict as
    :func:`_release_top`'s (the payload a uniform solid cylinder on top of the
    top stage, no separation impulse). The model left keeps the fairing if it
    still had one.
    """
    if spec.payload is None or model.stage_names != [s.name for s in spec.stages[first:]]:
        raise ValueError("deploy_payload() needs the model of stages first..top with its payload")
    p = spec.payload
    without = build(spec.model_copy(update={"payload": None}), first, air=air, fairing=model.has_fairing)
    ixx, iyy = solid_cylinder(p.mass, 0.5 * p.diameter, p.length)
    kept, (payload,) = _release_top(spec, model, without, y, p.length, [
        (p.mass, (ixx, iyy, iyy), 0.0, 0.0, cylinder_area(0.5 * p.diameter, p.length))])
    return kept, payload


def half_shell(mass: float, radius: float, length: float) -> tuple[tuple[float, float, float], float]:
    """``((Ixx, Iyy, Izz), d)`` of a thin half cylindrical shell (no end caps) of
    ``mass`` (kg), ``radius`` and ``length`` (m) lying on the ``+y`` side of the
    ``x`` axis: its inertia (kg m^2) about its own centre of mass, which is
    ``d = 2 R / pi`` (m) off the axis along ``y``. About the axis the shell's
    ``Ixx`` is ``m R^2``; its ``Iyy`` and ``Izz`` ``m (R^2/2 + L^2/12)`` (the mean of
    ``y^2`` and of ``z^2`` over the half circle is ``R^2/2``); the parallel-axis
    theorem moves ``Ixx`` and ``Izz`` to the centre (``- m d^2``); ``y`` and ``z``
    are principal (the half is symmetric in ``z`` and in ``x``)."""
    d = 2.0 * radius / np.pi
    transverse = mass * (0.5 * radius ** 2 + length ** 2 / 12.0)
    return (mass * (radius ** 2 - d * d), transverse, transverse - mass * d * d), d


def _release_top(spec, model: VehicleModel, without: VehicleModel, y: np.ndarray, length: float,
                 pieces):
    """Split a part ``length`` (m) long standing on top of the top stage from
    ``model`` in state ``y``, as ``pieces``: ``(mass, (Ixx, Iyy, Izz), y_off, speed,
    area)`` each (kg, kg m^2 about its own centre, m off the body x axis along body
    y, m/s pushed along body y, mean tumbling area m^2), whose masses add up to the
    part's and whose mass-weighted offsets and speeds add up to zero. ``without`` is the model of what stays. Returns ``((without, y_without),
    [part, ...])``, each part a dict: ``mass``, ``inertia``, ``position`` and
    ``velocity`` (of its centre, same frame as ``y``), ``attitude`` and ``rates``
    (the stack's), ``area`` (m^2) and ``length`` (m). Centre of mass and momentum
    are conserved (all parts moved from the whole's centre)."""
    y_new = y.copy()
    _copy_commands(model, without, 0, 0)
    without.arrays.chute[:, CH_DEPLOYED] = model.arrays.chute[:, CH_DEPLOYED]
    without.arrays.motor[:, M_IGNITION] = model.arrays.motor[:, M_IGNITION]
    without.arrays.aero.ref[A_GROUND] = model.arrays.aero.ref[A_GROUND]
    x_cm = model.mass_properties(y)[1]
    y_new[R:R + 3], y_new[V:V + 3] = moved(y, without.mass_properties(y_new)[1] - x_cm)
    top = float(model.stage_base[-1] + spec.stages[-1].length)
    parts = []
    for piece_mass, inertia, y_off, speed, area in pieces:
        r, v = moved(y, top + 0.5 * length - x_cm, y_off)
        v = v + quat_rotate(y[Q:Q + 4], np.array([0.0, speed, 0.0]))
        parts.append({"mass": piece_mass, "inertia": inertia, "position": r, "velocity": v,
                      "attitude": y[Q:Q + 4].copy(), "rates": y[W:W + 3].copy(), "area": area,
                      "length": length})
    return (without, y_new), parts


def moved(y: np.ndarray, dx: float, dy: float = 0.0):
    """Position and velocity of the point ``dx`` (m) ahead of the centre of mass along
    body x and ``dy`` (m) off it along body y."""
    offset = np.array([dx, dy, 0.0])
    return (y[R:R + 3] + quat_rotate(y[Q:Q + 4], offset),
            y[V:V + 3] + quat_rotate(y[Q:Q + 4], np.cross(y[W:W + 3], offset)))


def _copy_commands(source: VehicleModel, part: VehicleModel, engine0: int, stage0: int) -> None:
    """Engine commands and stage dry flags of ``part``, from ``source`` from engine/stage 0 on."""
    part.arrays.cmd[:] = source.arrays.cmd[engine0:engine0 + part.n_engines]
    for column in (S_DRY, S_DRY_AT):
        part.arrays.stage[:, column] = source.arrays.stage[stage0:stage0 + len(part.stage_names), column]
