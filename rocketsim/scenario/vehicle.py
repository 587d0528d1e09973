"""Staged vehicles, as pydantic v2 models (the ``stages:`` of a vehicle file).

A staged vehicle is a stack of stages listed **bottom to top** (first stage
first), optionally crowned by a payload and a fairing. The body x axis runs
along the stack from its base towards the nose; every position in a stage is
a height above that stage's own base, so stages can be rearranged or flown
alone (a separated stage is a vehicle of its own, see
:mod:`rocketsim.vehicle.build`).

What each part is, for the mass properties (:mod:`rocketsim.vehicle.mass_properties`):

* a stage's structure: a thin cylindrical shell of the stage's diameter and
  length, its centre of mass at ``structure_centre`` (default mid-stage);
* a tank: a thin cylindrical shell wall (``wall_mass``) and a propellant
  column, a solid cylinder of the tank's radius settled on the tank's bottom;
  the first tank listed is the lowest only if its ``position`` says so:
  positions are explicit (a methalox stage carries its oxidiser aft, so its
  LOX tank has the lower position);
* engines and other point masses: points on the axis or on a ring;
* payload: a uniform solid cylinder; fairing: a thin shell.

Engines belong to the stage they are listed under: that is what "staging as
data" means here. All tanks of a stage feed all engines of that stage, and
drain in proportion to their loads (the loads fix the mixture ratio), so
every tank of a stage runs dry at the same instant; 1 % of each stage's
propellant is unusable (:data:`rocketsim.constants.UNUSABLE_PROPELLANT`).
"""

from __future__ import annotations

import math
import os
from typing import Annotated, Literal, Optional, Union

from pathlib import Path

from pydantic import BaseModel, Field, ValidationInfo, field_validator, model_validator
from pydantic_core import InitErrorDetails, PydanticCustomError, ValidationError

from rocketsim.constants import ENGINE_TAIL_OFF, G0, MAX_DURATION
from rocketsim.scenario.bounds import (ANGLE, BODY_MASS, BOUNDS, BURN_TIME, COUNT, CURVE_THRUST,
                                       DEPLOY_DELAY, DEPLOY_HEIGHT, DRAG_AREA, EXTENT, INFLATION,
                                       ISP, MAX_COUNT, MAX_DENSITY, MAX_MASS, MAX_PRESSURE,
                                       MAX_SEPARATION_SPEED, MAX_SIZE, MAX_THROTTLE_RATE, MIN_DENSITY,
                                       MIN_DESCENT_SPEED, MIN_IMPULSE, OPENING_LAG, PART_MASS,
                                       RESPONSE, SIZE, SLEW, THRUST, descent_speed, within)
from rocketsim.scenario.motor_file import MotorFileError, read_thrust_curve
from rocketsim.scenario.units import (STRICT, Angle, AngularRate, Area, Density, Duration, Force,
                                      Fraction, Length, Mass, MassFlow, Pressure, SpecificImpulse,
                                      Speed)

# a vehicle's figures, within the physical bounds of rocketsim.scenario.bounds
PositiveLength = Annotated[Length, SIZE]
NonNegativeLength = Annotated[Length, EXTENT]
NonNegativeMass = Annotated[Mass, PART_MASS]
PositiveMass = Annotated[Mass, BODY_MASS]
Count = Annotated[int, COUNT]


class _Strict(BaseModel):
    """Unknown fields are errors (the same settings as ``models.Strict``, which imports us)."""

    model_config = STRICT


# the error type of a field this file needs although the schema has a default for others
REQUIRED = "required"


def field_error(loc: tuple, message: str, value, kind: str = "vehicle") -> ValidationError:
    """A validation error at ``loc`` (relative to the model raising it).

    Raised from a model validator, pydantic prefixes the model's own location,
    so the loader names the exact field (and its line) of the problem. ``kind``
    :data:`REQUIRED`: the field is needed here and not written (the loader then
    names it, as it does a missing field, at its parent's line).
    """
    return ValidationError.from_exception_data("vehicle", [InitErrorDetails(
        type=PydanticCustomError(kind, message), loc=loc, input=value)])


