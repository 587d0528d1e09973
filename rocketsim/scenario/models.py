"""The shapes of scenario files, as pydantic v2 models.

A scenario names a vehicle, a launch site, the day's weather, a mission and
a flight-computer program. Each of ``vehicle``, ``site`` and ``mission`` is
either written inline or given as a path to its own YAML file, resolved
relative to the scenario file. Quantities are SI numbers or strings with a
unit (``"400 km"``, ``"51.6 deg"``; see :mod:`rocketsim.scenario.units`);
angles always carry a unit.

Where a flight starts (a site, an orbit, a state vector, a rail) is
:mod:`rocketsim.scenario.start_spec`'s; a staged vehicle's stages, payload and
fairing :mod:`rocketsim.scenario.vehicle`'s, their tanks, engines and motors
:mod:`rocketsim.scenario.propulsion_spec`'s. Every model forbids unknown fields
(:class:`rocketsim.scenario.strict.Strict`), so a misspelt field is an error (with a
"did you mean"), never silently ignored. New capabilities add optional fields
(``stages:`` on a vehicle, say) so existing files keep validating.
"""

from __future__ import annotations

import datetime as dt
import math
from pathlib import Path
from typing import Annotated, Literal, Optional, Union

from pydantic import Field, field_validator, model_validator

from rocketsim.constants import (EARTH_RADIUS_EQ, MAX_DURATION, MAX_HEADLESS_STEP, MAX_START_DISTANCE,
                                 MIN_STEP, STEP)
from rocketsim.errors import ArgumentError
from rocketsim.limits import MAX_SEED, check_data
from rocketsim.scenario.bounds import (BOUNDS, MAX_PROGRAM_CPU, MAX_PROGRAM_WAIT, MAX_SIZE, MIN_SIZE, SIZE,
                                       within)
from rocketsim.scenario.classic_range import CLASSIC, classic_site
from rocketsim.scenario.weather import Weather
from rocketsim.scenario.units import Angle, Duration, Frequency, Inertia, Length, parse_quantity
from rocketsim.scenario.aero_spec import AeroSpec, check_aero, check_axial_load
from rocketsim.scenario.start_spec import ELEMENTS_DESCRIPTION, ElementsKind, Rate, SiteSpec, StartSpec, TargetPad
from rocketsim.scenario.strict import PositiveMass, Strict, field_error
from rocketsim.scenario.vehicle import FairingSpec, PayloadSpec, StageSpec, check_staged
from rocketsim.scenario.stage_selection import keep_stages, reload_tanks, stack_spacecraft

UNIX_EPOCH = dt.datetime(1970, 1, 1, tzinfo=dt.timezone.utc)

# a path to a YAML file of its own, resolved by the loader relative to the scenario
FileReference = Annotated[str, Field(pattern=r"\.ya?ml$")]
PositiveInertia = Annotated[Inertia, Field(gt=0)]


# --- vehicle ------------------------------------------------------------------

class RigidBodySpec(Strict):
    """A vehicle as one rigid body of constant mass (body x = roll axis, nose)."""

    mass: PositiveMass = Field(description="total mass")
    inertia: tuple[PositiveInertia, PositiveInertia, PositiveInertia] = Field(
        description="principal moments of inertia about the centre of mass: roll (x), pitch (y), "
        "yaw (z); each at most the sum of the other two (as any body's are), and each the mass "
        f"times a radius of gyration of {MIN_SIZE:g} m .. {MAX_SIZE:g} m ({BOUNDS['size']})")
    length: Annotated[Length, SIZE] = Field(1.0, description="overall length (for plots)")
    diameter: Annotated[Length, SIZE] = Field(1.0, description="reference diameter")

    @model_validator(mode="after")
    def _physical_inertia(self) -> "RigidBodySpec":
        moments = self.inertia
        for k, moment in enumerate(moments):
            gyration = math.sqrt(moment / self.mass)
            if not MIN_SIZE <= gyration <= MAX_SIZE:
                raise field_error(("inertia", k), f"{moment:g} kg m2 on {self.mass:g} kg is a radius "
                                  f"of gyration of {gyration:g} m, not {MIN_SIZE:g} m .. {MAX_SIZE:g} m: "
                                  f"{BOUNDS['size']}", moment)
            others = sum(moments) - moment
            if moment > others * (1 + 1e-9):
                raise field_error(("inertia", k), f"{moment:g} kg m2 is more than the other two "
                                  f"moments together ({others:g} kg m2): no body's principal moments "
                                  "are (each is at most the sum of the other two)", moment)
        return self


