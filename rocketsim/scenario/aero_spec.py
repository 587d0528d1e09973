"""The ``aero:`` section of a staged vehicle file: shape, fins, grid fins, legs, RCS, heat shield.

Optional: a vehicle without it flies without aerodynamics or ground contact.
Positions are heights above the base of the named stage (as everywhere in a
vehicle file); a leg's foot may sit below its stage's base (negative). The
body's outline is the stack of the stages' cylinders, then the payload fairing
(or payload) on top; the top
``nose.length`` of it is the nose. See :mod:`rocketsim.vehicle.aero` for the
models these figures feed.
"""

from __future__ import annotations

from typing import Annotated, Literal, Optional

from pydantic import Field, field_validator

from rocketsim.constants import (BODY_CONTACT_DAMPING, BODY_CONTACT_RATE, BODY_CONTACT_STIFFNESS,
                                 FRICTION_REGULARISATION)
from rocketsim.scenario.bounds import (ANGLE, AREA, BODY_MASS, BOUNDS, COUNT, DIRECTION, ISP, MAX_AXIAL_LOAD,
                                       MAX_COEFFICIENT, MAX_CONTACT_RATE, MAX_DAMPING, MAX_FRICTION,
                                       MAX_FRICTION_SPEED, MAX_MACH, MAX_Q_ALPHA, MAX_SPECIFIC_HEAT,
                                       MAX_STIFFNESS, MAX_TEMPERATURE, MIN_FRICTION_SPEED, MIN_SPECIFIC_HEAT,
                                       SLEW, STATION, THRUST, contact_rate, within)
from rocketsim.scenario.strict import REQUIRED, NonNegativeLength, PositiveLength, Strict, field_error
from rocketsim.scenario.units import (Acceleration, Angle, AngularRate, Area, Force, Length, Mass, Speed,
                                      SpecificImpulse, Temperature)
from rocketsim.scenario.vehicle import lightest_body

# a vehicle's figures, within the physical bounds of rocketsim.scenario.bounds
STIFFNESS = within(0.0, MAX_STIFFNESS, "stiffness", "N/m", above=True)
DAMPING = within(0.0, MAX_DAMPING, "damping", "N s/m")
Station = Annotated[Length, STATION]
# a (Mach, C_A) row of an axial-force table
AxialRow = tuple[Annotated[float, within(0.0, MAX_MACH, "mach")],
                 Annotated[float, within(0.0, MAX_COEFFICIENT, "coefficient")]]


class NoseSpec(Strict):
    """The nose: the top ``length`` of the part it caps (the fairing, else the payload, else
    the top stage), a cone or a tangent ogive (or blunt: no nose lift). That part's
    ``length`` includes it: a stage that caps the stack reaches to the nose's tip, and a
    stage written to end at the nose's base puts the nose inside it (docs/physics.md#the-stack-and-its-nose)."""

    length: NonNegativeLength = Field(
        description="length of the nose from its base to the tip, e.g. '0.61 m': the top of the "
        "part it caps (the fairing, else the payload, else the top stage), whose length includes it")
    shape: Literal["cone", "ogive", "blunt"] = Field("ogive", description="cone, ogive (tangent) "
                                                     "or blunt (no nose lift)")


class BoattailSpec(Strict):
    """A conical boattail: the bottom ``length`` of the vehicle's lowest stage narrows from
    the stage's diameter to ``diameter`` at its base (part of the stage's length, as the
    nose is part of the part it caps). Its slender-body lift acts against the nose's
    (Barrowman's conical transition: it moves the centre of pressure forward)."""

    stage: str = Field(description="name of the vehicle's lowest stage (the boattail leaves "
                       "with it at a separation)")
    length: PositiveLength = Field(description="length of the cone frustum, e.g. '0.127 m'")
    diameter: PositiveLength = Field(description="diameter at the base, narrower than the "
                                     "stage's, e.g. '155 mm'")


class FinSetSpec(Strict):
    """A set of 3 or 4 flat trapezoidal fins (Barrowman's normal-force slope and centre of pressure)."""

    stage: str = Field(description="name of the stage the fins are on")
    count: Annotated[int, Field(ge=3, le=4)] = 4
    position: Station = Field(description="height of the root chord's leading (upper) edge above "
                              "the stage base, e.g. '0.27 m'")
    root_chord: PositiveLength = Field(description="e.g. '0.15 m'")
    tip_chord: NonNegativeLength = Field(description="e.g. '0.08 m'")
    span: PositiveLength = Field(description="from the body to the tip, e.g. '0.17 m'")
    sweep: NonNegativeLength = Field(0.0, description="axial distance from the root's to the tip's leading edge")