class TankSpec(_Strict):
    """A propellant tank: a thin-shell cylinder holding a settled liquid column."""

    name: str
    propellant: str = Field(description="what it holds, e.g. LOX, RP-1, LCH4, LH2")
    density: Annotated[Density, within(MIN_DENSITY, MAX_DENSITY, "density", "kg/m3")] = Field(
        description="propellant density, e.g. '1141 kg/m3' (LOX; RP-1 810, LH2 71, LCH4 423)")
    radius: PositiveLength = Field(description="inner radius of the cylinder, e.g. '1.83 m'")
    length: PositiveLength = Field(description="length of the cylinder, e.g. '22.9 m'")
    position: NonNegativeLength = Field(description="height of the tank's bottom above the stage "
                                        "base, e.g. '15.4 m'")
    wall_mass: NonNegativeMass = Field(0.0, description="mass of the tank wall (thin shell), "
                                       "e.g. '2500 kg'")
    propellant_mass: Optional[NonNegativeMass] = Field(
        None, description="propellant loaded at liftoff; default: full")
    feeds_engines: bool = Field(
        True, description="false: a tank only the RCS thrusters draw from (a cold-gas bottle), "
        "not the stage's engines")

    @property
    def capacity(self) -> float:
        """Propellant mass (kg) of a full tank."""
        return self.density * math.pi * self.radius ** 2 * self.length

    @property
    def load(self) -> float:
        """Propellant mass (kg) loaded."""
        return self.capacity if self.propellant_mass is None else self.propellant_mass

    @model_validator(mode="after")
    def _fits(self) -> "TankSpec":
        if self.propellant_mass is not None and self.propellant_mass > self.capacity * (1 + 1e-9):
            raise field_error(("propellant_mass",),
                              f"{self.propellant_mass:g} kg of {self.propellant} does not fit in tank "
                              f"{self.name!r}: it holds {self.capacity:.6g} kg "
                              f"(density x pi radius^2 x length)", self.propellant_mass)
        return self


# why an engine with a gimbal cone must say how fast it slews (no default is honest)
GIMBAL_RATE_WHY = ("an engine that cannot slew stays centred and cannot steer (an unfinned launcher "
                   "left so turns over in the air), and no rate is true of every actuator")