class VehicleSpec(Strict):
    """A vehicle file: exactly one of ``rigid_body`` (constant mass) or ``stages``
    (listed bottom to top, see :mod:`rocketsim.scenario.vehicle`)."""

    name: str
    description: str = ""
    source: str = Field("", description="where the figures come from")
    rigid_body: Optional[RigidBodySpec] = None
    stages: Optional[list[StageSpec]] = Field(None, description="the stages, bottom to top")
    payload: Optional[PayloadSpec] = None
    fairing: Optional[FairingSpec] = None
    engines: Optional[object] = Field(None, description="not allowed here: engines belong to a stage")
    aero: Optional[AeroSpec] = Field(None, description="aerodynamics and ground contact (staged vehicles)")

    @model_validator(mode="after")
    def _one_kind(self) -> "VehicleSpec":
        if (self.rigid_body is None) == (self.stages is None):
            raise ValueError("give exactly one of 'rigid_body' or 'stages'")
        if self.stages is not None:
            check_staged(self.stages, self.engines, self.payload)
            check_aero(self.aero, self.stages, self.payload, self.fairing)
            check_axial_load(self)
        elif (self.engines is not None or self.payload is not None or self.fairing is not None
              or self.aero is not None):
            raise ValueError("'engines', 'payload', 'fairing' and 'aero' go with 'stages', not 'rigid_body'")
        return self


# --- mission ------------------------------------------------------------------

class TargetOrbit(Strict):
    """The orbit a mission aims for (programs read it as ``fc.target``).

    The altitude and inclination are Kozai mean elements unless ``elements:
    osculating`` (then the altitude is the osculating circular radius at the
    ascending node). ``inclination: sso`` asks for the sun-synchronous
    inclination of that orbit
    (:func:`rocketsim.bodies.sun_synchronous.sun_synchronous_inclination`: the
    mean node turning with the mean Sun); programs read the number.
    """

    altitude: Annotated[Length, Field(gt=0, le=MAX_START_DISTANCE)] = Field(
        description="circular altitude above the equatorial radius")
    elements: ElementsKind = Field("mean", description=ELEMENTS_DESCRIPTION)
    inclination: Union[Angle, Literal["sso"]] = Field(
        description="an angle, or 'sso': sun-synchronous at the altitude (J2 nodal rate = the mean Sun's)")

    @model_validator(mode="after")
    def _sun_synchronous(self) -> "TargetOrbit":
        if self.inclination == "sso":
            from rocketsim.bodies.sun_synchronous import (sun_synchronous_inclination,
                                                          sun_synchronous_osculating_inclination)
            if self.elements == "mean":
                i = sun_synchronous_inclination(self.altitude)
            else:
                i = sun_synchronous_osculating_inclination(EARTH_RADIUS_EQ + self.altitude, 0.0, 0.0,
                                                           0.0, 0.0)
            object.__setattr__(self, "inclination", i)
        return self


class TargetSpec(Strict):
    """What the mission aims for: an orbit, a landing pad (touchdown distances are
    measured to it; without one, to the launch site), or both."""

    orbit: Optional[TargetOrbit] = None
    pad: Optional[Union[TargetPad, str]] = Field(
        None, description="a pad, or the name of one of the site's pads")


class MissionSpec(Strict):
    """What the flight is: when it starts, from where, and for how long."""

    name: str = ""
    epoch: dt.datetime = Field(description="UTC instant of mission time 0 (ISO 8601)")
    dut1: Annotated[float, Field(ge=-0.9, le=0.9)] = Field(0.0, description="UT1 - UTC, s")
    start: StartSpec
    duration: Annotated[Duration, Field(gt=0)] = Field(description="mission time to fly, e.g. '3 h'")
    initial_rates: tuple[Rate, Rate, Rate] = Field(
        (0.0, 0.0, 0.0), description="body rates at the start, rad/s (roll, pitch, yaw)")
    target: TargetSpec = Field(TargetSpec(), description="what the mission aims for")
    gravity: Literal["earth", "n-body"] = Field(
        "earth", description="earth: Earth's point mass and J2 (flights near Earth); n-body: "
        "the central body's point mass and J2 plus the Sun, Earth, Moon and Mars, handing "
        "over from sphere of influence to sphere of influence (Moon and Mars missions)")

    @field_validator("duration")
    @classmethod
    def _duration_limit(cls, value: float) -> float:
        return check_duration(value)

    @field_validator("epoch")
    @classmethod
    def _utc(cls, value: dt.datetime) -> dt.datetime:
        value = value.replace(tzinfo=dt.timezone.utc) if value.tzinfo is None else value.astimezone(dt.timezone.utc)
        if value < UNIX_EPOCH:
            # telemetry stamps are MCAP's unsigned ns since 1970 (rocketsim.telemetry.writer)
            raise ValueError(f"the epoch {value.isoformat()} is before 1970-01-01: the telemetry's "
                             "timestamps (MCAP, ns since 1970) cannot hold it")
        return value


