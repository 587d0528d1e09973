"""The shapes of scenario files, as pydantic v2 models.

A scenario names a vehicle, a launch site, the day's weather, a mission and
a flight-computer program. Each of ``vehicle``, ``site`` and ``mission`` is
either written inline or given as a path to its own YAML file, resolved
relative to the scenario file. Quantities are SI numbers or strings with a
unit (``"400 km"``, ``"51.6 deg"``; see :mod:`rocketsim.scenario.units`);
angles always carry a unit.

Every model forbids unknown fields, so a misspelt field is an error (with a
"did you mean"), never silently ignored. New capabilities add optional fields
(``stages:`` on a vehicle, say) so existing files keep validating.
"""

from __future__ import annotations

import datetime as dt
import math
from pathlib import Path
from typing import Annotated, Literal, Optional, Union

from pydantic import BaseModel, Field, field_validator, model_validator

from rocketsim.constants import (EARTH_J2, EARTH_MU, EARTH_RADIUS_EQ, EARTH_RADIUS_POLAR, MARS_FLATTENING,
                                 MARS_J2, MARS_MU, MARS_RADIUS_EQ, MAX_DURATION, MAX_HEADLESS_STEP,
                                 MAX_START_DISTANCE, MAX_START_SPEED, MIN_STEP, MOON_J2, MOON_MU,
                                 MOON_RADIUS, STEP)
from rocketsim.limits import MAX_SEED, check_data
from rocketsim.scenario.bounds import (BODY_MASS, BOUNDS, EXTENT, MAX_PROGRAM_CPU, MAX_PROGRAM_WAIT,
                                       MAX_SITE_HEIGHT, MAX_SIZE, MIN_SITE_HEIGHT, MIN_SIZE, SIZE, within)
from rocketsim.scenario.classic_range import CLASSIC, classic_site
from rocketsim.scenario.weather import Weather
from rocketsim.scenario.units import STRICT, Angle, Duration, Frequency, Inertia, Length, Mass, Speed
from rocketsim.scenario.aero_spec import AeroSpec, check_aero, check_axial_load
from rocketsim.scenario.vehicle import FairingSpec, PayloadSpec, StageSpec, check_staged, field_error
from rocketsim.scenario.stage_selection import keep_stages, reload_tanks, stack_spacecraft

UNIX_EPOCH = dt.datetime(1970, 1, 1, tzinfo=dt.timezone.utc)

PositiveMass = Annotated[Mass, BODY_MASS]
# a path to a YAML file of its own, resolved by the loader relative to the scenario
FileReference = Annotated[str, Field(pattern=r"\.ya?ml$")]
PositiveInertia = Annotated[Inertia, Field(gt=0)]
# a height of a site above the WGS84 ellipsoid
SiteHeight = Annotated[Length, within(MIN_SITE_HEIGHT, MAX_SITE_HEIGHT, "site height", "m")]
# a latitude, -90 deg .. 90 deg
Latitude = Annotated[Angle, within(-math.pi / 2, math.pi / 2, "latitude", "rad")]


class Strict(BaseModel):
    """Base of every scenario model: unknown fields are errors."""

    model_config = STRICT


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


# --- site ---------------------------------------------------------------------