class EngineSpec(_Strict):
    """``count`` identical engines, evenly spaced on a ring (one on the axis if the radius is 0).

    Thrust ``T = tau T_vac - p_a A_e`` at throttle ``tau`` and ambient pressure
    ``p_a``; mass flow ``tau T_vac / (g0 Isp_vac)``. Give ``isp_vacuum`` or
    ``mass_flow`` (the full-throttle flow of one engine).
    """

    name: str
    count: Count = 1
    layout_radius: NonNegativeLength = Field(0.0, description="radius of the ring the engines sit on")
    layout_angle: Angle = Field(0.0, description="angle of the first engine from body +y about +x")
    position: NonNegativeLength = Field(0.0, description="height of the gimbal points above the stage base")
    mass: NonNegativeMass = Field(0.0, description="mass of one engine (a point mass at its gimbal point)")
    thrust_vacuum: Annotated[Force, THRUST] = Field(description="vacuum thrust of one engine at full "
                                                    "throttle, e.g. '914 kN' (a Merlin 1D)")
    isp_vacuum: Optional[Annotated[SpecificImpulse, ISP]] = Field(
        None, description="vacuum specific impulse, e.g. '311 s'")
    mass_flow: Optional[Annotated[MassFlow, Field(gt=0)]] = Field(
        None, description="mass flow of one engine at full throttle (the specific impulse it "
        "gives with the thrust is held to the bounds of isp_vacuum)")
    exit_area: Annotated[Area, within(0.0, MAX_SIZE ** 2, "size", "m2")] = Field(
        description="nozzle exit area, e.g. '0.68 m2'")
    exit_pressure: Optional[Annotated[Pressure, within(0.0, MAX_PRESSURE, "pressure", "Pa", above=True)]] = Field(
        None, description="nozzle exit pressure at full throttle (flow separation check); "
        "none: the nozzle never separates")
    throttle: tuple[Fraction, Fraction] = Field((1.0, 1.0), description="throttle range [min, max], fractions")
    throttle_rate: Annotated[float, within(0.0, MAX_THROTTLE_RATE, "throttle rate", "/s", above=True)] = Field(
        1.0, description="throttle slew limit, fraction of full thrust per second")
    gimbal_range: Annotated[Angle, ANGLE] = Field(
        0.0, description="half-angle of the gimbal cone, e.g. '5 deg'; default 0: the engine is "
        "fixed (it cannot steer)")
    gimbal_rate: Optional[Annotated[AngularRate, SLEW]] = Field(
        None, description="gimbal slew limit, e.g. '10 deg/s' (launcher actuators slew at about "
        f"5-20 deg/s); required with a gimbal_range: {GIMBAL_RATE_WHY}")
    ignition_delay: Annotated[Duration, Field(ge=0.2, le=0.5)] = Field(
        0.3, description="dead time from the ignition command to first thrust (0.2-0.5 s)")
    spool_up: Annotated[Duration, RESPONSE] = Field(1.0, description="time from first thrust to full thrust")
    tail_off: Annotated[Duration, RESPONSE] = Field(ENGINE_TAIL_OFF, description="time from shutdown to no thrust")
    restarts: Annotated[int, within(0, MAX_COUNT, "count")] = Field(
        0, description="ignitions allowed after the first")

    @field_validator("throttle")
    @classmethod
    def _throttle_range(cls, value):
        low, high = value
        if not (0.0 <= low <= high <= 1.0):
            raise ValueError(f"throttle range must be [min, max] with 0 <= min <= max <= 1 "
                             f"(got [{low:g}, {high:g}])")
        if high == 0.0:
            raise ValueError("throttle range: the maximum must be above 0")
        return value

    @model_validator(mode="after")
    def _one_flow(self) -> "EngineSpec":
        if (self.isp_vacuum is None) == (self.mass_flow is None):
            raise ValueError(f"engine {self.name!r}: give exactly one of 'isp_vacuum' or 'mass_flow'")
        if self.gimbal_range > 0.0 and not self.gimbal_rate:
            raise field_error(("gimbal_rate",), f"engine {self.name!r} gimbals "
                              f"{math.degrees(self.gimbal_range):g} deg but "
                              + ("its gimbal_rate is 0" if self.gimbal_rate == 0.0 else
                                 "gives no gimbal_rate")
                              + f": {GIMBAL_RATE_WHY}; give one, e.g. gimbal_rate: 10 deg/s "
                              "(launcher actuators slew at about 5-20 deg/s), or gimbal_range: "
                              "0 deg for a fixed engine", self.gimbal_rate,
                              REQUIRED if self.gimbal_rate is None else "vehicle")
        if self.mass_flow is not None:
            try:
                ISP.check(self.isp)
            except ValueError as error:
                raise field_error(("mass_flow",), f"with the thrust it gives a specific impulse of "
                                  f"{self.isp:g} s, which {error}", self.mass_flow) from None
        return self

    @property
    def isp(self) -> float:
        """Vacuum specific impulse (s)."""
        return self.isp_vacuum if self.isp_vacuum is not None else self.thrust_vacuum / (G0 * self.mass_flow)


class GrainSpec(_Strict):
    """The propellant grain of a solid motor: ``count`` BATES segments (hollow cylinders)
    stacked along the axis, centred in the motor. Only the core burns (the ends are taken
    as inhibited): the core widens as the propellant goes, each segment's length and
    outer diameter stay; the propellant's density is the motor's propellant mass over
    the grains' initial volume (docs/physics.md#solid-motors)."""

    count: Count = 1
    outer_diameter: PositiveLength
    core_diameter: NonNegativeLength = Field(description="initial diameter of the core")
    length: PositiveLength = Field(description="length of one segment")
    separation: NonNegativeLength = Field(0.0, description="axial gap between segments")

    @model_validator(mode="after")
    def _hollow(self) -> "GrainSpec":
        if self.core_diameter >= self.outer_diameter:
            raise field_error(("core_diameter",), "the core must be narrower than the grain",
                              self.core_diameter)
        return self

    @property
    def stack_length(self) -> float:
        """m, from the first segment's aft end to the last one's forward end."""
        return self.count * self.length + (self.count - 1) * self.separation


