"""Staging in flight: a body splits into the part that flies on and new bodies.

The split itself (mass properties, centre of mass and momentum conserved) is
:mod:`rocketsim.vehicle.staging`'s; here each new part becomes a body of the
world with its own channels, its central body and field, its sensors and,
for a separated stage the scenario names in ``programs:``, its own program.
Each function takes the :class:`~rocketsim.sim.world.World` first.

A scenario that names the bodies to follow (``follow``) flies the others no
further once each followed body flies (:func:`leave_unfollowed`, after every split):
they end where they are, with the event ``not followed``. The followed bodies'
flights are the same, bit for bit: no body acts on another once split.
"""

from __future__ import annotations

import numpy as np

from rocketsim.constants import EARTH_J2, EARTH_MU, EARTH_RADIUS_EQ, EARTH_RADIUS_POLAR
from rocketsim.dynamics.soi import central_params
from rocketsim.dynamics.third_bodies import field_of, with_field
from rocketsim.flight.sensors import Sensors
from rocketsim.layout import make_params, make_state
from rocketsim.scenario.models import VehicleSpec
from rocketsim.sim.body import Body, Part, Vehicle, channel_name
from rocketsim.sim.flight_events import FlightEvents
from rocketsim.sim.handover import fly_in_air_of
from rocketsim.sim.vehicle_checks import VehicleChecks
from rocketsim.vehicle import staging as split
from rocketsim.vehicle.build import VehicleModel

def jettison_fairing(world, body: Vehicle) -> tuple[Part, Part]:
    """Drop ``body``'s payload fairing: it opens into two rigid bodies of their own,
    ``fairing_1`` and ``fairing_2`` (half shells pushed apart along the body's
    ``+y`` and ``-y`` axes, each with its own channels and tumbling drag); centre of
    mass and momentum are conserved (:func:`rocketsim.vehicle.staging.jettison_fairing`).
    Returns the two new bodies."""
    stack = body.stack
    if body.vehicle is None or stack is None or not body.vehicle.has_fairing:
        raise ValueError(f"{body.name} has no fairing to jettison")
    kept, halves = split.jettison_fairing(stack, body.vehicle, body.y, 0, air=world.atmosphere)
    new = _split_rigid(world, body, kept, halves, ("fairing_1", "fairing_2"),
                       stack.model_copy(update={"fairing": None}))
    world.event(body, "fairing jettison", {"fairing_mass_kg": stack.fairing.mass,
                                           "fairing_bodies": [half.name for half in new]})
    leave_unfollowed(world)
    return new


def deploy_payload(world, body: Vehicle) -> Part:
    """Release ``body``'s payload (after the fairing has gone): it becomes a rigid
    body of its own (a solid cylinder, with its tumbling drag) named ``payload``,
    with its own channels; centre of mass and momentum are conserved, no
    separation impulse (:func:`rocketsim.vehicle.staging.deploy_payload`).
    Returns the new body."""
    stack = body.stack
    if body.vehicle is None or stack is None or stack.payload is None:
        raise ValueError(f"{body.name} has no payload to deploy")
    if body.vehicle.has_fairing:
        raise ValueError(f"{body.name} still carries its fairing: jettison it before deploying the payload")
    kept, part = split.deploy_payload(stack, body.vehicle, body.y, 0, air=world.atmosphere)
    new, = _split_rigid(world, body, kept, [part], ("payload",), stack.model_copy(update={"payload": None}))
    figures = {"payload_mass_kg": new.mass, "upper_mass_kg": body.mass}
    world.event(body, "payload deploy", {**figures, "payload_body": new.name})
    world.event(new, "payload deploy", {**figures, "from_body": body.name})
    leave_unfollowed(world)
    return new