class SiteSpec(Strict):
    """A launch site on the WGS84 ellipsoid."""

    name: str
    latitude: Angle = Field(description="geodetic latitude, north positive, e.g. '28.5619 deg' "
                            "(Cape Canaveral SLC-40)")
    longitude: Angle = Field(description="longitude, east positive, e.g. '-80.5774 deg' "
                             "(Cape Canaveral SLC-40)")
    height: SiteHeight = Field(
        0.0, description="height of the pad above the WGS84 ellipsoid, e.g. '1380 m' (the height "
        "above sea level plus the geoid's undulation there)")
    pad_azimuth: Angle = Field(1.5707963267948966, description="launch azimuth from north, e.g. "
                               "'90 deg'; default due east")
    ground_height: Optional[SiteHeight] = Field(
        None, description="height above the WGS84 ellipsoid of a flat ground around the site that "
        "a vehicle launched from here stands and lands on (its contact points, touchdown, impact, "
        "parachute heights), e.g. '0 m' for the ellipsoid; default the pad's height (a vehicle "
        "standing on the pad stands on the ground)")
    source: str = ""
    model: Literal["realistic", "classic"] = Field(
        "realistic", description="the physics model flown from this site: 'classic' is the classic "
        "range's original model (thrust, mass and the density above 86 km held for the step; "
        "standard-gravity hydrostatics; weather standard or classic)")
    pads: list["TargetPad"] = Field(
        default_factory=list, description="landing zones and drone ships a mission can name "
        "as its target pad (target: {pad: <name>})")

    @field_validator("latitude")
    @classmethod
    def _latitude_range(cls, value: float) -> float:
        if not -1.5707963267948966 <= value <= 1.5707963267948966:
            raise ValueError("latitude must be within -90 deg .. 90 deg")
        return value

    @property
    def ground(self) -> float:
        """m, height above the WGS84 ellipsoid of the flat ground around the site:
        ``ground_height``, else the pad's ``height``."""
        return self.height if self.ground_height is None else self.ground_height

    @model_validator(mode="after")
    def _pad_on_or_above_the_ground(self) -> "SiteSpec":
        if self.height < self.ground:
            raise ValueError(f"the pad's height {self.height:g} m is below the ground "
                             f"(ground_height {self.ground:g} m): a vehicle would start inside "
                             "the ground")
        return self


# --- mission ------------------------------------------------------------------

# how a mission file's orbital elements are read
ElementsKind = Literal["mean", "osculating"]
ELEMENTS_DESCRIPTION = (
    "mean: Kozai's first-order J2 mean elements (the orbit with its twice-per-revolution J2 "
    "ripple removed, as mission designers state orbits; rocketsim.frames.mean_elements); "
    "osculating: the two-body elements of the instantaneous state")


# a body rate at the start, rad/s: 10 000 rad/s (1 600 turns a second) is beyond any vehicle
_Rate = Annotated[float, Field(ge=-1e4, le=1e4)]
# gravitational parameter (m^3/s^2), equatorial and polar radii (m) and J2 of the bodies an
# orbit can start about (the J2 reference radius is the equatorial one)
_BODIES = {"earth": (EARTH_MU, EARTH_RADIUS_EQ, EARTH_RADIUS_POLAR, EARTH_J2),
           "moon": (MOON_MU, MOON_RADIUS, MOON_RADIUS, MOON_J2),
           "mars": (MARS_MU, MARS_RADIUS_EQ, MARS_RADIUS_EQ * (1.0 - MARS_FLATTENING), MARS_J2)}


def inside_body(r, body: str) -> bool:
    """Whether the point ``r`` (m, in the body's frame: ``z`` along its pole) lies inside
    ``body``'s ellipsoid (or on it)."""
    _, equatorial, polar, _ = _BODIES[body]
    return (r[0] ** 2 + r[1] ** 2) / equatorial ** 2 + r[2] ** 2 / polar ** 2 <= 1.0
# a start's lengths and speeds (m, m/s), within the constants' bounds either way
_StartLength = Annotated[Length, Field(ge=-MAX_START_DISTANCE, le=MAX_START_DISTANCE)]
_StartSpeed = Annotated[Speed, Field(ge=-MAX_START_SPEED, le=MAX_START_SPEED)]


