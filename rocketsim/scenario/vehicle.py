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
from typing import Annotated, Optional

from pydantic import BaseModel, Field, field_validator, model_validator
from pydantic_core import InitErrorDetails, PydanticCustomError, ValidationError

from rocketsim.constants import ENGINE_TAIL_OFF, G0
from rocketsim.scenario.units import (STRICT, Angle, AngularRate, Area, Density, Duration, Force,
                                      Fraction, Length, Mass, MassFlow, Pressure, SpecificImpulse,
                                      Speed)

PositiveLength = Annotated[Length, Field(gt=0)]
NonNegativeLength = Annotated[Length, Field(ge=0)]
NonNegativeMass = Annotated[Mass, Field(ge=0)]
PositiveMass = Annotated[Mass, Field(gt=0)]


class _Strict(BaseModel):
    """Unknown fields are errors (the same settings as ``models.Strict``, which imports us)."""

    model_config = STRICT


def field_error(loc: tuple, message: str, value) -> ValidationError:
    """A validation error at ``loc`` (relative to the model raising it).

    Raised from a model validator, pydantic prefixes the model's own location,
    so the loader names the exact field (and its line) of the problem.
    """
    return ValidationError.from_exception_data("vehicle", [InitErrorDetails(
        type=PydanticCustomError("vehicle", message), loc=loc, input=value)])


class TankSpec(_Strict):
    """A propellant tank: a thin-shell cylinder holding a settled liquid column."""

    name: str
    propellant: str = Field(description="what it holds, e.g. LOX, RP-1, LCH4, LH2")
    density: Annotated[Density, Field(gt=0)] = Field(description="propellant density")
    radius: PositiveLength = Field(description="inner radius of the cylinder")
    length: PositiveLength = Field(description="length of the cylinder")
    position: NonNegativeLength = Field(description="height of the tank's bottom above the stage base")
    wall_mass: NonNegativeMass = Field(0.0, description="mass of the tank wall (thin shell)")
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


class EngineSpec(_Strict):
    """``count`` identical engines, evenly spaced on a ring (one on the axis if the radius is 0).

    Thrust ``T = tau T_vac - p_a A_e`` at throttle ``tau`` and ambient pressure
    ``p_a``; mass flow ``tau T_vac / (g0 Isp_vac)``. Give ``isp_vacuum`` or
    ``mass_flow`` (the full-throttle flow of one engine).
    """

    name: str
    count: Annotated[int, Field(ge=1)] = 1
    layout_radius: NonNegativeLength = Field(0.0, description="radius of the ring the engines sit on")
    layout_angle: Angle = Field(0.0, description="angle of the first engine from body +y about +x")
    position: NonNegativeLength = Field(0.0, description="height of the gimbal points above the stage base")
    mass: NonNegativeMass = Field(0.0, description="mass of one engine (a point mass at its gimbal point)")
    thrust_vacuum: Annotated[Force, Field(gt=0)] = Field(description="vacuum thrust of one engine at full throttle")
    isp_vacuum: Optional[SpecificImpulse] = Field(None, description="vacuum specific impulse")
    mass_flow: Optional[MassFlow] = Field(None, description="mass flow of one engine at full throttle")
    exit_area: Annotated[Area, Field(ge=0)] = Field(description="nozzle exit area")
    exit_pressure: Optional[Annotated[Pressure, Field(gt=0)]] = Field(
        None, description="nozzle exit pressure at full throttle (flow separation check); "
        "none: the nozzle never separates")
    throttle: tuple[Fraction, Fraction] = Field((1.0, 1.0), description="throttle range [min, max], fractions")
    throttle_rate: Annotated[float, Field(gt=0)] = Field(
        1.0, description="throttle slew limit, fraction of full thrust per second")
    gimbal_range: Annotated[Angle, Field(ge=0)] = Field(0.0, description="half-angle of the gimbal cone")
    gimbal_rate: Annotated[AngularRate, Field(ge=0)] = Field(0.0, description="gimbal slew limit")
    ignition_delay: Annotated[Duration, Field(ge=0.2, le=0.5)] = Field(
        0.3, description="dead time from the ignition command to first thrust (0.2-0.5 s)")
    spool_up: Annotated[Duration, Field(gt=0)] = Field(1.0, description="time from first thrust to full thrust")
    tail_off: Annotated[Duration, Field(gt=0)] = Field(ENGINE_TAIL_OFF, description="time from shutdown to no thrust")
    restarts: Annotated[int, Field(ge=0)] = Field(0, description="ignitions allowed after the first")

    @field_validator("isp_vacuum", "mass_flow")
    @classmethod
    def _positive(cls, value, info):
        if value is not None and value <= 0:
            raise ValueError(f"{info.field_name} must be positive (got {value:g})")
        return value

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
        return self

    @property
    def isp(self) -> float:
        """Vacuum specific impulse (s)."""
        return self.isp_vacuum if self.isp_vacuum is not None else self.thrust_vacuum / (G0 * self.mass_flow)


