"""A staged vehicle's pre-flight design review: stability, loads, steering, rail exit.

Pure functions of a vehicle file's specs (``VehicleSpec`` with ``stages``); the
figures a designer checks before flying (docs/physics.md#design-review):

* **Centre of pressure and static margin** at liftoff and at each stage's
  burnout, stations above the vehicle's base, the margin ``(x_cm - x_cp) / d`` in
  calibres of the largest diameter ``d`` (positive: stable). ``x_cp`` two ways:
  at zero angle of attack by Barrowman's method, the normal-force slopes of the
  nose (slender body, 2 per radian), a boattail and the fins summed at their
  centres of pressure (J. S. Barrowman, *The Practical Calculation of the
  Aerodynamic Characteristics of Slender Finned Vehicles*, M.S. thesis, Catholic
  University of America, 1967; the lifts of
  :meth:`~rocketsim.vehicle.outline.BodyShape.lift_slopes`, as the flight's arrays
  hold them), the figure a finned rocket's stability is judged by; and at
  :data:`CROSSFLOW_ALPHA` in subsonic flow from the flight's own normal-force
  model, the slender-body lift plus Jorgensen's crossflow along the body (NASA TR
  R-474, 1977; :func:`~rocketsim.vehicle.aero.body_aero`), where an unfinned
  launcher's centre of pressure moves aft from its nose.
* **Thrust-to-weight** of each stage at its ignition, everything above it on
  (the lowest at sea level, the others in vacuum).
* **Peak axial load** of each stage's burn, the thrust alone over the mass
  (what the structure feels off the pad, before the air pushes back), against
  the structural limit (the file's ``aero.limits``, or the launcher defaults):
  at full throttle, and the least the burn can be flown at (solid motors as
  their curves, liquid engines at the bottom of their throttle range), with the
  stage's motors lit together at its ignition.
* **Rail exit**: the speed and time at which the lowest stage's thrust carries
  the vehicle off a rail of travel ``length - last_button`` at its inclination,
  ``s'' = T(t)/m(t) - g sin(theta)`` from rest (held at the foot while the thrust
  is below the weight; no drag: a few newtons at rail speeds), the engines' dead
  time and spool-up and the motors' curves as the flight flies them.
* **Steering** of each stage: gimbal range and rate, grid fins, RCS thrusters
  (active), fins (passive).

:func:`review` returns a :class:`Review`; its ``warnings`` are one line each for
a design that will break up (however its program throttles: a full-throttle peak
past the limit is the program's to avoid, and shows in the table), tumble, cannot
steer, cannot lift off, or, with no ``aero`` section, flies from its pad as in vacuum. :func:`design_warnings` gives them alone, in pure Python
(no array library, no compiled kernel: ``rocketsim validate`` stays light); the
crossflow centre of pressure and the stack's summary (masses, Delta-v, inertia) are
the full review's, from the compiled model. The stages' burns (thrust-to-weight, axial
loads, steering, rail exit) are computed by :mod:`rocketsim.vehicle.stage_burns`.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field, replace

from rocketsim.constants import (DEG, G0, STRUCTURE_AXIAL_LIMIT_G, STRUCTURE_Q_ALPHA_LIMIT,
                                 UNUSABLE_PROPELLANT)
from rocketsim.vehicle.outline import body_shape
from rocketsim.vehicle.stage_burns import RailExit, StageLoads, rail_exit, stage_loads

CROSSFLOW_ALPHA = 5.0 * DEG     # rad, the angle of attack of the crossflow centre of pressure
CROSSFLOW_MACH = 0.5            # the Mach number it is evaluated at (subsonic)
SEA_LEVEL = (1.225, 340.294)    # US 1976 sea-level density (kg/m^3) and speed of sound (m/s)


@dataclass(frozen=True)
class Phase:
    """The stack at one instant: ``stage`` burning, ``moment`` liftoff/ignition/burnout."""

    stage: str
    moment: str
    mass_kg: float
    centre_of_mass_m: float
    centre_of_pressure_m: float          # Barrowman, alpha -> 0 (nan: nothing lifts)
    static_margin_cal: float
    crossflow_centre_of_pressure_m: float   # at CROSSFLOW_ALPHA, CROSSFLOW_MACH
    crossflow_static_margin_cal: float


@dataclass
class Review:
    """A staged vehicle's design review (SI units, stations above the vehicle's base)."""

    name: str
    length_m: float
    diameter_m: float
    nose: str                            # what the nose is and where it sits
    aerodynamics: bool
    axial_limit_g: float
    q_alpha_limit_pa_deg: float
    limits_given: bool                   # the axial limit is the file's aero.limits (else assumed)
    q_alpha_limit_given: bool            # the q alpha limit is the file's (else assumed)
    phases: list[Phase]
    stages: list[StageLoads]
    rail: RailExit | None = None
    summary: dict = field(default_factory=dict)     # masses, Delta-v, inertia (vehicle.summary)
    warnings: list[str] = field(default_factory=list)
    spec: object = field(default=None, repr=False)  # the VehicleSpec reviewed

    def as_dict(self) -> dict:
        """The figures as JSON holds them (a figure there is none of, nan, as None); the
        summary and the spec left out."""
        found = asdict(replace(self, summary={}, spec=None))
        for key in ("summary", "spec"):
            found.pop(key)
        return _no_nan(found)

    def text(self) -> str:
        """The review as a table for a terminal."""
        lines = [f"{self.name}: {self.length_m:.3f} m from its base to the nose's tip, "
                 f"{self.diameter_m:.3f} m across; {self.nose}"]
        given = {"axial_load": self.limits_given, "q_alpha": self.q_alpha_limit_given}
        limits = (f"structural limits {self.axial_limit_g:g} g axial, {self.q_alpha_limit_pa_deg:,.0f} Pa deg "
                  + ("(the file's aero.limits)" if all(given.values()) else
                     "(assumed: a launcher's; give aero.limits for another structure)" if not any(given.values())
                     else "(the file's " + next(k for k, v in given.items() if v) + "; its "
                     + next(k for k, v in given.items() if not v) + " assumed, a launcher's)"))
        lines.append(limits if self.aerodynamics else "no aerodynamics: no centre of pressure, "
                     "no breakup checks")
        if self.rail is not None:
            lines.append(f"off a {self.rail.length_m:g} m rail at {self.rail.inclination_deg:g} deg: "
                         f"{self.rail.surface_speed_m_s:.1f} m/s at T+{self.rail.time_s:.2f} s (thrust alone, no drag)")
        if self.aerodynamics:
            lines += ["", f"{'':24}{'mass kg':>12}{'CM m':>9}{'CP m':>9}{'margin cal':>12}"
                          f"{'CP m at 5 deg':>15}{'margin':>9}"]
            for p in self.phases:
                lines.append(f"{(p.stage + ' ' + p.moment)[:23]:<24}{p.mass_kg:>12,.2f}"
                             f"{p.centre_of_mass_m:>9.3f}{_figure(p.centre_of_pressure_m, 9, 3)}"
                             f"{_figure(p.static_margin_cal, 12, 2)}"
                             f"{_figure(p.crossflow_centre_of_pressure_m, 15, 3)}"
                             f"{_figure(p.crossflow_static_margin_cal, 9, 2)}")
            lines.append("centre of pressure: Barrowman (1967) at zero angle of attack (nose, "
                         "boattail, fins); at 5 deg, Mach 0.5 the flight's slender-body lift and "
                         "Jorgensen's crossflow (NASA TR R-474)")
        lines += ["", f"{'stage':<16}{'T/W':>7}{'peak axial g':>14}{'least g':>9}  steers with"]
        for s in self.stages:
            lines.append(f"{s.name[:15]:<16}{s.thrust_to_weight:>7.2f}{s.peak_axial_load_g:>14.2f}"
                         f"{s.least_peak_axial_load_g:>9.2f}  {', '.join(s.steers_with) or 'nothing'}")
        lines += [""] + ([f"warning: {w}" for w in self.warnings] or ["no warnings"])
        return "\n".join(lines)


def _no_nan(value):
    """``value`` (nested dicts and lists) with every nan as None."""
    if isinstance(value, dict):
        return {k: _no_nan(v) for k, v in value.items()}
    if isinstance(value, list):
        return [_no_nan(v) for v in value]
    return None if isinstance(value, float) and math.isnan(value) else value


def _figure(value: float, width: int, digits: int) -> str:
    """``value`` right-aligned in ``width`` columns, or a dash when there is none (nan)."""
    return f"{'-':>{width}}" if math.isnan(value) else f"{value:>{width}.{digits}f}"


def review(spec, rail=None, gravity: float = G0, pad: bool = False) -> Review:
    """The design review of ``spec`` (a staged ``VehicleSpec``); ``rail``: the mission's
    ``(length m, inclination rad, last_button m)`` for the rail exit; ``gravity``: the
    pad's (m/s^2, default g0); ``pad``: the flight starts on a pad (a thrust-to-weight
    under 1 then cannot lift off)."""
    from rocketsim.vehicle.build import build
    from rocketsim.vehicle.summary import summary
    found = _review(spec, rail, gravity, pad)
    if found.aerodynamics:
        phases = []
        for p in found.phases:
            i = [st.name for st in spec.stages].index(p.stage)
            cross = crossflow_centre_of_pressure(build(spec, first=i).arrays.aero)
            phases.append(replace(p, crossflow_centre_of_pressure_m=cross,
                                  crossflow_static_margin_cal=(p.centre_of_mass_m - cross) / found.diameter_m))
        found.phases = phases
    found.summary = summary(spec)
    return found


def design_warnings(spec, pad: bool = False) -> list[str]:
    """The warnings of :func:`review`, one line each, in pure Python (the review without
    its crossflow centre of pressure and summary, which need the compiled model)."""
    return _review(spec, None, G0, pad).warnings


def _review(spec, rail, gravity: float, pad: bool) -> Review:
    """The review's figures that pure Python gives (see :func:`review`)."""
    aero = spec.aero
    aerodynamic = aero is not None and aero.aerodynamics
    limits = aero.limits if aero is not None else None
    given = limits is not None and limits.axial_load is not None
    axial_limit = limits.axial_load / G0 if given else STRUCTURE_AXIAL_LIMIT_G
    q_alpha_given = limits is not None and limits.q_alpha is not None
    q_alpha_limit = limits.q_alpha if q_alpha_given else STRUCTURE_Q_ALPHA_LIMIT
    shape = _shape(spec, 0) if aerodynamic else None
    length = shape.length if shape is not None else _stack_length(spec)
    d = shape.reference_diameter if shape is not None else max(st.diameter for st in spec.stages)
    loads = [stage_loads(spec, i) for i in range(len(spec.stages))]
    phases = stability(spec, pad or rail is not None) if aerodynamic else []
    found = Review(spec.name, length, d, nose_place(spec), aerodynamic, axial_limit, q_alpha_limit,
                   given, q_alpha_given, phases, loads, None if rail is None else rail_exit(spec, *rail, gravity),
                   spec=spec)
    found.warnings = warnings(found, spec, pad or rail is not None)
    return found