class GridFinSpec(Strict):
    """Grid fins on arms round the stage (``count`` evenly spaced from body +y)."""

    stage: str
    count: Annotated[int, Field(ge=2), COUNT] = 4
    position: Station = Field(description="height of the fins' centre above the stage base")
    radius: PositiveLength = Field(description="distance of each fin's centre of pressure from the axis")
    area: Annotated[Area, AREA] = Field(description="frontal (reference) area of one fin")
    max_deflection: Annotated[Angle, Field(gt=0), ANGLE] = Field(0.349, description="deflection limit (default 20 deg)")
    rate: Annotated[AngularRate, Field(gt=0), SLEW] = Field(1.047, description="slew limit (default 60 deg/s)")
    stall: Annotated[Angle, Field(gt=0), ANGLE] = Field(0.436, description="stall angle of the lattice (default 25 deg)")


class LegSpec(Strict):
    """Landing legs: ``count`` feet on a ring, each a stiff spring with damping and friction."""

    stage: str
    count: Annotated[int, Field(ge=3), COUNT] = 4
    position: Station = Field(description="height of the feet above the stage base (negative: below it)")
    radius: PositiveLength = Field(description="radius of the ring of feet")
    stiffness: Annotated[float, STIFFNESS] = Field(description="spring stiffness of one leg, N/m")
    damping: Annotated[float, DAMPING] = Field(description="damping of one leg, N s/m")
    friction: Annotated[float, within(0.0, MAX_FRICTION, "friction")] = Field(
        0.6, description="Coulomb friction coefficient")
    friction_speed: Annotated[Speed, within(MIN_FRICTION_SPEED, MAX_FRICTION_SPEED, "friction speed",
                                            "m/s")] = Field(
        FRICTION_REGULARISATION, description="sliding speed below which friction is regularised "
        "(a damper of mu N / speed; keep mu N r^2 / (speed I_roll) under ~400 /s)")


class ThrusterSpec(Strict):
    """One reaction-control thruster, drawing from one of its stage's tanks."""

    stage: str
    tank: str = Field(description="name of the tank (of that stage) it draws from")
    position: Station = Field(description="height above the stage base")
    y: Station = 0.0
    z: Station = 0.0
    direction: tuple[Annotated[float, DIRECTION], Annotated[float, DIRECTION],
                     Annotated[float, DIRECTION]] = Field(
        description="thrust direction in body axes (normalised)")
    thrust: Annotated[Force, THRUST]
    isp: Annotated[SpecificImpulse, ISP]

    @field_validator("direction")
    @classmethod
    def _nonzero(cls, value):
        if sum(c * c for c in value) == 0.0:
            raise ValueError("a thruster's direction must not be zero")
        return value


class HeatShieldSpec(Strict):
    """A heat shield as one lumped thermal mass at the stagnation point."""

    nose_radius: PositiveLength = Field(description="effective nose radius for Sutton-Graves")
    mass: Annotated[Mass, BODY_MASS]
    specific_heat: Annotated[float, within(MIN_SPECIFIC_HEAT, MAX_SPECIFIC_HEAT, "specific heat",
                                           "J/(kg K)")] = Field(description="J/(kg K)")
    area: Annotated[Area, AREA] = Field(description="heated (and radiating) area")
    emissivity: Annotated[float, Field(gt=0, le=1)] = 0.85
    initial_temperature: Annotated[Temperature, within(0.0, MAX_TEMPERATURE, "temperature", "K",
                                                       above=True)] = 290.0


class LimitsSpec(Strict):
    """A vehicle's own structural limits (docs/physics.md#structural-limits), in place of
    the launcher's assumed without them (250 kPa deg, 15 g): a small hobby rocket takes
    far higher loads, and one whose motor alone passes 15 g must give its own."""

    q_alpha: Optional[Annotated[float, within(0.0, MAX_Q_ALPHA, "structural limit", "Pa deg",
                                              above=True)]] = Field(
        None, description="bending load q alpha that breaks the vehicle, Pa deg, e.g. 500000; "
        "default 250000 (a launcher's, assumed)")
    axial_load: Optional[Annotated[Acceleration, within(0.0, MAX_AXIAL_LOAD, "structural limit",
                                                        "m/s2", above=True)]] = Field(
        None, description="axial load that breaks the vehicle, e.g. '40 g'; default 15 g (a "
        "launcher's, assumed), required when a stage's motor alone passes it")