class MotorSpec(_Strict):
    """A solid rocket motor: a thrust curve against the time since ignition, a case and a
    propellant grain (docs/physics.md#solid-motors).

    Give the curve as ``file`` (a RASP ``.eng`` file, whose header gives the diameter,
    length, propellant and total masses, or a ``time,thrust`` CSV; relative to the
    vehicle file) or inline as ``thrust`` pairs; figures the file does not give go in
    the fields of the same names. The motor's aft end (its nozzle exit) sits at
    ``position`` above the stage's base; it reaches ``length`` above that. Its thrust
    acts along body x through the axis; propellant burns in proportion to the impulse
    delivered, ``m(t) = m0 (1 - I(t)/I_total)``. The case (total less propellant mass) is
    a thin cylindrical shell of the motor's size. Without ``grain`` the propellant is a
    uniform cylinder of the motor's size losing density, its centre fixed at the
    motor's centre. A motor lights once, at its ``ignition`` time or when the program
    lights it (``ignition: program``), and burns to the end of its curve.
    """

    name: str
    file: Optional[str] = Field(None, description="thrust-curve file (.eng or .csv), relative "
                                "to the vehicle file")
    thrust: Optional[list[tuple[Annotated[float, BURN_TIME], Annotated[float, CURVE_THRUST]]]] = Field(
        None, description="(time s since ignition, thrust N) pairs, times increasing; "
        "instead of 'file'")
    position: NonNegativeLength = Field(0.0, description="height of the motor's aft end (nozzle "
                                        "exit) above the stage base, e.g. '0 m'")
    diameter: Optional[PositiveLength] = Field(None, description="motor diameter (default: the .eng header's)")
    length: Optional[PositiveLength] = Field(None, description="motor length (default: the .eng header's)")
    propellant_mass: Optional[Annotated[Mass, within(0.0, MAX_MASS, "mass", "kg", above=True)]] = Field(
        None, description="default: the .eng header's")
    total_mass: Optional[PositiveMass] = Field(None, description="loaded motor, case and propellant "
                                               "(default: the .eng header's)")
    grain: Optional[GrainSpec] = None
    thrust_scale: Annotated[float, Field(gt=0, le=10)] = Field(
        1.0, description="multiplies the curve's thrust at every point, so its total impulse, "
        "at the same times and propellant: one motor's scatter about its curve (a campaign's "
        "dispersion of the impulse)")
    ignition: Union[Annotated[Duration, Field(ge=0, le=MAX_DURATION)], Literal["program"]] = Field(
        0.0, description="mission time of ignition (0: at the start, off the pad or rail), or "
        "program: lit by the flight program's fc.ignite (an upper stage, an air start)")

    @model_validator(mode="after")
    def _curve(self, info: ValidationInfo) -> "MotorSpec":
        if (self.file is None) == (self.thrust is None):
            raise ValueError(f"motor {self.name!r}: give exactly one of 'file' or 'thrust'")
        if self.file is not None:
            base = (info.context or {}).get("base_dir") if info is not None else None
            # realpath, not resolve: a loop of symlinks is then the file's read error, located
            path = Path(os.path.realpath((Path(base) if base is not None else Path()) / self.file))
            try:
                curve = read_thrust_curve(path)
            except MotorFileError as error:
                raise field_error(("file",), str(error), self.file) from None
            header = {"diameter": curve.diameter, "length": curve.length,
                      "propellant_mass": curve.propellant_mass, "total_mass": curve.total_mass}
            for key, value in header.items():
                if value is not None and getattr(self, key) is not None:
                    raise field_error((key,), f"the motor file's header gives the {key.replace('_', ' ')}; "
                                      "give it in one place", getattr(self, key))
                if value is not None:
                    object.__setattr__(self, key, value)
            object.__setattr__(self, "file", str(path))
            object.__setattr__(self, "thrust", [tuple(p) for p in curve.points])
        else:
            points = list(self.thrust)
            if points and points[0][0] > 0.0:
                points.insert(0, (0.0, 0.0))
            if points and points[0][1] != 0.0:
                raise field_error(("thrust",), "a thrust curve starts from no thrust at ignition "
                                  "(a first point (0, T) would jump at an instant the step cannot split)",
                                  self.thrust)
            if len(points) < 2 or any(b[0] <= a[0] for a, b in zip(points, points[1:])) \
                    or any(f < 0 for _, f in points) or not any(f > 0 for _, f in points):
                raise field_error(("thrust",), "a thrust curve needs increasing times from 0, no "
                                  "negative thrust and some thrust", self.thrust)
            object.__setattr__(self, "thrust", points)
        for key in ("diameter", "length", "propellant_mass", "total_mass"):
            if getattr(self, key) is None:
                raise field_error((key,), f"motor {self.name!r}: give its {key.replace('_', ' ')} "
                                  "(a CSV or inline curve has no header)", None)
        if self.total_impulse < MIN_IMPULSE:
            raise field_error(("file",) if self.file is not None else ("thrust",),
                              f"the thrust curve delivers {self.total_impulse:g} N s, less than the "
                              f"{MIN_IMPULSE:g} N s of any motor: {BOUNDS['impulse']}", self.file or self.thrust)
        if self.propellant_mass >= self.total_mass:
            raise field_error(("propellant_mass",), "the propellant mass must be less than the total "
                              "mass (the case is the difference)", self.propellant_mass)
        if self.grain is not None:
            if self.grain.outer_diameter > self.diameter * (1 + 1e-12):
                raise field_error(("grain", "outer_diameter"), "the grain is wider than its motor",
                                  self.grain.outer_diameter)
            if self.grain.stack_length > self.length * (1 + 1e-12):
                raise field_error(("grain", "length"), "the grain stack is longer than its motor",
                                  self.grain.length)
        return self

    @property
    def case_mass(self) -> float:
        """kg, the loaded motor less its propellant."""
        return self.total_mass - self.propellant_mass

    @property
    def total_impulse(self) -> float:
        """N s, the trapezoid integral of the (linearly interpolated) curve, times
        ``thrust_scale``."""
        pts = self.thrust
        return self.thrust_scale * sum(0.5 * (a[1] + b[1]) * (b[0] - a[0]) for a, b in zip(pts, pts[1:]))