def _shape(spec, first: int):
    """The :class:`~rocketsim.vehicle.outline.BodyShape` of stages ``first``.. (the top's
    payload and fairing on)."""
    bases, base = [], 0.0
    for st in spec.stages[first:]:
        bases.append(base)
        base += st.length
    return body_shape(spec, spec.stages[first:], bases, True, spec.fairing is not None)


def _stack_length(spec) -> float:
    """m, from the base to the top of the payload or fairing."""
    return sum(st.length for st in spec.stages) + max(
        [p.length for p in (spec.payload, spec.fairing) if p is not None], default=0.0)


def nose_place(spec) -> str:
    """Where the nose sits: the top ``length`` of the part it caps (the fairing, else the
    payload, else the top stage), whose length includes it."""
    aero = spec.aero
    if aero is None or aero.nose.length == 0.0:
        return "no nose (a blunt top)"
    if spec.fairing is not None:
        part, length = "the fairing", spec.fairing.length
    elif spec.payload is not None:
        part, length = f"the payload {spec.payload.name!r}", spec.payload.length
    else:
        part, length = f"stage {spec.stages[-1].name!r}", spec.stages[-1].length
    tip = sum(st.length for st in spec.stages) + (max(spec.payload.length if spec.payload else 0.0,
                                                      spec.fairing.length if spec.fairing else 0.0))
    return (f"the nose ({aero.nose.shape}, {aero.nose.length:g} m) is the top of {part} "
            f"({length:g} m long, nose included), from {tip - aero.nose.length:.3f} m")