# --- scenario -----------------------------------------------------------------

class TelemetrySpec(Strict):
    rate: Annotated[Frequency, Field(ge=1e-6, le=50)] = Field(
        10.0, description="samples per second (1e-6 Hz, one every 11.6 days, .. 50 Hz)")
    coast_rate: Optional[Annotated[Frequency, Field(ge=1e-6, le=50)]] = Field(
        None, description="samples per second of a body coasting (no engine running, dynamic "
        "pressure under 1 Pa or none), at most the rate; default: the rate (rocketsim.sim.sample_watch)")

    @model_validator(mode="after")
    def _coast_rate(self) -> "TelemetrySpec":
        if self.coast_rate is not None and self.coast_rate > self.rate:
            raise ValueError(f"coast_rate {self.coast_rate:g} Hz is above the rate {self.rate:g} Hz")
        return self


class Scenario(Strict):
    """A scenario file: what flies, from where, on which day, with which program."""

    name: str
    description: str = ""
    vehicle: Union[VehicleSpec, FileReference] = Field(
        description="the vehicle, inline or as a path to a vehicle file (relative to this file)")
    site: Optional[Union[SiteSpec, FileReference]] = Field(
        None, description="the launch site, inline or as a path to a site file")
    mission: Union[MissionSpec, FileReference] = Field(
        description="the mission, inline or as a path to a mission file")
    payload: Optional[PayloadSpec] = Field(
        None, description="this mission's payload, in place of the vehicle file's")
    spacecraft: Optional[Union[VehicleSpec, FileReference]] = Field(
        None, description="a staged spacecraft (inline or a vehicle file) stacked on top of the "
        "vehicle: its stages above the vehicle's, its payload in place of the vehicle's; the "
        "program flies on with it once the vehicle's stages have separated")
    weather: Optional[Union[Weather, FileReference]] = Field(
        None, description="the day's weather, inline or as a path to a weather file; "
        "default: the US Standard Atmosphere 1976, calm")
    program: Optional[Path] = Field(None, description="flight-computer program (Python file with main(fc))")
    programs: dict[str, Path] = Field(
        default_factory=dict, description="programs of stages that separate: stage name -> "
        "program file; a stage without one coasts as a body nobody flies")
    step: Annotated[Duration, Field(gt=0)] = Field(STEP, description="integration step, at most 0.1 s")
    program_cpu_budget: Annotated[Duration, within(0.0, MAX_PROGRAM_CPU, "cpu", "s", above=True)] = Field(
        1.0, description="CPU time the program may use in one step before it is stopped")
    program_time_limit: Annotated[Duration, within(0.0, MAX_PROGRAM_WAIT, "wait", "s", above=True)] = Field(
        10.0, description="wall time one wake-up of the program may take before it is stopped "
        "(blocked or busy)")
    telemetry: TelemetrySpec = TelemetrySpec()
    seed: int = Field(0, ge=0, le=MAX_SEED, description="seed of every random stream of the run "
                      "(0 .. 2^64 - 1)")
    sensors: Literal["truth", "realistic", "hard"] = Field(
        "truth", description="what programs read: the true state, or a navigation estimate "
        "with realistic (or three times larger, 'hard') sensor errors")
    stages: Optional[list[str]] = Field(
        None, description="fly only these stages of the vehicle, its lowest, bottom first "
        "(a first-stage hop: [booster]); no payload or fairing")
    propellant: dict[str, PositiveMass] = Field(
        default_factory=dict, description="tank loads in place of the vehicle file's: "
        "'stage/tank' -> mass (a hop flies light enough to hover)")
    follow: Optional[list[str]] = Field(
        None, description="the bodies the flight is about, by name: a stage's (it flies as a body of "
        "that name once separated), the vehicle's (the stack, and what is left of it), fairing_1, "
        "fairing_2 or payload; once each of them flies, the others are no longer flown: each ends "
        "where it is with the event 'not followed' (a booster's landing campaign: [booster]); "
        "default: every body, to the end")

    @model_validator(mode="before")
    @classmethod
    def _bounded(cls, data):
        """A scenario handed over in memory is held to the limits a file is read within
        (:func:`rocketsim.limits.check_data`): nesting, number of values, text lengths."""
        return check_data(data)

    @model_validator(mode="before")
    @classmethod
    def _classic_range(cls, data):
        """``site: classic``: the procedural range generated from the scenario's seed."""
        if isinstance(data, dict) and data.get("site") == CLASSIC:
            seed = data.get("seed", 0)
            if isinstance(seed, int) and not isinstance(seed, bool):
                data = {**data, "site": classic_site(seed)}
        return data

    @field_validator("step")
    @classmethod
    def _step_limit(cls, value: float) -> float:
        return check_step(value)

    @model_validator(mode="after")
    def _site_when_needed(self) -> "Scenario":
        for name in ("vehicle", "site", "mission", "weather", "spacecraft"):
            if isinstance(getattr(self, name), str):
                raise ValueError(f"'{name}' names a file: load scenarios with rocketsim.scenario.load")
        if self.spacecraft is not None:
            if self.vehicle.stages is None:
                raise ValueError("'spacecraft' goes with a staged vehicle")
            object.__setattr__(self, "vehicle", stack_spacecraft(self.vehicle, self.spacecraft))
        if self.payload is not None:
            if self.vehicle.stages is None:
                raise ValueError("'payload' goes with a staged vehicle")
            object.__setattr__(self, "vehicle", self.vehicle.model_copy(update={"payload": self.payload}))
        if (self.stages is not None or self.propellant) and self.vehicle.stages is None:
            raise ValueError("'stages' and 'propellant' go with a staged vehicle")
        if self.stages is not None:
            object.__setattr__(self, "vehicle", keep_stages(self.vehicle, self.stages))
        if self.propellant:
            object.__setattr__(self, "vehicle", reload_tanks(self.vehicle, self.propellant))
        if self.mission.start.site is not None and self.site is None:
            raise ValueError("mission starts on a site: give 'site'")
        self._stands_on_the_ground()
        if self.mission.start.site is not None and self.mission.start.site.rail is not None \
                and self.vehicle.stages is None:
            raise ValueError("a launch rail (mission.start.site.rail) goes with a staged vehicle, "
                             "not a rigid_body")
        pad = self.mission.target.pad
        if isinstance(pad, str):
            found = [p for p in (self.site.pads if self.site else []) if p.name == pad]
            if not found:
                names = ", ".join(p.name for p in self.site.pads) if self.site else ""
                raise ValueError(f"target pad {pad!r} is not one of the site's pads"
                                 + (f" ({names})" if names else " (the site lists none)"))
            target = self.mission.target.model_copy(update={"pad": found[0]})
            object.__setattr__(self, "mission", self.mission.model_copy(update={"target": target}))
        if self.site is not None and self.site.model == CLASSIC and \
                getattr(self.weather, "kind", "standard") not in ("standard", CLASSIC):
            raise ValueError("the classic range flies the original model's air: weather kind "
                             "'standard' or 'classic' (the standard shifted by the day's "
                             f"surface temperature), not {self.weather.kind!r}")
        return self


    def _stands_on_the_ground(self) -> None:
        """A vehicle with ground contact starting at rest on the pad stands on the ground:
        a pad above an explicit ``ground_height`` would start it in the air, to fall at
        T+0 (a rail holds it; a pad on a tower is not modelled)."""
        start, site, aero = self.mission.start.site, self.site, self.vehicle.aero
        if start is None or start.rail is not None or any(start.velocity) or aero is None \
                or not aero.aerodynamics or site.height <= site.ground:
            return
        raise field_error(("site", "ground_height"), f"the vehicle starts at rest on the pad, "
                          f"{site.height - site.ground:g} m above the ground (ground_height "
                          f"{site.ground:g} m, the pad's height {site.height:g} m): it would fall "
                          "at T+0. Leave ground_height out (the ground is then the pad's height) "
                          "or start on a rail (mission.start.site.rail)", site.ground_height)