class PointMassSpec(_Strict):
    """A point mass on the axis (avionics, legs, fins, interstage...), or a ring of them."""

    name: str
    mass: PositiveMass
    position: NonNegativeLength = Field(description="height above the stage base")
    count: Annotated[int, Field(ge=1)] = 1
    radius: NonNegativeLength = Field(0.0, description="radius of the ring (legs, fins)")


class StageSpec(_Strict):
    """One stage: structure, tanks, engines and point masses; positions from its base."""

    name: str
    length: PositiveLength
    diameter: PositiveLength
    structure_mass: NonNegativeMass = Field(
        description="dry mass of the structure alone (a thin shell of the stage's size); "
        "tank walls, engines and point masses are listed separately")
    structure_centre: Optional[NonNegativeLength] = Field(
        None, description="height of the structure's centre of mass above the base; default mid-stage")
    tanks: list[TankSpec] = []
    engines: list[EngineSpec] = []
    point_masses: list[PointMassSpec] = []
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
        for i, engine in enumerate(self.engines):
            if engine.position > self.length * (1 + 1e-12):
                raise field_error(("engines", i, "position"),
                                  f"engine {engine.name!r} sits above the top of stage {self.name!r}",
                                  engine.position)
        return self

    @property
    def propellant_mass(self) -> float:
        return sum(t.load for t in self.tanks)

    @property
    def dry_mass(self) -> float:
        """Structure, tank walls, engines and point masses (kg)."""
        return (self.structure_mass + sum(t.wall_mass for t in self.tanks)
                + sum(e.mass * e.count for e in self.engines)
                + sum(p.mass * p.count for p in self.point_masses))


class PayloadSpec(_Strict):
    """The payload, a uniform solid cylinder sitting on top of the top stage."""

    name: str = "payload"
    mass: NonNegativeMass
    length: PositiveLength = 1.0
    diameter: PositiveLength = 1.0


class FairingSpec(_Strict):
    """The payload fairing, a thin shell on top of the top stage, jettisoned as data says:
    it opens into two halves pushed apart along the body's y axis at ``separation_speed``
    (their relative speed; default 2 m/s, an estimate of the order of a spring or
    pneumatic pusher's push, not a published figure)."""

    mass: PositiveMass
    length: PositiveLength
    diameter: PositiveLength
    jettison: bool = True
    separation_speed: Annotated[Speed, Field(ge=0)] = 2.0


def check_staged(stages: list[StageSpec], extra_engines) -> None:
    """Cross-field checks of a staged vehicle (raise a located ValidationError)."""
    if extra_engines is not None:
        raise field_error(("engines",), "an engine must belong to a stage: list it under a "
                          "stage's 'engines' (stages are listed bottom to top)", extra_engines)
    if not stages:
        raise field_error(("stages",), "a staged vehicle needs at least one stage", stages)
