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
propellant is unusable (:data:`rocketsim.constants.UNUSABLE_PROPELLANT`). The tanks, engines
and solid motors are :mod:`rocketsim.scenario.propulsion_spec`'s models.
"""

from __future__ import annotations

from typing import Annotated, Literal, Optional, Union

from pydantic import Field, model_validator

from rocketsim.scenario.bounds import (BOUNDS, DEPLOY_DELAY, DEPLOY_HEIGHT, DRAG_AREA, INFLATION,
                                       MAX_SEPARATION_SPEED, MIN_DESCENT_SPEED, OPENING_LAG, descent_speed,
                                       within)
from rocketsim.scenario.propulsion_spec import EngineSpec, MotorSpec, TankSpec
from rocketsim.scenario.strict import (REQUIRED, Count, NonNegativeLength, NonNegativeMass, PositiveLength,
                                       PositiveMass, Strict, field_error)
from rocketsim.scenario.units import Area, Duration, Length, Speed


class AfterEvent(Strict):
    """An event of the body (by its name in the flight's events) and a delay after it."""

    event: str = Field(description="name of an event of this body, e.g. burnout, apogee, off_rail")
    delay: Annotated[Duration, DEPLOY_DELAY] = Field(0.0, description="after the event")


class HeightTrigger(Strict):
    height: Annotated[Length, DEPLOY_HEIGHT] = Field(
        description="deploy on the way down at this height above the ground (the ground the "
        "body lands on: the ellipsoid, or the site's ground_height)")


class AfterTrigger(Strict):
    after: AfterEvent


class ParachuteSpec(Strict):
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


class PointMassSpec(Strict):
    """A point mass on the axis (avionics, legs, fins, interstage...), or a ring of them."""

    name: str
    mass: PositiveMass
    position: NonNegativeLength = Field(description="height above the stage base")
    count: Count = 1
    radius: NonNegativeLength = Field(0.0, description="radius of the ring (legs, fins)")


class StageSpec(Strict):
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


class PayloadSpec(Strict):
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


class FairingSpec(Strict):
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