def separate(world, body: Vehicle) -> Vehicle:
    """Separate the lowest stage of ``body``: ``body`` flies on as the upper stack,
    the stage becomes a body of its own (its own channels, and its own program
    when the scenario's ``programs:`` names one for it). Returns the new body.

    Centre of mass and momentum of the two parts add up to the stack's
    (:func:`rocketsim.vehicle.staging.separate`); no separation impulse.
    """
    stack = body.stack
    if body.vehicle is None or stack is None or len(stack.stages) < 2:
        raise ValueError(f"{body.name} has no stage left to separate")
    (lower, y_lower), (upper, y_upper) = split.separate(stack, body.vehicle, body.y, 1,
                                                        air=world.atmosphere)
    stage = stack.stages[0].name
    body.vehicle, body.y, body._view = upper, y_upper, None
    body.stack = upper_stack(stack)
    new = add_body(world, stage, y_lower, body.p.copy(), body, vehicle=lower)
    if body.checks is not None:         # the stage is a vehicle with aero of its own
        new.checks = VehicleChecks(stack.aero.heat_shield, pad_ecef=body.checks.pad, limits=stack.aero.limits)
    if body.watch is not None:
        new.watch = FlightEvents(world, new, on_ground=False, stage_names=body.watch.stage_names)
        new.watch.inherit(body.watch)
    figures = {"stage": stage, "stage_mass_kg": new.mass, "upper_mass_kg": body.mass}
    world.event(body, "separation", {**figures, "separated_body": new.name})
    world.event(new, "separation", {**figures, "from_body": body.name})
    if stage in world.stage_programs:
        world.attach_program(new, *world.stage_programs[stage])
        new.fc.warm_up()
    leave_unfollowed(world)
    return new


def leave_unfollowed(world) -> None:
    """Once every body in ``world.follow`` flies, end each other body still flying: the
    event ``not followed`` and its last sample, where it is."""
    follow = world.follow
    if follow is None or not follow <= {b.name for b in world.bodies}:
        return
    for body in world.bodies:
        if body.flying and body.name not in follow:
            world.end_flight(body, "not followed", {})


def _split_rigid(world, body: Vehicle, kept, parts, names, stack: VehicleSpec) -> tuple[Part, ...]:
    """Fly ``body`` on as ``kept`` (model and state, what is left of ``stack``) and
    add each of ``parts`` (a rigid body's mass, inertia, state and drag:
    :func:`rocketsim.vehicle.staging._release_top`) as a new body named as ``names``."""
    without, y_without = kept
    body.vehicle, body.y, body._view, body.stack = without, y_without, None, stack
    new = []
    for name, part in zip(names, parts):
        added = add_body(world, name, make_state(part["position"], part["velocity"], part["attitude"],
                                                 part["rates"]),
                         make_params(part["mass"], part["inertia"], EARTH_MU, EARTH_RADIUS_EQ,
                                     EARTH_J2, EARTH_RADIUS_POLAR), body,
                         drag=(part["area"] / part["mass"], part["length"]))
        new.append(added)
    return tuple(new)


def add_body(world, name: str, y: np.ndarray, p: np.ndarray, parent: Body,
             vehicle: VehicleModel | None = None, drag: tuple | None = None) -> Body:
    """A new body split from ``parent`` now: a staged :class:`Vehicle` (``vehicle``) or
    a tumbling :class:`Part` (``drag``), with a unique channel name, the parent's
    central body, field, air and sensors level, its telemetry channels and first sample."""
    names = {b.name for b in world.bodies}
    name = channel_name(name)
    while name in names:
        name += "_"
    fp = field_of(parent.p)
    if fp is not None:              # the parent's central body and field
        p = with_field(central_params(p, parent.central), fp)
    common = dict(name=name, y=y, p=p, t=parent.t, mu=parent.mu, atmosphere=parent.atmosphere,
                  central=parent.central, sensors=Sensors(world.seed, name, world.sensor_level, world.h))
    new = Vehicle(vehicle=vehicle, **common) if vehicle is not None else Part(drag=drag, **common)
    if vehicle is not None and parent.central != "earth":
        fly_in_air_of(world, new)
    world.bodies.append(new)
    if world.sample_watch is not None:      # it flew with its parent so far
        world.sample_watch.inherit(new.name, parent.name)
    if world.telemetry is not None:
        world.telemetry.add_body(new.name)
        world.record(new)
    return new


def upper_stack(stack: VehicleSpec) -> VehicleSpec:
    """The vehicle file of what is left when the lowest stage of ``stack`` separates:
    its stages from the second up, with the aerodynamic parts (fins, grid fins,
    legs, thrusters) of the stages that remain."""
    stages = stack.stages[1:]
    aero = stack.aero
    if aero is not None:
        names = {s.name for s in stages}
        aero = aero.model_copy(update={
            part: [item for item in getattr(aero, part) if item.stage in names]
            for part in ("fins", "grid_fins", "legs", "rcs")})
    return stack.model_copy(update={"stages": stages, "aero": aero})
