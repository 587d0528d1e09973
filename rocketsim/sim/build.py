"""A world built from a loaded scenario: the first body, its air, sensors and program.

The site (or the mission's starting orbit or state) gives the initial state
(:mod:`rocketsim.sim.start`); a ``rigid_body`` vehicle becomes a :class:`Body`
of fixed mass, a staged one a :class:`Vehicle` standing on its feet on the pad;
a mission with ``gravity: n-body`` or starting about another body carries the
n-body field; the weather becomes the day's air table, built on first use.
"""

from __future__ import annotations

import math

import numpy as np

from rocketsim.constants import EARTH_J2, EARTH_MU, EARTH_RADIUS_EQ, EARTH_RADIUS_POLAR
from rocketsim.dynamics.central import nbody_field
from rocketsim.dynamics.soi import central_params
from rocketsim.dynamics.third_bodies import with_field
from rocketsim.flight.program import load_program, plain_program
from rocketsim.flight.sensors import Sensors
from rocketsim.frames.earth_fixed import ecef_to_eci_velocity
from rocketsim.frames.geodetic import enu_basis, geodetic_to_ecef
from rocketsim.layout import P_MU, R, V, W, make_params, make_state
from rocketsim.scenario.load import LoadedScenario
from rocketsim.scenario.models import check_duration, check_step, time_argument
from rocketsim.sim.body import Body, Vehicle, channel_name
from rocketsim.sim.coast_runs import compile_coasts_beside
from rocketsim.sim.flight_events import FlightEvents
from rocketsim.sim.handover import fly_in_air_of
from rocketsim.sim.start import on_rail, standing_on_ground, start_state
from rocketsim.sim.vehicle_checks import VehicleChecks
from rocketsim.sim.window import compile_runs_beside
from rocketsim.sim.world import World
from rocketsim.timescales import Epoch
from rocketsim.vehicle.aero import A_GROUND
from rocketsim.vehicle.build import build


def build_world(loaded: LoadedScenario, step: float | None = None,
                duration: float | None = None) -> World:
    """The world of ``loaded``, ready to :meth:`~rocketsim.sim.world.World.run`;
    ``step`` and ``duration`` (s) override the scenario's."""
    scenario = loaded.scenario
    h = scenario.step if step is None else time_argument(step, "step", check_step)
    mission = scenario.mission
    epoch = Epoch.from_utc(mission.epoch, mission.dut1)
    r, v, q = start_state(mission, scenario.site, epoch.gmst())
    rigid = scenario.vehicle.rigid_body
    body = (Body if rigid else Vehicle)(
        name=channel_name(scenario.vehicle.name),
        y=make_state(r, v, q, mission.initial_rates),
        p=make_params(rigid.mass if rigid else 1.0, rigid.inertia if rigid else (1.0, 1.0, 1.0),
                      EARTH_MU, EARTH_RADIUS_EQ, EARTH_J2, EARTH_RADIUS_POLAR,
                      # the classic range's original model (held for the step); stages inherit p
                      classic=scenario.site is not None and scenario.site.model == "classic"),
    )
    flown = mission.duration if duration is None else time_argument(duration, "duration", check_duration)
    world = World(epoch, h, flown, [body], atmosphere=loaded.atmosphere)
    world.scenario_file, world.vehicle_file = loaded.files.get("scenario"), loaded.files.get("vehicle")
    world.step_line = loaded.step_line if step is None else None
    center = mission.start.orbit.body if mission.start.orbit is not None else "earth"
    if mission.gravity == "n-body" or center != "earth":
        body.p = with_field(central_params(body.p, center),
                            nbody_field(center, epoch.jd_tt(), world.gmst0))
        body.central, body.mu = center, float(body.p[P_MU])
    body.atmosphere = lambda: world.atmosphere
    body.sensors = Sensors(scenario.seed, body.name, scenario.sensors, h)
    if rigid is None:
        # tanks and engine clocks extend the state; p's mass is unused
        body.vehicle = build(scenario.vehicle, air=world.atmosphere)
        body.y = body.vehicle.state(r, v, q, mission.initial_rates)
        site_start = mission.start.site
        contact = body.vehicle.arrays.aero.contact
        if site_start is not None and site_start.rail is not None:
            x_cm = body.vehicle.mass_properties(body.y)[1]
            r, w, rail = on_rail(scenario.site, site_start.rail, q, x_cm)
            body.y[R:R + 3], body.y[V:V + 3] = r, ecef_to_eci_velocity(r, np.zeros(3), 0.0)
            body.y[W:W + 3] = w
            body.vehicle.arrays.rail[:] = rail
        elif site_start is not None and len(contact) and site_start.elevation == math.pi / 2 \
                and not any(site_start.velocity):
            # upright on the pad: feet on the ground, not the centre of mass
            up = enu_basis(scenario.site.latitude, scenario.site.longitude)[2]
            x_cm = body.vehicle.mass_properties(body.y)[1]
            body.y[R:R + 3] = standing_on_ground(r, up, x_cm, float(contact[:, 0].min()))
        if scenario.site is not None and mission.start.site:
            body.vehicle.arrays.aero.ref[A_GROUND] = scenario.site.ground   # flat ground
        if scenario.vehicle.aero is not None and scenario.vehicle.aero.aerodynamics:
            site, target_pad = scenario.site, mission.target.pad
            if target_pad is not None:
                pad = geodetic_to_ecef(target_pad.latitude, target_pad.longitude, 0.0)
            else:
                pad = None if site is None else geodetic_to_ecef(site.latitude, site.longitude, site.height)
            body.checks = VehicleChecks(scenario.vehicle.aero.heat_shield, pad_ecef=pad,
                                        limits=scenario.vehicle.aero.limits)
        body.stack = scenario.vehicle
        if center != "earth":
            fly_in_air_of(world, body)
    body.watch = FlightEvents(world, body, on_ground=mission.start.site is not None,
                              stage_names=[s.name for s in scenario.vehicle.stages or []])
    world.sample_every = max(1, round(1.0 / (scenario.telemetry.rate * h)))
    coast = scenario.telemetry.coast_rate
    if coast is not None:           # a multiple of the sample interval (rocketsim.sim.sample_watch)
        world.coast_every = world.sample_every * max(1, round(1.0 / (coast * h * world.sample_every)))
    world.seed, world.sensor_level = scenario.seed, scenario.sensors
    if scenario.follow is not None:
        world.follow = frozenset(channel_name(name) for name in scenario.follow)
    world.target = mission.target
    world.pad_azimuth = scenario.site.pad_azimuth if scenario.site else math.nan
    world.program_cpu_budget = scenario.program_cpu_budget
    world.program_time_limit = scenario.program_time_limit
    # on a cold cache a second process compiles the first runs' kernels from here on, while
    # this one compiles the programs' and the first sample's
    compile_runs_beside(world)
    compile_coasts_beside(world)
    programs = loaded.programs()
    for stage, path in loaded.stage_program_paths.items():
        given = programs[f"program/{stage}"][0]
        world.stage_programs[stage] = (plain_program(given, path) if given else load_program(path), path)
    if "program" in programs:
        main, path = programs["program"]
        world.attach_program(body, plain_program(main, path) if main else load_program(path), path)
    return world
