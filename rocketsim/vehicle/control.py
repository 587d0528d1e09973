"""Engine commands and readings of one staged vehicle, by engine, group or stage name.

A thin layer over the arrays the integrator reads (:mod:`.engines`), for the
flight computer and the world: commands are given between steps and held for
the step; readings are evaluated at a given time and ambient pressure with
the same compiled functions the derivative uses.

``which`` selects engines: ``None`` (all), an index, a stage name
(``"booster"``), a group name (``"booster/Merlin 1D ring"`` or just
``"Merlin 1D ring"``), an engine name (``"booster/Merlin 1D ring/3"``), or a
list of those. Ignition and shutdown also take solid motors, by stage name
(``"sustainer"``) or motor name (``"sustainer/K1000T"`` or just ``"K1000T"``):
a motor lights once, at the instant the program lights it (docs/physics.md#solid-motors),
and cannot be shut down.
"""

from __future__ import annotations

import math

import numpy as np

from rocketsim.jit import Entries
from rocketsim.vehicle import engines, motors
from rocketsim.vehicle.motors import M_IGNITION
from rocketsim.vehicle.build import VehicleModel


class Propulsion:
    """The engines of ``model`` (a :class:`~rocketsim.vehicle.build.VehicleModel`)."""

    def __init__(self, model: VehicleModel):
        self.model = model
        self.a = model.arrays
        self.kernels = Entries()        # compiled entries bound to its arrays (the autopilot's step)

    def select(self, which=None) -> list[int]:
        """Engine indices named by ``which`` (see the module); ValueError if it names none."""
        n = self.model.n_engines
        if which is None:
            return list(range(n))
        if isinstance(which, (list, tuple)):
            return sorted({e for item in which for e in self.select(item)})
        if isinstance(which, (int, np.integer)):
            if not 0 <= which < n:
                raise ValueError(f"no engine {which} (the vehicle has {n})")
            return [int(which)]
        names, groups = self.model.engine_names, self.model.engine_groups
        stages = self.model.stage_names
        found = [e for e in range(n) if which in (names[e], groups[e], groups[e].split("/", 1)[1])
                 or (which in stages and int(self.a.eng[e, engines.E_STAGE]) == stages.index(which))]
        if not found:
            raise ValueError(f"no engine, group or stage named {which!r}; engines: {', '.join(names)}")
        return found

    def lowest_stage(self) -> str | None:
        """The name of the lowest stage with engines or solid motors (None: there is none):
        what ``fc.ignite()`` lights when it names nothing."""
        found = {int(self.a.eng[e, engines.E_STAGE]) for e in range(self.model.n_engines)}
        found |= {self.model.stage_names.index(name.split("/", 1)[0]) for name in self.model.motor_names}
        return self.model.stage_names[min(found)] if found else None

    def choose(self, which=None) -> tuple[list[int], list[int]]:
        """``(engines, motors)``: the indices of the engines and of the solid motors named
        by ``which`` (see the module; an index names an engine); ValueError if an item
        names neither."""
        if which is None:
            return list(range(self.model.n_engines)), list(range(self.model.n_motors))
        if isinstance(which, (list, tuple)):
            chosen = [self.choose(item) for item in which]
            return (sorted({e for found, _ in chosen for e in found}),
                    sorted({m for _, found in chosen for m in found}))
        motors = [] if isinstance(which, (int, np.integer)) else [
            i for i, name in enumerate(self.model.motor_names) if which in (name, *name.split("/", 1))]
        try:
            return self.select(which), motors
        except ValueError as error:
            if motors:
                return [], motors
            if self.model.n_motors:
                raise ValueError(f"{error}; solid motors: {', '.join(self.model.motor_names)}") from None
            raise

    def ignite(self, y: np.ndarray, which=None) -> list[str]:
        """Command ignition; returns the names of the engines that accepted it (not already
        on, stage not dry, an ignition left)."""
        return [self.model.engine_names[e] for e in self.select(which)
                if engines.ignite(y, self.a.eng, self.a.cmd, self.a.stage, e, self.a.first_clock)]

    def light(self, t: float, chosen: list[int]) -> list[str]:
        """Light the solid motors ``chosen`` (indices) at mission time ``t`` (s); returns the
        names of those lit: not lit before (``ignition: program``; a motor lights once)."""
        lit = []
        for i in chosen:
            if math.isnan(self.a.motor[i, M_IGNITION]):
                self.a.motor[i, M_IGNITION] = t
                lit.append(self.model.motor_names[i])
        return lit

    def shutdown(self, y: np.ndarray, which=None) -> list[str]:
        """Command shutdown (tail-off follows); returns the names of the engines that were on.
        ValueError if ``which`` (or an item of it) names solid motors and no engine: a solid
        motor burns to the end of its curve."""
        for item in which if isinstance(which, (list, tuple)) else [which]:
            chosen, motors = self.choose(item)
            if motors and not chosen:
                named = ", ".join(self.model.motor_names[i] for i in motors)
                raise ValueError(f"{named}: a solid motor cannot be shut down (it burns to the end "
                                 "of its thrust curve)")
        return [self.model.engine_names[e] for e in self.choose(which)[0]
                if engines.shutdown(y, self.a.eng, self.a.cmd, e, self.a.first_clock)]

    def throttle(self, t: float, value: float, which=None) -> None:
        """Command a throttle (clipped to each engine's range) at mission time ``t`` (s)."""
        engines.command_throttles(self.a.eng, self.a.cmd, np.array(self.select(which), dtype=np.int64),
                            float(t), float(value))

    def limit_q(self, t: float, start: float, end: float, which=None) -> None:
        """Give the engines a dynamic-pressure throttle law from ``start`` to ``end`` (Pa;
        :func:`~rocketsim.vehicle.engines.hold_q_law`), or (``start`` nan) remove it and
        command their last throttle again at mission time ``t`` (s)."""
        engines.set_q_law(self.a.eng, self.a.cmd, self.select(which), float(t), float(start), float(end))

    def gimbal(self, t: float, gy: float, gz: float, which=None) -> None:
        """Command a gimbal deflection (rad; towards body +y and +z), clipped to each cone."""
        gy, gz = float(gy), float(gz)
        engines.command_gimbals(self.a.eng, self.a.cmd, np.array(self.select(which), dtype=np.int64),
                          float(t), gy, gz, math.hypot(gy, gz))

    def states(self, y: np.ndarray, t: float, p_a: float) -> list[dict]:
        """Each engine at time ``t`` and ambient pressure ``p_a`` (Pa): on, spool fraction,
        throttle flown and its range, gimbal (rad), thrust (N), mass flow (kg/s), ignitions
        left, separated."""
        a, out = self.a, []
        rows = engines.engine_states(t, y, a.first_clock, a.eng, a.cmd, a.stage, p_a).tolist()
        for e, name in enumerate(self.model.engine_names):
            f, tau, gy, gz, separated, thrust = rows[e]
            out.append({
                "name": name,
                "on": bool(a.cmd[e, engines.C_ON] > 0.5),
                "spool": f,
                "throttle": tau,
                "throttle_range": (a.eng[e, engines.E_TAU_MIN], a.eng[e, engines.E_TAU_MAX]),
                "gimbal_rad": (gy, gz),
                "thrust_N": thrust,
                "mass_flow_kg_s": f * tau * a.eng[e, engines.E_MDOT],
                "ignitions_left": int(a.eng[e, engines.E_IGNITIONS] - a.cmd[e, engines.C_IGNITED]),
                "separated": separated > 0.5,
            })
        return out

    def thrusts(self, y: np.ndarray, t: float, p_a: float) -> np.ndarray:
        """Thrust (N) of every engine at time ``t`` and ambient pressure ``p_a`` (Pa)."""
        a = self.a
        return engines.thrusts(t, y, a.first_clock, a.eng, a.cmd, a.stage, p_a)

    def motor_thrust(self, t: float) -> float:
        """Thrust (N) of all solid motors at mission time ``t`` (s)."""
        a = self.a
        return float(sum(motors.motor_thrust(float(t), a.motor, a.curve, i) for i in range(self.model.n_motors)))

    def propellant(self, y: np.ndarray) -> dict[str, float]:
        """Propellant left in each tank and solid motor (kg), by ``stage/tank`` and
        ``stage/motor`` name."""
        return dict(zip(self.model.tank_names + self.model.motor_names,
                        (float(m) for m in np.concatenate((y[self.model.tanks], y[self.model.motors])))))