class OrbitStart(Strict):
    """Start in orbit about Earth (or ``body``) from classical elements at the mission epoch.

    Give ``altitude`` (circular, above the equatorial radius) or
    ``semi_major_axis`` (with ``eccentricity``). The elements are Kozai mean
    elements unless ``elements: osculating`` (the starting state is then the
    two-body state of the numbers as given); ``true_anomaly`` is that of the
    mean ellipse for mean elements. ``inclination: sso`` (about Earth) asks for
    the sun-synchronous inclination of the orbit
    (:mod:`rocketsim.bodies.sun_synchronous`). About the Moon or Mars the
    mission flies ``gravity: n-body`` in that body's frame (its IAU pole as
    ``z``, ``x`` the node of its equator on the J2000 equator; ``raan`` from
    that node) and mean elements are those of that body's J2.
    """

    body: Literal["earth", "moon", "mars"] = Field("earth", description="the body orbited")
    elements: ElementsKind = Field("mean", description=ELEMENTS_DESCRIPTION)

    altitude: Optional[Annotated[Length, Field(le=MAX_START_DISTANCE)]] = Field(
        None, description="circular altitude above the equatorial radius, e.g. '415 km'")
    semi_major_axis: Optional[Annotated[Length, Field(gt=0, le=MAX_START_DISTANCE)]] = None
    eccentricity: Annotated[float, Field(ge=0, lt=1)] = 0.0
    inclination: Union[Angle, Literal["sso"]] = Field(
        description="an angle, or 'sso' (about Earth): sun-synchronous, the mean node turning "
        "with the mean Sun")
    raan: Angle = 0.0
    arg_periapsis: Angle = 0.0
    true_anomaly: Angle = 0.0

    @model_validator(mode="after")
    def _one_size(self) -> "OrbitStart":
        if (self.altitude is None) == (self.semi_major_axis is None):
            raise ValueError("give exactly one of 'altitude' or 'semi_major_axis'")
        if self.altitude is not None and self.eccentricity != 0.0:
            raise ValueError("'altitude' means a circular orbit: use 'semi_major_axis' with 'eccentricity'")
        mu, equatorial, polar, j2 = _BODIES[self.body]
        a = self.semi_major_axis if self.altitude is None else equatorial + self.altitude
        e, nu = self.eccentricity, self.true_anomaly
        start = a * (1.0 - e * e) / (1.0 + e * math.cos(nu))
        if not start >= polar:
            raise ValueError(f"the orbit starts {start:g} m from the centre of {self.body}, below its "
                             f"surface (polar radius {polar:g} m): raise the altitude or semi-major axis")
        if self.inclination == "sso":
            from rocketsim.bodies.sun_synchronous import (sun_synchronous_inclination,
                                                          sun_synchronous_osculating_inclination)
            if self.body != "earth":
                raise ValueError("'inclination: sso' is sun-synchronous about Earth only")
            a = self.semi_major_axis if self.altitude is None else EARTH_RADIUS_EQ + self.altitude
            if self.elements == "mean":
                i = sun_synchronous_inclination(a - EARTH_RADIUS_EQ, self.eccentricity)
            else:
                i = sun_synchronous_osculating_inclination(a, self.eccentricity, self.raan,
                                                           self.arg_periapsis, self.true_anomaly)
            object.__setattr__(self, "inclination", i)
        self._starts_above_the_surface(a, mu, equatorial, j2)
        return self

    def _starts_above_the_surface(self, a: float, mu: float, radius: float, j2: float) -> None:
        """The point the flight starts from (for mean elements, that of the osculating
        orbit, J2's short-period terms added: tens of km lower at some anomalies) lies
        outside the body's ellipsoid; a start inside it would begin the flight with its
        contact springs compressed by kilometres."""
        from rocketsim.frames.elements import Elements, elements_to_state   # numpy: only for
        from rocketsim.frames.mean_elements import mean_to_osculating        # an orbit start

        elements = Elements(a, self.eccentricity, self.inclination, self.raan, self.arg_periapsis,
                            self.true_anomaly, mu)
        try:
            if self.elements == "mean":
                elements = mean_to_osculating(elements, radius, j2)
            r, _ = elements_to_state(elements.a, elements.e, elements.i, elements.raan,
                                     elements.argp, elements.nu, mu)
        except (ArithmeticError, ValueError):
            r = None
        if r is None or not all(math.isfinite(c) for c in r):
            raise ValueError("these mean elements have no osculating orbit (J2's short-period "
                             f"terms do not converge this close to {self.body} or this eccentric): "
                             "raise the altitude, or give 'elements: osculating'")
        if inside_body(r, self.body):
            distance = math.sqrt(sum(c * c for c in r))
            raise ValueError(f"the orbit starts {distance:g} m from the centre of {self.body}, "
                             "below its surface there" + (" (the starting point of the osculating "
                                                          "orbit of these mean elements)"
                                                          if self.elements == "mean" else "")
                             + ": raise the altitude or semi-major axis")