def stability(spec, pad: bool = True) -> list[Phase]:
    """Each stage's ignition (``liftoff`` for the lowest off a ``pad``) and its burnout, the
    stages above still full: the stack's centre of mass and its centre of pressure at zero
    angle of attack (the crossflow's left nan: :func:`review` fills it in)."""
    phases = []
    for i, stage in enumerate(spec.stages):
        shape = _shape(spec, i)
        slopes = shape.lift_slopes()
        total = sum(k for _, k in slopes)
        cp = sum(x * k for x, k in slopes) / total if total > 0.0 else math.nan
        for moment, burnt in (("liftoff" if i == 0 and pad else "ignition", False), ("burnout", True)):
            mass, x_cm = centre_of_mass(spec, i, burnt)
            phases.append(Phase(stage.name, moment, mass, x_cm, cp,
                                (x_cm - cp) / shape.reference_diameter, math.nan, math.nan))
    return phases


def centre_of_mass(spec, first: int = 0, burnt: bool = False) -> tuple[float, float]:
    """``(mass kg, station m of the centre of mass)`` of stages ``first``.. of ``spec``
    with the payload and fairing, loaded, or with stage ``first``'s burn done (its
    feeding tanks down to their unusable 1 %, its motors empty): the parts where
    :func:`rocketsim.vehicle.build.build` puts them (structure at its centre, tank walls
    mid-tank, liquid columns settled on their tanks' bottoms, engines and point masses at
    their stations, motors' cases and propellant at the motors' centres, payload and
    fairing at theirs)."""
    mass = moment = base = 0.0
    for s, st in enumerate(spec.stages[first:]):
        done = burnt and s == 0
        parts = [(st.structure_mass, 0.5 * st.length if st.structure_centre is None else st.structure_centre)]
        for tank in st.tanks:
            load = tank.load * (UNUSABLE_PROPELLANT if done and tank.feeds_engines else 1.0)
            column = load / (tank.density * math.pi * tank.radius ** 2)
            parts += [(tank.wall_mass, tank.position + 0.5 * tank.length), (load, tank.position + 0.5 * column)]
        parts += [(e.mass * e.count, e.position) for e in st.engines]
        parts += [(p.mass * p.count, p.position) for p in st.point_masses]
        parts += [(m.case_mass + (0.0 if done else m.propellant_mass), m.position + 0.5 * m.length)
                  for m in st.motors]
        for m, x in parts:
            mass += m
            moment += m * (base + x)
        base += st.length
    for part in (spec.payload, spec.fairing):
        if part is not None:
            mass += part.mass
            moment += part.mass * (base + 0.5 * part.length)
    return mass, moment / mass


