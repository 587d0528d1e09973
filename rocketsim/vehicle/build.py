"""A staged vehicle spec becomes flat arrays, once, for the compiled kernels.

:func:`build` turns a :class:`~rocketsim.scenario.models.VehicleSpec` with
``stages`` (or any consecutive run of its stages: a separated booster, the
upper stack after staging) into a :class:`VehicleModel`: the summed fixed
masses, per-tank and per-engine arrays, and the layout of the extra state
entries. Stations are metres above the base of the lowest stage built, so a
separated stage is a complete vehicle of its own.

The state of a staged vehicle is the rigid body's 13 numbers followed by the
propellant mass of every tank (kg, stage by stage, in file order), the
clock of every engine (s since its last ignition or shutdown command) and the
propellant mass of every solid motor (kg, :mod:`rocketsim.vehicle.motors`).
"""

from __future__ import annotations

import math
from collections import namedtuple
from dataclasses import dataclass, field
from functools import lru_cache

import numpy as np

from rocketsim.constants import G0, UNUSABLE_PROPELLANT
from rocketsim.layout import N_STATE, make_state
from rocketsim.vehicle.engines import (C_BASE, C_Q_END, C_Q_START, C_TAU, C_TAU0, E_AREA, E_DEAD, E_GIMBAL_RANGE,
                                       E_GIMBAL_RATE, E_IGNITIONS, E_MDOT, E_PEXIT, E_SPOOL,
                                       E_STAGE, E_TAIL, E_TAU_MAX, E_TAU_MIN, E_TAU_RATE, E_THRUST,
                                       E_X, E_Y, E_Z, N_CMD, N_ENG, N_STAGE)
from rocketsim.vehicle.aero_build import build_aero
from rocketsim.vehicle.mass_properties import (N_FIXED, add_fixed, mass_properties, shell,
                                               solid_cylinder)
from rocketsim.vehicle.motors import M_PROPELLANT, build_motors
from rocketsim.vehicle.aero import A_WIND
from rocketsim.vehicle.parachutes import N_CHUTE
from rocketsim.vehicle.rail import no_rail

# What the derivative reads for a staged vehicle (a numba-friendly tuple).
VehicleArrays = namedtuple("VehicleArrays", [
    "fixed", "tank_bottom", "tank_radius", "tank_density", "tank_share", "eng", "cmd", "stage",
    "first_tank", "first_clock",
    "air",      # the air table: AtmosphereTable.arrays() (h0, dh, then six columns)
    "aero",
    "motor", "curve", "first_motor",     # solid motors (rocketsim.vehicle.motors)
    "rail",                              # the launch rail (rocketsim.vehicle.rail)
    "chute"])                            # parachutes (rocketsim.vehicle.parachutes)


@dataclass
class VehicleModel:
    """A staged vehicle at run time (SI units, body x from the base of its lowest stage)."""

    name: str
    stage_names: list[str]
    tank_names: list[str]
    engine_names: list[str]
    stage_base: np.ndarray          # m, station of each stage's base
    stage_length: np.ndarray        # m
    stage_diameter: np.ndarray      # m
    stage_dry_mass: np.ndarray      # kg, structure + tank walls + engines + point masses
    tank_load: np.ndarray           # kg, propellant loaded in each tank
    tank_stage: np.ndarray          # int, stage of each tank
    length: float                   # m, base of the stack to the nose
    arrays: VehicleArrays
    engine_groups: list[str] = field(default_factory=list)   # "stage/group" of each engine
    has_fairing: bool = False
    motor_names: list[str] = field(default_factory=list)     # "stage/motor" of each solid motor
    parachutes: list = field(default_factory=list)           # ParachuteSpec of each row of arrays.chute

    @property
    def n_tanks(self) -> int:
        return len(self.tank_names)

    @property
    def n_engines(self) -> int:
        return len(self.engine_names)

    @property
    def n_motors(self) -> int:
        return len(self.motor_names)

    @property
    def n_state(self) -> int:
        return N_STATE + self.n_tanks + self.n_engines + self.n_motors

    @property
    def tanks(self) -> slice:
        """Slice of the state holding the propellant masses."""
        return slice(N_STATE, N_STATE + self.n_tanks)

    @property
    def clocks(self) -> slice:
        """Slice of the state holding the engine clocks."""
        return slice(N_STATE + self.n_tanks, N_STATE + self.n_tanks + self.n_engines)

    @property
    def motors(self) -> slice:
        """Slice of the state holding the solid motors' propellant masses."""
        return slice(N_STATE + self.n_tanks + self.n_engines, self.n_state)

    def state(self, r, v, q=(1.0, 0.0, 0.0, 0.0), w=(0.0, 0.0, 0.0), propellant=None) -> np.ndarray:
        """A state vector: body state, tanks as loaded (or ``propellant``), clocks at 0,
        motors loaded."""
        y = np.zeros(self.n_state)
        y[:N_STATE] = make_state(r, v, q, w)
        y[self.tanks] = self.tank_load if propellant is None else propellant
        y[self.motors] = self.arrays.motor[:, M_PROPELLANT]
        return y

    def mass_properties(self, y_or_propellant, motors=None) -> tuple[float, float, float, float, float]:
        """``(mass, x_cm, Ixx, Iyy, Izz)`` for a state vector, or for the tanks' propellant
        masses with the motors' ``motors`` (kg each; default loaded)."""
        a = self.arrays
        prop = np.asarray(y_or_propellant, dtype=float)
        if prop.shape[0] == self.n_state:
            prop, motors = prop[self.tanks], prop[self.motors]
        elif motors is None:
            motors = a.motor[:, M_PROPELLANT]
        return mass_properties(a.fixed, a.tank_bottom, a.tank_radius, a.tank_density,
                               np.ascontiguousarray(prop), a.motor,
                               np.ascontiguousarray(np.asarray(motors, dtype=float)))

    def stage_propellant(self, y) -> np.ndarray:
        """Propellant (kg) left in each stage, unusable reserve included."""
        return np.bincount(self.tank_stage, weights=y[self.tanks], minlength=len(self.stage_names))

    def stage_engines(self, s: int) -> list[int]:
        """Indices of the engines of stage ``s``."""
        return [e for e in range(self.n_engines) if int(self.arrays.eng[e, E_STAGE]) == s]