class StateStart(Strict):
    """Start from a state vector in the inertial frame (ECI at the epoch)."""

    position: tuple[_StartLength, _StartLength, _StartLength]
    velocity: tuple[_StartSpeed, _StartSpeed, _StartSpeed]

    @field_validator("position")
    @classmethod
    def _above_the_surface(cls, value):
        if inside_body(value, "earth"):
            raise ValueError(f"the state starts inside the Earth ({math.sqrt(sum(c * c for c in value)):g} m "
                             "from its centre, on or below the WGS84 ellipsoid there)")
        return value


class RailSpec(Strict):
    """A launch rail on the pad (docs/physics.md#launch-rail): the vehicle stands on its
    base at the rail's foot and slides along it, without turning, until its last (aft)
    rail button leaves the rail's top: after a travel of ``length - last_button``.

    On the mission's start, not the site: like RocketPy's ``Flight(rail_length,
    inclination, heading)``, the rail's angle is set for each flight (tilted
    away from the crowd, into the day's wind), while the site file stays the place.
    """

    length: Annotated[Length, SIZE] = Field(description="length of the rail, e.g. '5.2 m'")
    inclination: Optional[Angle] = Field(
        None, description="elevation of the rail above the horizon; default the start's elevation")
    heading: Optional[Angle] = Field(
        None, description="azimuth the rail leans towards, from north; default the site's pad azimuth")
    last_button: Annotated[Length, EXTENT] = Field(
        0.0, description="height of the vehicle's aft rail button above its base (the last to "
        "leave), e.g. '0.25 m'")

    @model_validator(mode="after")
    def _travel(self) -> "RailSpec":
        if self.last_button >= self.length:
            raise ValueError("the last rail button must sit lower than the rail is long "
                             f"({self.last_button:g} m on a {self.length:g} m rail)")
        if self.inclination is not None and not 0.0 < self.inclination <= 1.5707963267948966:
            raise ValueError("a rail's inclination is above 0 deg and at most 90 deg")
        return self


class SiteStart(Strict):
    """Start on the launch site, optionally moving relative to the ground, or off a rail.

    ``velocity`` is east, north, up relative to the rotating Earth (a
    free-flight release); the body's nose points along ``elevation`` above the
    horizon towards the site's pad azimuth. With ``rail`` the vehicle starts at
    rest on the rail, its nose along it (the rail's inclination and heading).
    """

    velocity: tuple[_StartSpeed, _StartSpeed, _StartSpeed] = (0.0, 0.0, 0.0)
    elevation: Annotated[Angle, within(-math.pi / 2, math.pi / 2, "elevation", "rad")] = Field(
        1.5707963267948966, description="nose elevation, default vertical")
    rail: Optional[RailSpec] = Field(None, description="a launch rail (a staged vehicle)")

    @model_validator(mode="after")
    def _on_rail(self) -> "SiteStart":
        if self.rail is not None:
            if any(self.velocity):
                raise ValueError("a vehicle on a rail starts at rest: no 'velocity'")
            if self.rail.inclination is not None and "elevation" in self.model_fields_set \
                    and self.elevation != self.rail.inclination:
                raise ValueError("give the rail's 'inclination' or the start's 'elevation', not both")
        return self

    @property
    def nose_elevation(self) -> float:
        """rad: the rail's inclination, else the start's elevation."""
        if self.rail is not None and self.rail.inclination is not None:
            return self.rail.inclination
        return self.elevation


class StartSpec(Strict):
    """Where the flight starts: exactly one of ``site``, ``orbit``, ``state``."""

    site: Optional[SiteStart] = None
    orbit: Optional[OrbitStart] = None
    state: Optional[StateStart] = None

    @model_validator(mode="after")
    def _exactly_one(self) -> "StartSpec":
        given = [name for name in ("site", "orbit", "state") if getattr(self, name) is not None]
        if len(given) != 1:
            raise ValueError("give exactly one of 'site', 'orbit' or 'state'"
                             + (f" (got {', '.join(given)})" if given else ""))
        return self


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


class TargetPad(Strict):
    """A landing pad on the WGS84 ellipsoid (the ground; no terrain)."""

    name: str = "pad"
    latitude: Latitude
    longitude: Angle


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
    initial_rates: tuple[_Rate, _Rate, _Rate] = Field(
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