class AfterEvent(_Strict):
    """An event of the body (by its name in the flight's events) and a delay after it."""

    event: str = Field(description="name of an event of this body, e.g. burnout, apogee, off_rail")
    delay: Annotated[Duration, DEPLOY_DELAY] = Field(0.0, description="after the event")


class HeightTrigger(_Strict):
    height: Annotated[Length, DEPLOY_HEIGHT] = Field(
        description="deploy on the way down at this height above the ground (the ground the "
        "body lands on: the ellipsoid, or the site's ground_height)")


class AfterTrigger(_Strict):
    after: AfterEvent


class ParachuteSpec(_Strict):
    """A parachute (docs/physics.md#parachutes): its drag area, opening lag and inflation
    time, and what deploys it: ``apogee`` (the vertical speed turns down), ``{height:
    300 m}`` (on the way down), ``{after: {event: burnout, delay: 2 s}}``, or ``program``
    (``fc.deploy_parachute(name)``; any parachute can be deployed by the program)."""

    name: str
    cd_s: Annotated[Area, DRAG_AREA] = Field(description="C_D S: drag coefficient times "
                                             "reference area, fully inflated, e.g. '5.65 m2' (a "
                                             "3 m flat circular canopy at C_D 0.8)")
    lag: Annotated[Duration, OPENING_LAG] = Field(1.0, description="from deployment to the start "
                                                  "of inflation")
    inflation: Annotated[Duration, INFLATION] = Field(1.0, description="from the start of "
                                                      "inflation to full drag area (linear)")
    deploy: Union[Literal["apogee", "program"], HeightTrigger, AfterTrigger] = Field(
        description="apogee, program, {height: <length>} or {after: {event: <name>, delay: <time>}}")
    releases: list[str] = Field([], description="parachutes (by name) cut away when this one "
                                "begins to inflate (a drogue released by the main); default none: "
                                "they stay on and their drag areas add")
    attachment: Optional[NonNegativeLength] = Field(
        None, description="height above the stage base of the shock cord's attachment on the "
        "axis, where the canopy's drag pulls (the body hangs from it); default the stage's top")


class PointMassSpec(_Strict):
    """A point mass on the axis (avionics, legs, fins, interstage...), or a ring of them."""

    name: str
    mass: PositiveMass
    position: NonNegativeLength = Field(description="height above the stage base")
    count: Count = 1
    radius: NonNegativeLength = Field(0.0, description="radius of the ring (legs, fins)")