class AeroSpec(Strict):
    """Aerodynamics and ground contact of a staged vehicle."""

    aerodynamics: bool = Field(
        True, description="false: no air forces, grid fins or ground contact (a spacecraft "
        "that only flies in vacuum); the section then carries only its RCS thrusters")
    nose: NoseSpec = NoseSpec(length=0.0, shape="blunt")
    segments: Annotated[int, Field(ge=10, le=200)] = Field(20, description="body segments for the crossflow")
    axial_nose_first: Optional[list[AxialRow]] = Field(
        None, description="(Mach, C_A) pairs, increasing Mach; default the physics model's table")
    axial_tail_first: Optional[list[AxialRow]] = Field(
        None, description="(Mach, C_A) pairs, increasing Mach; default the physics model's table")
    boattail: Optional[BoattailSpec] = Field(None, description="a conical boattail at the "
                                             "base of the lowest stage")
    fins: list[FinSetSpec] = []
    grid_fins: list[GridFinSpec] = []
    legs: list[LegSpec] = []
    body_contact_stiffness: Optional[Annotated[float, STIFFNESS]] = Field(
        None, description="N/m, the body's ends and engine bells touching the ground; default "
        "2e7, or 1e4 per kg of dry mass under 2 t (docs/physics.md#ground-contact)")
    body_contact_damping: Optional[Annotated[float, DAMPING]] = Field(
        None, description="N s/m; default 2e5, or 100 per kg of dry mass under 2 t")
    rcs: list[ThrusterSpec] = []
    heat_shield: Optional[HeatShieldSpec] = None
    limits: LimitsSpec = Field(LimitsSpec(), description="structural limits in place of the "
                               "launcher's assumed (15 g, 250 000 Pa deg)")

    def body_springs(self, dry_mass: float) -> tuple[float, float]:
        """``(stiffness N/m, damping N s/m)`` of each of the body's contact points: the
        file's, else the defaults of :data:`~rocketsim.constants.BODY_CONTACT_STIFFNESS`,
        softened for a vehicle of ``dry_mass`` (kg) under 2 t to a natural frequency of
        :data:`~rocketsim.constants.BODY_CONTACT_RATE` (docs/physics.md#ground-contact)."""
        k = min(BODY_CONTACT_STIFFNESS, dry_mass * BODY_CONTACT_RATE ** 2)
        c = min(BODY_CONTACT_DAMPING, dry_mass * BODY_CONTACT_RATE)
        return (k if self.body_contact_stiffness is None else self.body_contact_stiffness,
                c if self.body_contact_damping is None else self.body_contact_damping)

    @field_validator("axial_nose_first", "axial_tail_first")
    @classmethod
    def _table(cls, value):
        if value is None:
            return value
        if len(value) < 2:
            raise ValueError("an axial table needs at least two (Mach, C_A) rows")
        machs = [m for m, _ in value]
        if any(b <= a for a, b in zip(machs, machs[1:])) or machs[0] < 0:
            raise ValueError("an axial table's Mach numbers must start at 0 or above and increase")
        if any(c < 0 for _, c in value):
            raise ValueError("an axial coefficient cannot be negative")
        return value


def check_aero(aero: AeroSpec | None, stages, payload=None, fairing=None) -> None:
    """Every part of ``aero`` names a stage of the vehicle (and a thruster a tank of its
    stage), and the nose is no longer than the part it caps at liftoff (the fairing, else
    the payload, else the top stage; once a fairing is gone, out of the air, the nose's
    shape is taken from the top of what is left); raises a located ValidationError
    (relative to the vehicle)."""
    if aero is None or stages is None:
        return
    stack = sum(st.length for st in stages) + (payload.length if payload is not None else 0.0)
    if fairing is not None:
        part, length = f"the fairing ({fairing.length:g} m)", fairing.length
    elif payload is not None:
        part, length = f"the payload {payload.name!r} ({payload.length:g} m)", payload.length
    else:
        part, length = f"the top stage {stages[-1].name!r} ({stages[-1].length:g} m)", stages[-1].length
    if aero.nose.length > length * (1 + 1e-12):
        raise field_error(("aero", "nose", "length"), f"the nose ({aero.nose.length:g} m) is "
                          f"longer than {part}, the part it caps: the nose is the top of that "
                          "part, and its length includes the nose", aero.nose.length)
    by_name = {st.name: st for st in stages}
    _check_boattail(aero, stages, stack)
    for label in ("fins", "grid_fins", "legs", "rcs"):
        for i, part in enumerate(getattr(aero, label)):
            if part.stage not in by_name:
                raise field_error(("aero", label, i, "stage"), f"no stage is named {part.stage!r} "
                                  f"(stages: {', '.join(by_name)})", part.stage)
            if label == "rcs" and part.tank not in [t.name for t in by_name[part.stage].tanks]:
                raise field_error(("aero", label, i, "tank"), f"stage {part.stage!r} has no tank named "
                                  f"{part.tank!r}", part.tank)
    if not aero.aerodynamics:           # no ground contact
        return
    held = {st.name: lightest_body(stages, s, payload) for s, st in enumerate(stages)}
    for i, leg in enumerate(aero.legs):
        # all the feet on the ground together, holding the lightest body of the leg's stage
        _check_contact(("aero", "legs", i), f"{leg.count} legs", held[leg.stage],
                       leg.count * leg.stiffness, leg.count * leg.damping)
    if aero.body_contact_stiffness is not None or aero.body_contact_damping is not None:
        # the lightest body standing on the four points of its base ring
        lightest = min(held.values())
        k, c = aero.body_springs(lightest)
        _check_contact(("aero",), "the body's 4 base points", lightest, 4 * k, 4 * c,
                       "body_contact_stiffness", "body_contact_damping")