def check_step(value: float) -> float:
    """The headless step limit: any step from 0.1 ms up to 0.1 s, nothing else."""
    if value > MAX_HEADLESS_STEP:
        raise ValueError(f"step {value:g} s is larger than the {MAX_HEADLESS_STEP:g} s a headless "
                         "run accepts (the flight model flies 0.02 s)")
    if not value >= MIN_STEP:     # nan too
        raise ValueError(f"step {value:g} s is not at least the {MIN_STEP:g} s a run accepts "
                         "(the flight model flies 0.02 s)")
    return value


def check_duration(value: float) -> float:
    """A mission time to fly: at least 0 s (0: the initial state alone), at most a century."""
    if not value >= 0 or not value <= MAX_DURATION:
        raise ValueError(f"a duration of {value:g} s is not at least 0 s and at most "
                         f"{MAX_DURATION:g} s (a century)")
    return value


def time_argument(value, name: str, check) -> float:
    """``value`` (s, or a time as the files write it, ``"10 s"``), an argument of a call, in
    s and passed by ``check`` (:func:`check_duration`, :func:`check_step`); otherwise an
    :class:`~rocketsim.errors.ArgumentError` naming the argument ``name``."""
    try:
        return check(parse_quantity(value, "time"))
    except ValueError as error:
        raise ArgumentError(str(error), name) from None