class StageSpec(_Strict):
    """One stage: structure, tanks, engines and point masses; positions from its base."""

    name: str
    length: PositiveLength = Field(description="from the stage's base to its top (to the nose's "
                                   "tip if the nose caps it), e.g. '41.2 m'")
    diameter: PositiveLength = Field(description="e.g. '3.7 m'")
    structure_mass: PositiveMass = Field(
        description="e.g. '8890 kg': dry mass of the structure alone (a thin shell of the stage's size); "
        "tank walls, engines and point masses are listed separately. Every stage has one: "
        "it keeps the mass and inertia of a stage flying on its own, its tanks dry, positive")
    structure_centre: Optional[NonNegativeLength] = Field(
        None, description="height of the structure's centre of mass above the base; default mid-stage")
    tanks: list[TankSpec] = Field([], description="propellant tanks; those feeding engines feed "
                                   "all the stage's engines, drawn in proportion to their loads "
                                   "(the loads are the mixture ratio: each runs dry at the same "
                                   "instant)")
    engines: list[EngineSpec] = []
    point_masses: list[PointMassSpec] = []
    motors: list[MotorSpec] = Field([], description="solid motors (thrust curves) of the stage")
    parachutes: list[ParachuteSpec] = Field([], description="parachutes the stage carries")
    separates: bool = Field(True, description="drops away at staging (false: stays with the stage above)")

    @model_validator(mode="after")
    def _inside(self) -> "StageSpec":
        for i, tank in enumerate(self.tanks):
            if tank.position + tank.length > self.length * (1 + 1e-12):
                raise field_error(("tanks", i, "length"),
                                  f"tank {tank.name!r} is longer than its stage: from {tank.position:g} m "
                                  f"it reaches {tank.position + tank.length:g} m, the stage "
                                  f"{self.name!r} is {self.length:g} m long", tank.length)
            if tank.radius > 0.5 * self.diameter * (1 + 1e-12):
                raise field_error(("tanks", i, "radius"),
                                  f"tank {tank.name!r} (radius {tank.radius:g} m) is wider than its "
                                  f"stage (diameter {self.diameter:g} m)", tank.radius)
        if self.structure_centre is not None and self.structure_centre > self.length:
            raise field_error(("structure_centre",), "the structure's centre lies above the stage's top",
                              self.structure_centre)
        for i, part in enumerate(self.point_masses):
            if part.position > self.length * (1 + 1e-12):
                raise field_error(("point_masses", i, "position"),
                                  f"point mass {part.name!r} sits above the top of stage {self.name!r}",
                                  part.position)
        if self.engines and not self.tanks:
            raise field_error(("engines",), f"stage {self.name!r} has engines but no tanks to feed "
                              "them (list its propellant under 'tanks')", None)
        for i, motor in enumerate(self.motors):
            if motor.position + motor.length > self.length * (1 + 1e-12):
                raise field_error(("motors", i, "position"),
                                  f"motor {motor.name!r} reaches above the top of stage {self.name!r}",
                                  motor.position)
            if motor.diameter > self.diameter * (1 + 1e-12):
                raise field_error(("motors", i, "diameter"),
                                  f"motor {motor.name!r} is wider than stage {self.name!r}", motor.diameter)
        for i, chute in enumerate(self.parachutes):
            if chute.attachment is not None and chute.attachment > self.length * (1 + 1e-12):
                raise field_error(("parachutes", i, "attachment"),
                                  f"parachute {chute.name!r} is attached above the top of stage "
                                  f"{self.name!r}", chute.attachment)
        for i, engine in enumerate(self.engines):
            if engine.position > self.length * (1 + 1e-12):
                raise field_error(("engines", i, "position"),
                                  f"engine {engine.name!r} sits above the top of stage {self.name!r}",
                                  engine.position)
            if engine.layout_radius > 0.5 * self.diameter * (1 + 1e-12):
                raise field_error(("engines", i, "layout_radius"),
                                  f"the ring of engine {engine.name!r} (radius {engine.layout_radius:g} m) "
                                  f"is wider than stage {self.name!r} (diameter {self.diameter:g} m)",
                                  engine.layout_radius)
        return self

    @property
    def propellant_mass(self) -> float:
        """Propellant loaded in the tanks and the solid motors (kg)."""
        return sum(t.load for t in self.tanks) + sum(m.propellant_mass for m in self.motors)

    @property
    def dry_mass(self) -> float:
        """Structure, tank walls, engines, point masses and motor cases (kg)."""
        return (self.structure_mass + sum(t.wall_mass for t in self.tanks)
                + sum(e.mass * e.count for e in self.engines)
                + sum(p.mass * p.count for p in self.point_masses)
                + sum(m.case_mass for m in self.motors))


PAYLOAD_SIZE_WHY = ("the payload's cylinder is the top of the vehicle's outline where no fairing "
                    "covers it (its nose's shape, the reference diameter) and sets its inertia, and no "
                    "size is true of both a hobby rocket's payload bay and a launcher's satellite")