def check_axial_load(vehicle) -> None:
    """A staged ``vehicle`` flying in the air without its own axial limit is held to the
    launcher default (docs/physics.md#structural-limits): if a stage's burn alone pushes the
    stack past it however it is flown (solid motors; liquid engines at their least
    throttle), the default cannot be this vehicle's, and the limit is required (a located
    ValidationError at ``aero.limits``)."""
    aero = vehicle.aero
    if aero is None or not aero.aerodynamics or aero.limits.axial_load is not None:
        return
    from rocketsim.constants import STRUCTURE_AXIAL_LIMIT_G
    from rocketsim.vehicle.stage_burns import stage_loads
    for i, stage in enumerate(vehicle.stages):
        loads = stage_loads(vehicle, i)
        if loads.least_peak_axial_load_g > STRUCTURE_AXIAL_LIMIT_G:
            what = (f"the {', '.join(loads.motors)} of stage {stage.name!r} "
                    + ("pushes" if len(loads.motors) == 1 else "push") if loads.motors
                    else f"the engines of stage {stage.name!r}, at their least throttle, push")
            raise field_error(("aero", "limits"), f"{what} the stack at "
                              f"{loads.least_peak_axial_load_g:.1f} g, past the "
                              f"{STRUCTURE_AXIAL_LIMIT_G:g} g axial limit assumed for a launcher's "
                              "structure when the file gives none: it would break up on the pad. "
                              "Give the axial load this airframe is built for, e.g. limits: "
                              "{axial_load: 40 g} (docs/physics.md#structural-limits)", None, REQUIRED)


def _check_boattail(aero: AeroSpec, stages, stack: float) -> None:
    """A boattail narrows the base of the lowest stage, within that stage and below the
    nose of the ``stack`` (m, the stages and the payload; a located ValidationError
    otherwise)."""
    tail = aero.boattail
    if tail is None:
        return
    lowest = stages[0]
    if tail.stage != lowest.name:
        raise field_error(("aero", "boattail", "stage"), f"a boattail narrows the base of the "
                          f"vehicle's lowest stage, {lowest.name!r}, not {tail.stage!r}", tail.stage)
    if tail.diameter >= lowest.diameter:
        raise field_error(("aero", "boattail", "diameter"), f"the boattail's base "
                          f"({tail.diameter:g} m) must be narrower than stage {lowest.name!r} "
                          f"({lowest.diameter:g} m)", tail.diameter)
    if tail.length > lowest.length * (1 + 1e-12) or tail.length + aero.nose.length > stack * (1 + 1e-12):
        raise field_error(("aero", "boattail", "length"), f"the boattail ({tail.length:g} m) "
                          f"reaches above stage {lowest.name!r} ({lowest.length:g} m) or into the "
                          "nose", tail.length)


def _check_contact(loc: tuple, what: str, mass: float, stiffness: float, damping: float,
                   stiffness_field: str = "stiffness", damping_field: str = "damping") -> None:
    """Refuse (a located ValidationError at ``loc`` + the field) contact springs
    ``stiffness`` (N/m) and dampers ``damping`` (N s/m), all of ``what`` together,
    whose fastest mode on ``mass`` (kg) is beyond
    :data:`~rocketsim.scenario.bounds.MAX_CONTACT_RATE`: the damper's field when the
    mode is overdamped (c^2 > 4 m k), else the spring's."""
    rate = contact_rate(mass, stiffness, damping)
    if rate <= MAX_CONTACT_RATE:
        return
    overdamped = damping * damping > 4.0 * mass * stiffness
    name = damping_field if overdamped else stiffness_field
    figure = (f"damping {damping:g} N s/m" if overdamped else f"stiffness {stiffness:g} N/m")
    raise field_error(loc + (name,), f"{what} ({figure} together) on {mass:g} kg (the dry mass they "
                      f"hold up) are a mode of {rate:g} /s, faster than {MAX_CONTACT_RATE:g} /s: "
                      f"{BOUNDS['contact rate']}", damping if overdamped else stiffness)