@lru_cache(maxsize=1)
def _standard_air():
    from rocketsim.atmosphere.day import standard_table
    return standard_table().arrays()


def build(spec, first: int = 0, last: int | None = None, air=None, fairing: bool = True) -> VehicleModel:
    """The runtime model of stages ``first..last`` (inclusive, bottom to top) of ``spec``.

    Payload and fairing are included when the top stage is (the fairing only
    while ``fairing`` is true: False after its jettison). ``air`` is an
    :class:`~rocketsim.atmosphere.table.AtmosphereTable` for the ambient
    pressure; by default the US Standard Atmosphere 1976.
    """
    if not spec.stages:
        raise ValueError(f"vehicle {spec.name!r} has no stages")
    stages = spec.stages
    last = len(stages) - 1 if last is None else last
    chosen = stages[first:last + 1]
    if not chosen:
        raise ValueError(f"no stages in {first}..{last}")
    top = last == len(stages) - 1

    fixed = np.zeros(N_FIXED)
    tank_bottom, tank_radius, tank_density, tank_load, tank_share, tank_stage = [], [], [], [], [], []
    tank_names, engine_names, engine_groups, eng_rows = [], [], [], []
    stage_rows, stage_base, dry = [], [], []
    base = 0.0
    for s, st in enumerate(chosen):
        stage_base.append(base)
        radius = 0.5 * st.diameter
        centre = base + (0.5 * st.length if st.structure_centre is None else st.structure_centre)
        add_fixed(fixed, st.structure_mass, centre, *shell(st.structure_mass, radius, st.length))
        # the engines draw from the tanks that feed them, listed first; RCS-only tanks after
        feeding = [tank for tank in st.tanks if tank.feeds_engines]
        load = sum(tank.load for tank in feeding)
        # a stage loaded with nothing starts dry: its engines cannot light
        stage_rows.append((UNUSABLE_PROPELLANT * load, 0.0 if load > 0 else 1.0, len(tank_names),
                           len(feeding), math.nan))
        for tank in feeding + [tank for tank in st.tanks if not tank.feeds_engines]:
            bottom = base + tank.position
            add_fixed(fixed, tank.wall_mass, bottom + 0.5 * tank.length,
                      *shell(tank.wall_mass, tank.radius, tank.length))
            tank_names.append(f"{st.name}/{tank.name}")
            tank_bottom.append(bottom)
            tank_radius.append(tank.radius)
            tank_density.append(tank.density * math.pi * tank.radius ** 2)
            tank_load.append(tank.load)
            tank_share.append(tank.load / load if load > 0 and tank.feeds_engines else 0.0)
            tank_stage.append(s)
        for group in st.engines:
            for k, (py, pz) in enumerate(_ring(group.count, group.layout_radius, group.layout_angle)):
                x = base + group.position
                add_fixed(fixed, group.mass, x, y=py, z=pz)
                engine_names.append(f"{st.name}/{group.name}" + (f"/{k + 1}" if group.count > 1 else ""))
                engine_groups.append(f"{st.name}/{group.name}")
                row = np.zeros(N_ENG)
                row[E_STAGE], row[E_X], row[E_Y], row[E_Z] = s, x, py, pz
                row[E_THRUST] = group.thrust_vacuum
                row[E_MDOT] = group.thrust_vacuum / (G0 * group.isp)
                row[E_AREA] = group.exit_area
                row[E_PEXIT] = group.exit_pressure or 0.0
                row[E_TAU_MIN], row[E_TAU_MAX] = group.throttle
                row[E_TAU_RATE] = group.throttle_rate
                row[E_GIMBAL_RANGE], row[E_GIMBAL_RATE] = group.gimbal_range, group.gimbal_rate or 0.0
                row[E_DEAD], row[E_SPOOL], row[E_TAIL] = (group.ignition_delay, group.spool_up,
                                                                group.tail_off)
                row[E_IGNITIONS] = 1 + group.restarts
                eng_rows.append(row)
        for part in st.point_masses:
            for py, pz in _ring(part.count, part.radius, 0.0):
                add_fixed(fixed, part.mass, base + part.position, y=py, z=pz)
        dry.append(st.dry_mass)
        base += st.length
    motor, curve, cases = build_motors(chosen, stage_base)
    for mass, centre, radius, length in cases:
        add_fixed(fixed, mass, centre, *shell(mass, radius, length))
    motor_names = [f"{st.name}/{m.name}" for st in chosen for m in st.motors]
    chutes = [c for st in chosen for c in st.parachutes]
    names = [c.name for c in chutes]
    cut_by = {other: names.index(c.name) for c in chutes for other in c.releases}
    chute = np.array([(s, c.cd_s, c.lag, c.inflation, math.nan, cut_by.get(c.name, -1),
                       stage_base[s] + (st.length if c.attachment is None else c.attachment))
                      for s, st in enumerate(chosen) for c in st.parachutes], dtype=float).reshape(-1, N_CHUTE)
    if top and spec.payload is not None:
        pl = spec.payload
        add_fixed(fixed, pl.mass, base + 0.5 * pl.length, *solid_cylinder(pl.mass, 0.5 * pl.diameter, pl.length))
    with_fairing = top and fairing and spec.fairing is not None
    if with_fairing:
        fr = spec.fairing
        add_fixed(fixed, fr.mass, base + 0.5 * fr.length, *shell(fr.mass, 0.5 * fr.diameter, fr.length))
    length = base + (max(spec.payload.length if spec.payload else 0.0,
                         spec.fairing.length if with_fairing else 0.0) if top else 0.0)

    eng = np.array(eng_rows, dtype=float).reshape(len(eng_rows), N_ENG)
    cmd = np.zeros((len(eng_rows), N_CMD))
    cmd[:, C_TAU0] = eng[:, E_TAU_MAX]          # throttle rests at the top of its range
    cmd[:, C_TAU] = eng[:, E_TAU_MAX]
    cmd[:, C_BASE] = eng[:, E_TAU_MAX]
    cmd[:, C_Q_START] = cmd[:, C_Q_END] = np.nan    # no dynamic-pressure throttle law
    air_table = _standard_air() if air is None else air.arrays()
    we, wn = air_table[6], air_table[7]
    windy = bool(np.any(we != 0.0) or np.any(wn != 0.0))
    aero = build_aero(spec, chosen, stage_base, top, with_fairing, tank_names, windy)
    if chutes and windy:
        aero.ref[A_WIND] = 1.0          # a canopy drifts with the wind, aerodynamics or not
    arrays = VehicleArrays(
        fixed, _f(tank_bottom), _f(tank_radius), _f(tank_density), _f(tank_share), eng, cmd,
        np.array(stage_rows, dtype=float).reshape(len(chosen), N_STAGE),
        N_STATE, N_STATE + len(tank_names),
        air_table, aero, motor, curve, N_STATE + len(tank_names) + len(eng_rows), no_rail(),
        chute)
    return VehicleModel(spec.name if first == 0 and top else f"{spec.name}[{chosen[0].name}..{chosen[-1].name}]",
                        [st.name for st in chosen], tank_names, engine_names,
                        _f(stage_base), _f([st.length for st in chosen]), _f([st.diameter for st in chosen]),
                        _f(dry), _f(tank_load), np.array(tank_stage, dtype=np.int64), length, arrays,
                        engine_groups, with_fairing, motor_names, chutes)


def _f(values) -> np.ndarray:
    return np.ascontiguousarray(np.array(values, dtype=float))


def _ring(count: int, radius: float, angle: float):
    """(y, z) of ``count`` points evenly spaced on a ring of ``radius`` (m) from ``angle`` (rad)."""
    if radius == 0.0:
        return [(0.0, 0.0)] * count
    return [(radius * math.cos(angle + 2 * math.pi * k / count),
             radius * math.sin(angle + 2 * math.pi * k / count)) for k in range(count)]