class PayloadSpec(_Strict):
    """The payload, a uniform solid cylinder sitting on top of the top stage; its
    ``length`` and ``diameter`` have no default (:data:`PAYLOAD_SIZE_WHY`)."""

    name: str = "payload"
    mass: NonNegativeMass
    length: PositiveLength = Field(
        description="e.g. '6 m' (a launcher's satellite) or '0.4 m' (a hobby rocket's nose cone, "
        "the nose included when it caps the payload)")
    diameter: PositiveLength = Field(
        description="e.g. '4 m' (inside a 5.2 m fairing) or the body's '0.1 m' (a hobby rocket's "
        "payload bay)")

    @model_validator(mode="before")
    @classmethod
    def _sized(cls, data):
        """A missing size refused with why and a typical value (not pydantic's bare 'missing')."""
        if isinstance(data, dict):
            for name, typical in (("length", "length: 6 m for a launcher's satellite, 0.4 m for a "
                                             "hobby rocket's nose cone"),
                                  ("diameter", "diameter: 4 m in a 5.2 m fairing, or the body's own "
                                               "for a hobby rocket's payload bay")):
                if name not in data:
                    raise field_error((name,), f"payload {data.get('name', 'payload')!r} gives no "
                                      f"{name}: {PAYLOAD_SIZE_WHY}; give it, e.g. {typical}", None, REQUIRED)
        return data


class FairingSpec(_Strict):
    """The payload fairing, a thin shell on top of the top stage, jettisoned as data says:
    it opens into two halves pushed apart along the body's y axis at ``separation_speed``
    (their relative speed; default 2 m/s, an estimate of the order of a spring or
    pneumatic pusher's push, not a published figure)."""

    mass: PositiveMass
    length: PositiveLength
    diameter: PositiveLength
    jettison: bool = True
    separation_speed: Annotated[Speed, within(0.0, MAX_SEPARATION_SPEED, "separation", "m/s")] = 2.0


def lightest_body(stages: list[StageSpec], s: int, payload: PayloadSpec | None) -> float:
    """kg, the least mass of a body carrying stage ``s`` (of ``stages``, bottom to top):
    its dry mass, and on the top stage the payload's (carried until a program deploys
    it); what its parachutes slow and its legs hold up (docs/physics.md#input-bounds)."""
    top = s == len(stages) - 1 and payload is not None
    return stages[s].dry_mass + (payload.mass if top else 0.0)


def check_staged(stages: list[StageSpec], extra_engines, payload: PayloadSpec | None = None) -> None:
    """Cross-field checks of a staged vehicle (raise a located ValidationError)."""
    if extra_engines is not None:
        raise field_error(("engines",), "an engine must belong to a stage: list it under a "
                          "stage's 'engines' (stages are listed bottom to top)", extra_engines)
    if not stages:
        raise field_error(("stages",), "a staged vehicle needs at least one stage", stages)
    names = [c.name for st in stages for c in st.parachutes]
    for s, st in enumerate(stages):
        for i, chute in enumerate(st.parachutes):
            if names.count(chute.name) > 1:
                raise field_error(("stages", s, "parachutes", i, "name"), f"two parachutes are named "
                                  f"{chute.name!r}: fc.deploy_parachute and 'releases' name them", chute.name)
    for s, st in enumerate(stages):
        if st.parachutes:
            # every canopy open at once on the lightest body that carries them
            i = max(range(len(st.parachutes)), key=lambda i: st.parachutes[i].cd_s)
            mass, area = lightest_body(stages, s, payload), sum(c.cd_s for c in st.parachutes)
            speed = descent_speed(mass, area)
            if speed < MIN_DESCENT_SPEED:
                raise field_error(("stages", s, "parachutes", i, "cd_s"), f"the lightest body "
                                  f"carrying stage {st.name!r} ({mass:g} kg, dry) under all its "
                                  f"parachutes ({area:g} m2 of C_D S) would descend at {speed:.3g} m/s "
                                  f"in sea-level air, slower than {MIN_DESCENT_SPEED:g} m/s: "
                                  f"{BOUNDS['descent']}", st.parachutes[i].cd_s)
        for i, chute in enumerate(st.parachutes):
            for k, other in enumerate(chute.releases):
                if other not in names or other == chute.name:
                    raise field_error(("stages", s, "parachutes", i, "releases", k),
                                      f"parachute {chute.name!r} releases {other!r}, not another "
                                      f"parachute of the vehicle ({', '.join(names)})", other)
