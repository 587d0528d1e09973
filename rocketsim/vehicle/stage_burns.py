"""Each stage's burn on paper, for the design review (:mod:`rocketsim.vehicle.review`, which
states the models): its thrust and burnt propellant against time from ignition (motors' curves,
liquid engines at either end of their throttle range), its thrust-to-weight at ignition and
peak axial load with everything above it on, how it steers, and the speed and time at which
the lowest stage carries the vehicle off its launch rail. Pure Python, SI units."""

from __future__ import annotations

import bisect
import math
from dataclasses import dataclass

from rocketsim.constants import DEG, G0, UNUSABLE_PROPELLANT
from rocketsim.vehicle.stage_thrust import stage_engines

_RAIL_STEP = 1e-4               # s, the rail integration's step


@dataclass(frozen=True)
class StageLoads:
    """One stage's burn with everything above it on."""

    name: str
    ignition_mass_kg: float
    thrust_to_weight: float
    peak_axial_load_g: float             # full throttle
    least_peak_axial_load_g: float       # solid motors, liquid engines at their least throttle
    peak_at_s: float                     # s after the stage's ignition, at full throttle
    steers_with: list[str]
    can_steer: bool                      # gimbal, grid fins or RCS on this stage
    liquid: bool                         # it burns liquid engines
    motors: list[str]


@dataclass(frozen=True)
class RailExit:
    """Where the stack leaves its rail: the rail's length and inclination, the speed
    along it (over the ground, the rail's frame) and the time from the start."""

    length_m: float
    inclination_deg: float
    surface_speed_m_s: float
    time_s: float


def _interp(xs, ys, x: float, left: float | None = None, right: float | None = None) -> float:
    """Linear interpolation in ``(xs, ys)`` (increasing ``xs``), held at the ends unless
    ``left``/``right`` are given for beyond them."""
    if x <= xs[0]:
        return ys[0] if left is None or x == xs[0] else left
    if x >= xs[-1]:
        return ys[-1] if right is None or x == xs[-1] else right
    k = bisect.bisect_right(xs, x)
    f = (x - xs[k - 1]) / (xs[k] - xs[k - 1])
    return ys[k - 1] + f * (ys[k] - ys[k - 1])


def _motor_curves(stage):
    """``(times, thrust N, burnt fraction, propellant kg)`` of each of ``stage``'s motors on
    its own points: the curve times ``thrust_scale``, the impulse delivered over the total."""
    found = []
    for motor in stage.motors:
        t = [p[0] for p in motor.thrust]
        f = [motor.thrust_scale * p[1] for p in motor.thrust]
        impulse = [0.0]
        for k in range(1, len(t)):
            impulse.append(impulse[-1] + 0.5 * (f[k] + f[k - 1]) * (t[k] - t[k - 1]))
        found.append((t, f, [i / impulse[-1] for i in impulse], motor.propellant_mass))
    return found


def _stage_burn(stage, throttle: str):
    """``thrust(t)`` (N) and ``burnt(t)`` (kg) of ``stage``'s burn from its ignition: its
    motors' curves and its liquid engines at the ``throttle`` end of their range (``max`` or
    ``min``, vacuum thrust) until their usable propellant is gone; and the instants where
    either has a kink."""
    curves = _motor_curves(stage)
    share = 1 if throttle == "max" else 0
    thrust = sum(e.count * e.thrust_vacuum * e.throttle[share] for e in stage.engines)
    flow = sum(e.count * e.thrust_vacuum * e.throttle[share] / (G0 * e.isp) for e in stage.engines)
    usable = (1.0 - UNUSABLE_PROPELLANT) * sum(t.load for t in stage.tanks if t.feeds_engines)
    end = usable / flow if flow > 0 else 0.0

    def force(t):
        return (thrust if t < end else 0.0) + sum(_interp(c[0], c[1], t, right=0.0) for c in curves)

    def burnt(t):
        return flow * min(t, end) + sum(c[3] * _interp(c[0], c[2], t) for c in curves)

    kinks = sorted({0.0, *(float(x) for c in curves for x in c[0]), *([end] if end > 0 else [])})
    return force, burnt, kinks


