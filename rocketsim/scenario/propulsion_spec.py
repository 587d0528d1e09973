"""What drives a stage, as pydantic v2 models: its propellant tanks (thin-shell cylinders
holding a settled liquid column), its liquid engines (thrust and specific impulse at sea level
and in vacuum, throttle, gimbal, start and shutdown) and its solid motors (a thrust curve from
a RASP ``.eng`` file or a tabulated one, or a grain whose burn it computes), each checked
against the physical bounds of :mod:`rocketsim.scenario.bounds`; the stages that carry them
are :mod:`rocketsim.scenario.vehicle`'s."""

from __future__ import annotations

import math
import os
from pathlib import Path
from typing import Annotated, Literal, Optional, Union

from pydantic import Field, ValidationInfo, field_validator, model_validator

from rocketsim.constants import ENGINE_TAIL_OFF, G0, MAX_DURATION
from rocketsim.scenario.bounds import (ANGLE, BOUNDS, BURN_TIME, CURVE_THRUST, ISP, MAX_COUNT, MAX_DENSITY,
                                       MAX_MASS, MAX_PRESSURE, MAX_SIZE, MAX_THROTTLE_RATE, MIN_DENSITY,
                                       MIN_IMPULSE, RESPONSE, SLEW, THRUST, within)
from rocketsim.scenario.motor_file import MotorFileError, read_thrust_curve
from rocketsim.scenario.strict import (REQUIRED, Count, NonNegativeLength, NonNegativeMass, PositiveLength,
                                       PositiveMass, Strict, field_error)
from rocketsim.scenario.units import (Angle, AngularRate, Area, Density, Duration, Force, Fraction, Mass,
                                      MassFlow, Pressure, SpecificImpulse)


class TankSpec(Strict):
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


class EngineSpec(Strict):
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


class GrainSpec(Strict):
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


class MotorSpec(Strict):
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