def crossflow_centre_of_pressure(a) -> float:
    """Station (m) where the flight's normal force acts at :data:`CROSSFLOW_ALPHA` nose first,
    Mach :data:`CROSSFLOW_MACH` in sea-level air (``a``: the stack's AeroArrays): ``x_cm -
    M_pitch / F_z`` (independent of ``x_cm``: no rotation). Compiled: the full review's."""
    from rocketsim.vehicle.aero import A_ON, body_aero
    if a.ref[A_ON] == 0.0:
        return math.nan
    rho, sound = SEA_LEVEL
    speed = CROSSFLOW_MACH * sound
    _, _, fz, _, my, _ = body_aero(speed * math.cos(CROSSFLOW_ALPHA), 0.0, speed * math.sin(CROSSFLOW_ALPHA),
                                   0.0, 0.0, 0.0, rho, sound, 0.0, 0.0, a.ref, a.seg, a.fin, a.ca_nf, a.ca_tf)
    return -my / fz if fz != 0.0 else math.nan


def warnings(found: Review, spec, pad: bool) -> list[str]:
    """One line for each way ``found``'s design will fail: break up, tumble, not steer, not
    lift off (from a ``pad``), or (from a pad, in the air) fly as in vacuum for want of an
    ``aero`` section."""
    lines = []
    first = found.stages[0]
    if pad and spec.aero is None:
        lines.append("flies as in vacuum: the vehicle has no aero section, so from its site it meets "
                     "no drag, no lift and no structural limit in the air (give aero, its nose at "
                     "least; or aero: {aerodynamics: false} to fly without air on purpose)")
    if pad and first.thrust_to_weight < 1.0 and (spec.stages[0].engines or spec.stages[0].motors):
        lines.append(f"cannot lift off: thrust-to-weight {first.thrust_to_weight:.2f} at liftoff "
                     f"(stage {first.name!r} at sea level)")
    if found.aerodynamics:
        where = "the file's aero.limits" if found.limits_given else "the launcher default"
        for s in found.stages:
            if s.least_peak_axial_load_g > found.axial_limit_g:
                lines.append(f"will break up: the burn of stage {s.name!r} pushes the stack at "
                             f"{s.least_peak_axial_load_g:.1f} g however it is flown, past its "
                             f"{found.axial_limit_g:g} g axial limit ({where})")
        for p in found.phases:
            i = [st.name for st in spec.stages].index(p.stage)
            active = any(s.can_steer for s in found.stages[i:])
            if p.static_margin_cal < 0.0 and not active:
                lines.append(f"will tumble: static margin {p.static_margin_cal:.2f} calibres at "
                             f"{p.stage} {p.moment} (centre of pressure {p.centre_of_pressure_m:.3f} m "
                             f"above the base, ahead of the centre of mass at {p.centre_of_mass_m:.3f} m) "
                             "and nothing steers it (no gimbal, grid fins or RCS)")
                break
    for i, s in enumerate(found.stages):
        finned = any(m.startswith("fins") for t in found.stages[i:] for m in t.steers_with)
        if s.liquid and not any(t.can_steer for t in found.stages[i:]) and not finned:
            lines.append(f"cannot steer: stage {s.name!r} burns liquid engines with no gimbal "
                         "(gimbal_range), grid fins or RCS on it or above it")
    return lines