def stage_loads(spec, i: int) -> StageLoads:
    """Stage ``i``'s burn with the stages above it, payload and fairing on: its
    thrust-to-weight at ignition and its peak axial load, thrust over mass (in g0)."""
    stage = spec.stages[i]
    ignition = ignition_mass(spec, i)
    vacuum, sea, _ = stage_engines(stage)
    peaks = []
    for throttle in ("max", "min"):
        force, burnt, kinks = _stage_burn(stage, throttle)
        # the load is piecewise monotone between kinks: its peak is at one, approached from
        # either side (an engine's cut-off: just before it)
        best = (0.0, 0.0)
        for t in kinks:
            for at in (max(t - 1e-9, 0.0), t):
                best = max(best, (force(at) / (ignition - burnt(at)) / G0, at))
        peaks.append(best)
    means = steering(spec, stage)
    return StageLoads(stage.name, ignition, (sea if i == 0 else vacuum) / (ignition * G0),
                      peaks[0][0], min(peaks[0][0], peaks[1][0]), peaks[0][1], means,
                      any(not m.startswith("fins") for m in means), bool(stage.engines),
                      [m.name for m in stage.motors])


def steering(spec, stage) -> list[str]:
    """How ``stage`` steers: its gimbals, grid fins, RCS thrusters (active) and fins (passive)."""
    means = [f"gimbal {e.name} +-{e.gimbal_range / DEG:g} deg at {e.gimbal_rate / DEG:g} deg/s"
             for e in stage.engines if e.gimbal_range > 0.0]
    aero = spec.aero
    if aero is not None:
        grid = sum(g.count for g in aero.grid_fins if g.stage == stage.name)
        rcs = sum(1 for r in aero.rcs if r.stage == stage.name)
        fins = sum(f.count for f in aero.fins if f.stage == stage.name)
        means += ([f"{grid} grid fins"] if grid and aero.aerodynamics else []) + \
            ([f"{rcs} RCS thrusters"] if rcs else []) + \
            ([f"fins ({fins}, passive)"] if fins and aero.aerodynamics else [])
    return means


def rail_exit(spec, length: float, inclination: float, last_button: float, gravity: float = G0) -> RailExit:
    """The lowest stage's thrust carrying the stack up a rail (see the module): speed over
    the ground (m/s) and time (s from the start) when the travel reaches ``length - last_button``. Liquid
    engines lit at T+0 follow their dead time and linear spool-up; motors start at their
    file's ignition time (``program``: T+0)."""
    stage = spec.stages[0]
    mass0 = ignition_mass(spec, 0)
    curves = _motor_curves(stage)
    starts = [m.ignition if isinstance(m.ignition, float) else 0.0 for m in stage.motors]
    thrust = sum(e.count * e.thrust_vacuum * e.throttle[1] for e in stage.engines)
    flow = sum(e.count * e.thrust_vacuum * e.throttle[1] / (G0 * e.isp) for e in stage.engines)
    dead = min((e.ignition_delay for e in stage.engines), default=0.0)
    spool = max((e.spool_up for e in stage.engines), default=1.0)

    def acceleration(t):
        f = thrust * min(1.0, max(0.0, (t - dead) / spool)) if thrust else 0.0
        gone = flow * max(0.0, t - dead)
        for (times, force, fraction, m0), start in zip(curves, starts):
            f += _interp(times, force, t - start, left=0.0, right=0.0)
            gone += m0 * _interp(times, fraction, t - start, left=0.0)
        return f / (mass0 - gone) - gravity * math.sin(inclination)

    travel, s, v, t, h = length - last_button, 0.0, 0.0, 0.0, _RAIL_STEP
    while s < travel and t < 60.0:
        a0 = acceleration(t)
        if v <= 0.0 and a0 <= 0.0:          # held at the foot
            t += h
            continue
        a1 = acceleration(t + h)
        v_next = v + 0.5 * (a0 + a1) * h
        s_next = s + h * (v + (2 * a0 + a1) * h / 6)
        if s_next >= travel:                # the exit within this step, by the secant
            f = (travel - s) / (s_next - s)
            return RailExit(length, inclination / DEG, v + f * (v_next - v), t + f * h)
        s, v, t = s_next, v_next, t + h
    return RailExit(length, inclination / DEG, math.nan, math.nan)


def ignition_mass(spec, i: int) -> float:
    """kg, stage ``i`` and everything above it loaded: stages, payload and fairing."""
    return (sum(st.dry_mass + st.propellant_mass for st in spec.stages[i:])
            + (spec.payload.mass if spec.payload else 0.0) + (spec.fairing.mass if spec.fairing else 0.0))
