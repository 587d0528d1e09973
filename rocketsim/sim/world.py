"""The world of one run: its bodies, the step loop, events and telemetry.

Everything with state lives here; the physics it calls is pure. Each step of
``h`` seconds (20 ms by default):

1. each awake program that is due runs once (it runs until it hands back);
2. every flying body is advanced by RK4 (sub-stepped within 2 m of the ground);
3. events are detected (impact);
4. telemetry is sampled at the configured rate.

Mission time is ``k h`` for the integer step count ``k``, never an
accumulated sum. While no program is due and no sample is due, steps are
batched inside the compiled kernel: bit-identical to stepping one at a time.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import partial
from typing import Callable

import numpy as np

from rocketsim.constants import DEG, EARTH_J2, EARTH_MU, EARTH_RADIUS_EQ, EARTH_RADIUS_POLAR
from rocketsim._jit import Entries
from rocketsim.atmosphere.table import TOP
from rocketsim.dynamics.derivative import radial_height
from rocketsim.dynamics.free_body import advance_free
from rocketsim.dynamics.cruise import DONE, SOI, advance_cruise, plan_step
from rocketsim.dynamics.nbody import make_field, no_air
from rocketsim.dynamics.rails import FREE, advance_rails, hold_mode, hold_offsets, rails_floor, settle
from rocketsim.dynamics.rk4 import advance
from rocketsim.dynamics.state import (P_IXX, P_IYY, P_IZZ, P_MASS, P_MU, Q, R, V,
                                      W, make_params, make_state)
from rocketsim.flight.fc import FlightComputer
from rocketsim.flight.program import ProgramRunner, load_program
from rocketsim.flight.readings import StateView
from rocketsim.flight.sensors import Sensors
from rocketsim.flight.steering import OMEGA_N, ZETA
from rocketsim.scenario.load import LoadedScenario
from rocketsim.scenario.models import check_duration, check_step
from rocketsim.errors import InputError
from rocketsim.frames.geodetic import enu_basis, geodetic_to_ecef
from rocketsim.sim.central import air_about, next_center, nbody_field, planetocentric, recentre
from rocketsim.dynamics.soi import central_params
from rocketsim.dynamics.third_bodies import bodies_at, field_of, with_field
from rocketsim.dynamics.prediction import coast
from rocketsim.ephemeris.solar_system import BODIES
from rocketsim.sim.start import standing_on_ground, start_state
from rocketsim.sim import sampling
from rocketsim.sim.flight_events import FlightEvents
from rocketsim.sim.vehicle_checks import VehicleChecks
from rocketsim.timescales import Epoch
from rocketsim.scenario.models import VehicleSpec
from rocketsim.vehicle.build import VehicleModel, build
from rocketsim.vehicle.engines import C_ON, E_TAIL
from rocketsim.vehicle.staging import deploy_payload, jettison_fairing, separate


# parking-orbit rails about Earth: Kepler + J2, no third bodies (issue 9); a rigid
# body with drag goes on them only above the air (free_body flies it below)
_RAILS_FIELD = make_field("earth", 0.0, bodies=())
_NO_AIR = no_air()
# a held attitude goes on sleep rails once the autopilot has settled on it:
HOLD_SETTLED_ERROR = math.radians(0.01)    # rad, attitude off the command (less the law's lag)
HOLD_SETTLED_RATE = 1e-4                   # rad/s, every body rate off the frame's turn rate


@dataclass
class Body:
    """One body in flight: its state, parameters, program and record."""

    name: str
    y: np.ndarray
    p: np.ndarray
    runner: ProgramRunner | None = None
    fc: FlightComputer | None = None
    flying: bool = True
    events: list[dict] = field(default_factory=list)
    mu: float = EARTH_MU
    t: float = 0.0
    atmosphere: Callable[[], object] | None = None    # the day's table, built on first use
    sensors: Sensors | None = None
    _view: StateView | None = None
    vehicle: VehicleModel | None = None     # a staged vehicle: mass and engines from its arrays
    checks: VehicleChecks | None = None     # breakup, heat shield, touchdown (a vehicle with aero:)
    watch: FlightEvents | None = None       # liftoff, max-Q, MECO/SECO, orbit
    stack: VehicleSpec | None = None        # the stages this body still carries (to separate)
    attitude_command: object | None = None  # what the autopilot steers to (fc.point, hold...)
    cruise_until: float = -math.inf         # mission time fc.cruise allows cruise rails until
    central: str = "earth"                  # the body whose frame and gravity it flies in
    kernels: Entries = field(default_factory=Entries)   # compiled entries bound to its arrays
    steering: tuple | None = None           # the autopilot's step folded into this step's advance
    drag: tuple | None = None               # a tumbling rigid body's (mean area / mass m^2/kg, length m)

    @property
    def position(self) -> np.ndarray:
        return self.y[R:R + 3]

    @property
    def velocity(self) -> np.ndarray:
        return self.y[V:V + 3]

    @property
    def attitude(self) -> np.ndarray:
        return self.y[Q:Q + 4]

    @property
    def body_rates(self) -> np.ndarray:
        return self.y[W:W + 3]

    @property
    def mass(self) -> float:
        if self.vehicle is not None:
            return float(self.vehicle.mass_properties(self.y)[0])
        return float(self.p[P_MASS])

    def view(self) -> StateView:
        """The truth's readings at the body's time (one view per step)."""
        if self._view is None or self._view.t != self.t:
            # the central body's air: the day's about Earth, Mars's about Mars, none elsewhere
            air = self.atmosphere if self.central == "earth" else partial(air_about, self.central, None)
            self._view = StateView.of_state(self.t, self.y, air, self.mu, self.p)
        return self._view


class World:
    """One run of a scenario. Build with :meth:`from_scenario`, then :meth:`run`."""

    def __init__(self, epoch: Epoch, h: float, duration: float, bodies: list[Body],
                 atmosphere: Callable[[], object] | None = None):
        self.epoch = epoch
        self.gmst0 = epoch.gmst()
        self.h = h
        self.duration = duration
        self.n_steps = int(math.floor(duration / h + 1e-9))
        self.bodies = bodies
        self.k = 0
        self.telemetry = None
        self.sample_every = 1
        self.on_progress: Callable[[float], None] | None = None
        self.phase = ""                     # the latest event, "<body>: <name>" (progress bars)
        self._build_atmosphere = atmosphere
        self._atmosphere = None
        self._field = None                  # cruise rails' field, built on first use
        self._ephemeris = None              # the bodies' positions about Earth (body_state)
        self._cruise_batch = False          # the last batch was one cruise step
        self.seed = 0
        self.sensor_level = "truth"
        self.stage_programs: dict[str, object] = {}      # stage name -> (main, path)
        self.program_cpu_budget = 1.0
        self.target = None                  # the mission's target (TargetSpec)
        self.pad_azimuth = math.nan

    @property
    def atmosphere(self):
        """The day's :class:`~rocketsim.atmosphere.table.AtmosphereTable`, built on first use."""
        if self._atmosphere is None and self._build_atmosphere is not None:
            self._atmosphere = self._build_atmosphere()
        return self._atmosphere

    @property
    def t(self) -> float:
        """Mission time (s)."""
        return self.k * self.h

    @classmethod
    def from_scenario(cls, loaded: LoadedScenario, step: float | None = None,
                      duration: float | None = None) -> "World":
        scenario = loaded.scenario
        h = scenario.step if step is None else _checked_step(step)
        mission = scenario.mission
        epoch = Epoch.from_utc(mission.epoch, mission.dut1)
        r, v, q = start_state(mission, scenario.site, epoch.gmst())
        rigid = scenario.vehicle.rigid_body
        body = Body(
            name=_channel_name(scenario.vehicle.name),
            y=make_state(r, v, q, mission.initial_rates),
            p=make_params(rigid.mass if rigid else 1.0, rigid.inertia if rigid else (1.0, 1.0, 1.0),
                          EARTH_MU, EARTH_RADIUS_EQ, EARTH_J2, EARTH_RADIUS_POLAR,
                          # the classic range's original model (held for the step); stages inherit p
                          classic=scenario.site is not None and scenario.site.model == "classic"),
        )
        world = cls(epoch, h, mission.duration if duration is None else _checked_duration(duration), [body],
                    atmosphere=loaded.atmosphere)
        center = mission.start.orbit.body if mission.start.orbit is not None else "earth"
        if mission.gravity == "n-body" or center != "earth":
            body.p = with_field(central_params(body.p, center),
                                nbody_field(center, epoch.jd_tt(), world.gmst0))
            body.central, body.mu = center, float(body.p[P_MU])
        body.atmosphere = lambda: world.atmosphere
        body.sensors = Sensors(scenario.seed, body.name, scenario.sensors, h)
        if rigid is None:
            # staged (issue 4): tanks and engine clocks extend the state; p's mass is unused
            body.vehicle = build(scenario.vehicle, air=world.atmosphere)
            body.y = body.vehicle.state(r, v, q, mission.initial_rates)
            site_start = mission.start.site
            contact = body.vehicle.arrays.aero.contact
            if site_start is not None and len(contact) and site_start.elevation == math.pi / 2 \
                    and not any(site_start.velocity):
                # upright on the pad: feet on the ground, not the centre of mass
                up = enu_basis(scenario.site.latitude, scenario.site.longitude)[2]
                x_cm = body.vehicle.mass_properties(body.y)[1]
                body.y[R:R + 3] = standing_on_ground(r, up, x_cm, float(contact[:, 0].min()))
            if scenario.vehicle.aero is not None and scenario.vehicle.aero.aerodynamics:
                site, target_pad = scenario.site, mission.target.pad
                if target_pad is not None:
                    pad = geodetic_to_ecef(target_pad.latitude, target_pad.longitude, 0.0)
                else:
                    pad = None if site is None else geodetic_to_ecef(site.latitude, site.longitude, site.height)
                body.checks = VehicleChecks(scenario.vehicle.aero.heat_shield, pad_ecef=pad)
            body.stack = scenario.vehicle
            if center != "earth":
                world._fly_in_air_of(body)
        body.watch = FlightEvents(world, body, on_ground=mission.start.site is not None,
                                  stage_names=[s.name for s in scenario.vehicle.stages or []])
        world.sample_every = max(1, round(1.0 / (scenario.telemetry.rate * h)))
        world.seed, world.sensor_level = scenario.seed, scenario.sensors
        world.target = mission.target
        world.pad_azimuth = scenario.site.pad_azimuth if scenario.site else math.nan
        world.program_cpu_budget = scenario.program_cpu_budget
        for stage, path in loaded.stage_program_paths.items():
            world.stage_programs[stage] = (load_program(path), path)
        if loaded.program_path is not None:
            world._attach_program(body, load_program(loaded.program_path), loaded.program_path)
        return world

    def _attach_program(self, body: Body, main, path) -> None:
        body.runner = ProgramRunner(main, path, self.program_cpu_budget)
        body.fc = FlightComputer(self, body)

    # --- staging ------------------------------------------------------------
    def jettison_fairing(self, body: Body) -> tuple[Body, Body]:
        """Drop ``body``'s payload fairing: it opens into two rigid bodies of their own,
        ``fairing_1`` and ``fairing_2`` (half shells pushed apart along the body's
        ``+y`` and ``-y`` axes, each with its own channels and tumbling drag); centre of
        mass and momentum are conserved (:func:`rocketsim.vehicle.staging.jettison_fairing`).
        Returns the two new bodies."""
        stack = body.stack
        if body.vehicle is None or stack is None or not body.vehicle.has_fairing:
            raise ValueError(f"{body.name} has no fairing to jettison")
        kept, halves = jettison_fairing(stack, body.vehicle, body.y, 0, air=self.atmosphere)
        new = self._split_rigid(body, kept, halves, ("fairing_1", "fairing_2"),
                                stack.model_copy(update={"fairing": None}))
        self.event(body, "fairing jettison", {"fairing_mass_kg": stack.fairing.mass,
                                              "fairing_bodies": [half.name for half in new]})
        return new

    def deploy_payload(self, body: Body) -> Body:
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
        kept, part = deploy_payload(stack, body.vehicle, body.y, 0, air=self.atmosphere)
        new, = self._split_rigid(body, kept, [part], ("payload",), stack.model_copy(update={"payload": None}))
        figures = {"payload_mass_kg": new.mass, "upper_mass_kg": body.mass}
        self.event(body, "payload deploy", {**figures, "payload_body": new.name})
        self.event(new, "payload deploy", {**figures, "from_body": body.name})
        return new

    def _split_rigid(self, body: Body, kept, parts, names, stack: VehicleSpec) -> tuple[Body, ...]:
        """Fly ``body`` on as ``kept`` (model and state, what is left of ``stack``) and
        add each of ``parts`` (a rigid body's mass, inertia, state and drag:
        :func:`rocketsim.vehicle.staging._release_top`) as a new body named as ``names``."""
        without, y_without = kept
        body.vehicle, body.y, body._view, body.stack = without, y_without, None, stack
        new = []
        for name, part in zip(names, parts):
            added = self._add_body(name, make_state(part["position"], part["velocity"], part["attitude"],
                                                    part["rates"]),
                                   make_params(part["mass"], part["inertia"], EARTH_MU, EARTH_RADIUS_EQ,
                                               EARTH_J2, EARTH_RADIUS_POLAR), body)
            added.drag = (part["area"] / part["mass"], part["length"])
            new.append(added)
        return tuple(new)

    def _add_body(self, name: str, y: np.ndarray, p: np.ndarray, parent: Body,
                  vehicle: VehicleModel | None = None) -> Body:
        """A new body split from ``parent`` now: a unique channel name, the parent's
        air and sensors level, its telemetry channels and first sample."""
        names = {b.name for b in self.bodies}
        name = _channel_name(name)
        while name in names:
            name += "_"
        fp = field_of(parent.p)
        if fp is not None:              # the parent's central body and field
            p = with_field(central_params(p, parent.central), fp)
        new = Body(name=name, y=y, p=p, vehicle=vehicle, t=parent.t, mu=parent.mu,
                   atmosphere=parent.atmosphere, central=parent.central,
                   sensors=Sensors(self.seed, name, self.sensor_level, self.h))
        if vehicle is not None and parent.central != "earth":
            self._fly_in_air_of(new)
        self.bodies.append(new)
        if self.telemetry is not None:
            self.telemetry.add_body(new.name)
            self._record(new)
        return new

    def separate(self, body: Body) -> Body:
        """Separate the lowest stage of ``body``: ``body`` flies on as the upper stack,
        the stage becomes a body of its own (its own channels, and its own program
        when the scenario's ``programs:`` names one for it). Returns the new body.

        Centre of mass and momentum of the two parts add up to the stack's
        (:func:`rocketsim.vehicle.staging.separate`); no separation impulse.
        """
        stack = body.stack
        if body.vehicle is None or stack is None or len(stack.stages) < 2:
            raise ValueError(f"{body.name} has no stage left to separate")
        (lower, y_lower), (upper, y_upper) = separate(stack, body.vehicle, body.y, 1,
                                                      air=self.atmosphere)
        stage = stack.stages[0].name
        body.vehicle, body.y, body._view = upper, y_upper, None
        body.stack = upper_stack(stack)
        new = self._add_body(stage, y_lower, body.p.copy(), body, vehicle=lower)
        if body.checks is not None:         # the stage is a vehicle with aero of its own
            new.checks = VehicleChecks(stack.aero.heat_shield, pad_ecef=body.checks.pad)
        if body.watch is not None:
            new.watch = FlightEvents(self, new, on_ground=False, stage_names=body.watch.stage_names)
            new.watch.dry_seen = set(body.watch.dry_seen)
            new.watch.max_q_done = body.watch.max_q_done
        figures = {"stage": stage, "mass_kg": new.mass, "upper_mass_kg": body.mass}
        self.event(body, "separation", {**figures, "separated_body": new.name})
        self.event(new, "separation", {**figures, "from_body": body.name})
        if stage in self.stage_programs:
            self._attach_program(new, *self.stage_programs[stage])
            new.fc.warm_up()
        return new

    # --- records ------------------------------------------------------------
    def log(self, body: Body, message: str) -> None:
        if self.telemetry is not None:
            self.telemetry.log(self.t, body.name, message)

    def event(self, body: Body, name: str, figures: dict) -> None:
        """Record an event of ``body`` at the body's own time (SI figures)."""
        record = {"name": name, "time_s": body.t, **figures}
        body.events.append(record)
        self.phase = f"{body.name}: {name}"
        if self.telemetry is not None:
            self.telemetry.event(body.t, body.name, name, figures)

    def sample(self, body: Body) -> dict:
        """The telemetry state message of ``body`` at its time (:mod:`rocketsim.sim.sampling`)."""
        return sampling.message(body, self.gmst0, self.where)

    def _record(self, body: Body) -> None:
        """Write ``body``'s telemetry sample: its state message (as :meth:`sample`) and the
        Foxglove messages drawn from it, from the numbers alone (no dictionaries)."""
        self.telemetry.sample(body.name, *sampling.values(body, self.gmst0, self.where))

    def orbit_summary(self, body: Body) -> dict:
        """The osculating elements of ``body``'s state message (:func:`rocketsim.sim.sampling.orbit`)."""
        return sampling.orbit(body, self.gmst0)

    # --- the loop -----------------------------------------------------------
    def run(self, telemetry=None) -> dict:
        """Fly to the end of the mission (or until every body has landed or hit)."""
        self.telemetry = telemetry
        for body in self.bodies:
            if telemetry is not None:
                telemetry.add_body(body.name)
        self._sample_all()
        self._prepare_programs()
        try:
            while self.k < self.n_steps and any(b.flying for b in self.bodies):
                self._run_programs()
                self._run_autopilots()
                n = self._batch_length()
                for body in self.bodies:
                    if body.flying:
                        self._advance(body, n)
                    if body.flying and body.watch is not None:
                        body.watch.after_step()
                self.k += n
                if self.k % self.sample_every == 0 or self.k >= self.n_steps or self._cruise_batch:
                    self._check_finite()
                    self._sample_all()
                if self.on_progress is not None:
                    self.on_progress(self.t)
        finally:
            for body in self.bodies:
                if body.runner is not None:
                    body.runner.close()
        return self.summary()

    def _prepare_programs(self) -> None:
        """Compute every reading once before the first step, outside any program's
        CPU budget: the day's air table is built and the compiled kernels behind
        the readings are loaded (or compiled, on a cold cache) here, not in the
        program's first step."""
        for body in self.bodies:
            if body.runner is not None:
                body.fc.warm_up()

    def _run_programs(self) -> None:
        t = self.t
        for body in self.bodies:
            if body.flying and body.runner is not None and body.runner.due(t):
                body.runner.resume(body.fc)

    def _run_autopilots(self) -> None:
        for body in self.bodies:
            if body.flying and body.attitude_command is not None and body.fc is not None:
                if self._holding(body):     # held on rails: the autopilot rests, its RCS off
                    if body.vehicle is not None:
                        body.vehicle.arrays.aero.rcs_cmd[:] = 0.0
                    continue
                # a vehicle with checks runs the autopilot's compiled step in its advance
                body.steering = body.fc.autopilot(fold=body.checks is not None)

    def _batch_length(self) -> int:
        """Steps that can be taken before anything needs deciding."""
        self._cruise_batch = False
        if any(b.flying and b.checks is not None and b.checks.every_step(b) for b in self.bodies):
            return 1                        # limits, heating and touchdown are checked every step
        if any(b.flying and b.attitude_command is not None and not self._holding(b) for b in self.bodies):
            return 1                        # the autopilot runs once per step
        n = min(self.n_steps - self.k, self.sample_every - self.k % self.sample_every)
        flying = [b for b in self.bodies if b.flying]
        cruise = [self._cruise_steps(b) for b in flying if self._cruising(b)]
        self._cruise_batch = len(cruise) == len(flying) and all(c > 0 for c in cruise)
        if self._cruise_batch:
            # every body cruises: one cruise step per batch, sampled at its end
            n = min([self.n_steps - self.k] + cruise)
        for body in self.bodies:
            runner = body.runner
            if not body.flying or runner is None or runner.finished:
                continue
            if runner.waiting_on_predicate:
                return 1
            wake_steps = math.ceil((runner.wake_time() - self.t) / self.h - 1e-9)
            n = min(n, max(1, wake_steps))
        return max(1, n)

    def _on_rails(self, body: Body) -> bool:
        """Sleep rails (issue 9) for a body nobody flies or whose program sleeps beyond
        the next step, axisymmetric (the exact torque-free attitude), above the rails
        floor, with no attitude command: a rigid body, or a staged vehicle coasting
        (:meth:`_coasting`); or holding an attitude once settled (:meth:`_holding`)."""
        if body.attitude_command is not None:
            return self._holding(body)
        return (self._asleep(body) and self._coasting(body)
                and radial_height(body.y, body.p) > self._rails_floor(body))

    def _rails_floor(self, body: Body) -> float:
        """Height (m) below which ``body`` cannot stay on rails: :func:`rails_floor`, or
        the air's top (600 km) for a tumbling rigid body about a body with air, Earth or
        Mars (its drag is flown awake, :mod:`rocketsim.dynamics.free_body`)."""
        if body.drag is not None and body.central in ("earth", "mars"):
            return TOP
        return rails_floor(body.central)

    def _asleep(self, body: Body) -> bool:
        """Nobody flies ``body`` or its program sleeps beyond the next step."""
        runner = body.runner
        return runner is None or runner.finished or (
            not runner.waiting_on_predicate and runner.wake_time() - self.t > self.h * (1 + 1e-9))

    def _holding(self, body: Body) -> bool:
        """Sleep rails for a held attitude (issue 9): ``body`` is asleep (:meth:`_asleep`),
        coasts but for the autopilot's own RCS (:meth:`_coasting`; the RCS stops on
        rails), is above the rails floor, and the autopilot has settled on its command
        (:func:`rocketsim.dynamics.rails.hold_offsets`): every body rate within
        ``HOLD_SETTLED_RATE`` (1e-4 rad/s) of the command frame's turn rate ``Omega``,
        and the attitude error within ``HOLD_SETTLED_ERROR`` (0.01 deg) of the law's
        steady lag ``2 zeta Omega / omega_n`` (:mod:`rocketsim.flight.steering`; zero
        for mode HELD, an inertial direction with no roll, 0.12 deg at a low orbit's
        rate for mode TRACK: fc.hold's modes, fc.point's pitch/heading, any commanded
        roll) or of none (a body already on rails is on the command itself). On rails
        the attitude is set exactly on the command (the residual is dropped) and kept
        there at every step, the rates zero (HELD) or the frame's turn rate (TRACK), so
        the autopilot wakes to no error (:func:`rocketsim.dynamics.rails.settle`). The
        truth's frame is held (an autopilot reading noisy sensors steers the estimate's)."""
        command = body.attitude_command
        # coasting first: in the air (most steps of an ascent or a landing) it says no at once
        if command is None or not (self._coasting(body, rcs_free=True) and self._asleep(body)
                                   and radial_height(body.y, body.p) > rails_floor(body.central)):
            return False
        error, turn = hold_offsets(command.code, body.y, body.t, self.h, body.p)
        lagging = error - (2.0 * ZETA / OMEGA_N) * turn
        return (min(math.sqrt(error @ error), math.sqrt(lagging @ lagging)) < HOLD_SETTLED_ERROR
                and float(np.max(np.abs(body.y[W:W + 3] - turn))) < HOLD_SETTLED_RATE)

    def _coasting(self, body: Body, rcs_free: bool = False) -> bool:
        """True when only gravity acts on ``body`` and it is symmetric about its roll
        axis: a rigid body with ``I_yy = I_zz``, or a staged vehicle with every engine
        commanded off and its tail-off over, its RCS off (``rcs_free``: the autopilot's
        RCS commands ignored, a held body's on rails stop), and out of the air's reach
        (a vehicle with aerodynamics: above 600 km)."""
        vehicle = body.vehicle
        if vehicle is None:
            return body.p[P_IYY] == body.p[P_IZZ]
        if body.checks is not None and body.checks.every_step(body):
            return False                    # tested first: the cheapest, and true below 600 km
        arrays = vehicle.arrays
        if np.any(arrays.cmd[:, C_ON] > 0.5) or np.any(body.y[vehicle.clocks] <= arrays.eng[:, E_TAIL]):
            return False
        if not rcs_free and np.any(arrays.aero.rcs_cmd != 0.0):
            return False
        return bool(self._inertia(body)[1] == vehicle.mass_properties(body.y)[4])

    def _inertia(self, body: Body) -> np.ndarray:
        """``(I_xx, I_t, I_t)`` kg m^2 of the torque-free attitude on rails (a staged
        vehicle's from the propellant it carries)."""
        if body.vehicle is None:
            return body.p[P_IXX:P_IZZ + 1]
        _, _, ixx, iyy, _ = body.vehicle.mass_properties(body.y)
        return np.array((ixx, iyy, iyy))

    def _cruising(self, body: Body) -> bool:
        """fc.cruise allows cruise rails now (they run wherever no shell is near:
        a body inside one flies 20 ms steps and cruises again once clear)."""
        return body.cruise_until > self.t and body.attitude_command is None

    def _cruise_steps(self, body: Body) -> int:
        """Flight-model steps of ``body``'s next cruise step (0: it cannot cruise here)."""
        k_end = self.k + math.ceil((body.cruise_until - self.t) / self.h - 1e-9)
        steps, _, reason = plan_step(body.y, self.k, self.h, k_end, body.p, self._cruise_field(body))
        return steps if reason == DONE else 0

    def _cruise_field(self, body: Body) -> np.ndarray:
        """The field cruise rails integrate: the awake flight's own (the n-body field
        ``body`` carries, or Earth's point mass and J2 in the mission's ECI)."""
        fp = field_of(body.p)
        if fp is not None:
            return fp
        if self._field is None:
            self._field = make_field("earth", self.epoch.jd_tt(), bodies=())
        return self._field

    def body_state(self, body: Body, name: str, t: float | None = None):
        """Position (m) and velocity (m/s) of the Sun, Earth, Moon or Mars relative to
        ``body``'s central body, in its frame's axes, at mission time ``t`` (s; default
        the body's time): the ephemeris of the n-body field."""
        fp = field_of(body.p)
        if fp is None:
            if self._ephemeris is None:
                self._ephemeris = nbody_field("earth", self.epoch.jd_tt(), self.gmst0)
            fp = self._ephemeris
        s, u = bodies_at(fp, body.t if t is None else float(t))
        j = BODIES.index(name)
        return s[j].copy(), u[j].copy()

    def predict(self, body: Body, seconds: float, delta_v=None, periapsis: bool = False):
        """``(t, r, v)``: where ``body`` coasts in ``seconds`` (s) from now, after an
        impulsive ``delta_v`` (m/s, frame axes) if given; stops at the next periapsis
        about the central body with ``periapsis`` (:func:`rocketsim.dynamics.prediction.coast`)."""
        fp = field_of(body.p)
        if fp is None:
            fp = self._cruise_field(body)
        v = body.velocity if delta_v is None else body.velocity + np.asarray(delta_v, dtype=float)
        return coast(body.position, v, body.t, float(seconds), body.p, fp, periapsis=periapsis)

    def where(self, body: Body) -> tuple[float, float, float]:
        """(latitude rad, longitude rad, height m): geodetic on WGS84 about Earth,
        planetocentric over the central body's ellipsoid elsewhere
        (:func:`rocketsim.sim.central.planetocentric`)."""
        if body.central == "earth":
            return body.view().geodetic
        return planetocentric(body.position, body.central, self.epoch.jd_tt() + body.t / 86400.0)

    def _rails_field(self, body: Body) -> np.ndarray:
        """The field of sleep rails: the n-body field the body carries (so a sleeping
        body follows the awake path to the bit), else Kepler + J2 about Earth."""
        fp = field_of(body.p)
        return _RAILS_FIELD if fp is None else fp

    def _watch_soi(self, body: Body) -> None:
        """Hand ``body`` over to the body whose sphere of influence it has crossed into."""
        new = next_center(body.y, body.p, body.t)
        if new is not None:
            self._hand_over(body, new)

    def _hand_over(self, body: Body, new: str) -> None:
        """Re-centre ``body`` on ``new`` now (:func:`rocketsim.sim.central.recentre`):
        a sample in the old frame, the handover event, a sample in the new one."""
        old = body.central
        if self.telemetry is not None:
            self._record(body)
        body.y, body.p = recentre(body.y, body.p, body.t, new, self.gmst0)
        body.central, body.mu, body._view = new, float(body.p[P_MU]), None
        if body.vehicle is not None:
            self._fly_in_air_of(body)
        self.event(body, "soi_handover", {"from": old, "to": new})
        if self.telemetry is not None:
            self._record(body)

    def _fly_in_air_of(self, body: Body) -> None:
        """Give a staged vehicle the air of its central body (none about the Moon)."""
        arrays = body.vehicle.arrays
        h0, dh, density, pressure, temperature, sound, east, north = air_about(
            body.central, self.atmosphere).arrays()
        body.vehicle.arrays = arrays._replace(
            air_h0=h0, air_dh=dh, air_density=density, air_pressure=pressure,
            air_temperature=temperature, air_speed_of_sound=sound, air_wind_east=east,
            air_wind_north=north)

    def _cruise(self, body: Body, n: int) -> int:
        """Cruise ``body`` up to ``n`` steps; returns the steps taken (the rest fly awake)."""
        p = body.p
        inertia = self._inertia(body)
        k = self.k
        while k < self.k + n:
            y, k_end, reason, _ = advance_cruise(body.y, k, self.h, self.k + n, p,
                                                 self._cruise_field(body), _NO_AIR, inertia)
            if body.vehicle is not None:
                y[body.vehicle.clocks] += (k_end - k) * self.h     # engine clocks run on
            body.y, body.t, k = y, k_end * self.h, k_end
            if reason != SOI:
                break
            new = next_center(body.y, body.p, body.t)
            if new is None:     # no field to hand over in: 20 ms steps on
                body.cruise_until = -math.inf
                self.event(body, "cruise_end", {"reason": "left the sphere of influence"})
                break
            self._hand_over(body, new)
            p = body.p
        return k - self.k

    def _advance(self, body: Body, n: int) -> None:
        k0 = self.k
        if self._cruising(body):
            done = self._cruise(body, n)
            k0, n = k0 + done, n - done
        if n > 0 and self._on_rails(body):
            mode, code = FREE, None
            if body.attitude_command is not None:   # a new state: a view of the old one stays
                code = body.attitude_command.code
                mode = hold_mode(code)
                body.y = body.y.copy()
                settle(body.y, code, k0 * self.h, mode, body.p)
            # same step, same orbit to the bit; stops below the floor and wakes for the rest
            body.y, done = advance_rails(body.y, k0, self.h, n, body.p, self._rails_field(body),
                                         _NO_AIR, self._inertia(body), mode,
                                         self._rails_floor(body), code)
            if body.vehicle is not None:
                body.y[body.vehicle.clocks] += done * self.h     # engine clocks run on
            k0, n = k0 + done, n - done
        if n == 0:
            body.t = k0 * self.h
            self._watch_soi(body)
            return
        if body.vehicle is None and body.drag is not None:     # a tumbling part: gravity and drag
            air = _NO_AIR if self.atmosphere is None else air_about(body.central, self.atmosphere).arrays()
            y, taken = advance_free(body.y, k0, self.h, n, body.p, self._rails_field(body), air, *body.drag)
        elif body.vehicle is None:
            y, taken = advance(body.y, k0, self.h, n, body.p)
        elif body.checks is not None:       # with the autopilot's step first, the checks' figures after
            y, taken = body.checks.advance(body, k0, self.h, n, body.steering)
            body.steering = None
        else:
            y, taken = body.kernels.call(advance, body.vehicle.arrays, body.y, k0, self.h, n, body.p,
                                         body.vehicle.arrays)
        body.y = y
        body.t = (k0 + taken) * self.h
        self._watch_soi(body)
        crash = None if body.checks is None else body.checks.after_step(self, body, self.h)
        if body.flying and (crash is not None or taken < n or radial_height(body.y, body.p) < 0.0):
            # the body went below the ground in its last step (the batch's last one
            # included, where advance cannot say so by stopping early), or its first
            # contact was a crash (its speeds at the contact, not after the springs): it has hit
            lat, lon, _ = self.where(body)
            ground_speed = np.linalg.norm(body.view().surface_velocity)     # over the central body's ground
            figures = {"latitude_deg": lat / DEG, "longitude_deg": lon / DEG, "speed_m_s": float(ground_speed)}
            if crash is not None:
                figures.update(crash, speed_m_s=math.hypot(crash["vertical_speed_m_s"],
                                                           crash["horizontal_speed_m_s"]))
            self.event(body, "impact", figures)
            body.flying = False
            if self.telemetry is not None:
                self._record(body)

    def _check_finite(self) -> None:
        """Stop the flight with an input error when a body's state is no longer finite
        (a step too large for its dynamics, or an unphysical vehicle). Checked at
        the telemetry rate, before sampling: the file ends with finite samples."""
        for body in self.bodies:
            if body.flying and not math.isfinite(float(body.y.sum())):
                raise InputError(f"the state of {body.name} is no longer finite at T+{body.t:.2f} s: the "
                                 f"step of {self.h:g} s is too large for its dynamics (stiff contact, a fast "
                                 "spin) or its vehicle is unphysical; fly with a smaller step", field="step")

    def _sample_all(self) -> None:
        if self.telemetry is None:
            return
        for body in self.bodies:
            if body.flying:
                self._record(body)

    def summary(self) -> dict:
        """Events and final state of each body, SI units (degrees where named)."""
        bodies = {}
        for body in self.bodies:
            lat, lon, height = self.where(body)
            bodies[body.name] = {
                "events": body.events,
                "final": {
                    "time_s": body.t,
                    "position_m": body.position.tolist(),
                    "velocity_m_s": body.velocity.tolist(),
                    "latitude_deg": lat / DEG,
                    "longitude_deg": lon / DEG,
                    "altitude_m": height,
                    "speed_m_s": float(np.linalg.norm(body.velocity)),
                },
                "orbit": self.orbit_summary(body),
            }
            landed = [e for e in body.events if e["name"] == "touchdown"]
            if landed:      # the first contact's figures (speeds m/s, tilt deg, distance m)
                bodies[body.name]["touchdown"] = {k: v for k, v in landed[0].items() if k != "name"}
        return {"epoch_utc": self.epoch.utc.isoformat(), "step_s": self.h,
                "mission_time_s": max(b.t for b in self.bodies), "bodies": bodies}


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


def _checked_step(step: float) -> float:
    try:
        return check_step(step)
    except ValueError as error:
        raise InputError(str(error), field="--step") from None


def _checked_duration(duration: float) -> float:
    try:
        return check_duration(duration)
    except ValueError as error:
        raise InputError(str(error), field="--duration") from None


def _channel_name(name: str) -> str:
    return "".join(c if c.isalnum() or c in "-_" else "_" for c in name) or "vehicle"


