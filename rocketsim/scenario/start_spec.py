"""Where a flight starts, as pydantic v2 models: a launch site on the WGS84 ellipsoid with
its landing pads, an orbit's elements about a central body, a state vector, a launch rail,
and the ``start:`` of a scenario that picks one of them (:class:`StartSpec`)."""

from __future__ import annotations

import math
from typing import Annotated, Literal, Optional, Union

from pydantic import Field, field_validator, model_validator

from rocketsim.constants import (EARTH_J2, EARTH_MU, EARTH_RADIUS_EQ, EARTH_RADIUS_POLAR, MARS_FLATTENING,
                                 MARS_J2, MARS_MU, MARS_RADIUS_EQ, MAX_START_DISTANCE, MAX_START_SPEED,
                                 MOON_J2, MOON_MU, MOON_RADIUS)
from rocketsim.scenario.bounds import EXTENT, MAX_SITE_HEIGHT, MIN_SITE_HEIGHT, SIZE, within
from rocketsim.scenario.strict import Strict
from rocketsim.scenario.units import Angle, Length, Speed

# a height of a site above the WGS84 ellipsoid
SiteHeight = Annotated[Length, within(MIN_SITE_HEIGHT, MAX_SITE_HEIGHT, "site height", "m")]
# a latitude, -90 deg .. 90 deg
Latitude = Annotated[Angle, within(-math.pi / 2, math.pi / 2, "latitude", "rad")]


class TargetPad(Strict):
    """A landing pad on the WGS84 ellipsoid (the ground; no terrain)."""

    name: str = "pad"
    latitude: Latitude
    longitude: Angle


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
    pads: list[TargetPad] = Field(
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


# how a mission file's orbital elements are read
ElementsKind = Literal["mean", "osculating"]


ELEMENTS_DESCRIPTION = (
    "mean: Kozai's first-order J2 mean elements (the orbit with its twice-per-revolution J2 "
    "ripple removed, as mission designers state orbits; rocketsim.frames.mean_elements); "
    "osculating: the two-body elements of the instantaneous state")


# a body rate at the start, rad/s: 10 000 rad/s (1 600 turns a second) is beyond any vehicle
Rate = Annotated[float, Field(ge=-1e4, le=1e4)]


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
