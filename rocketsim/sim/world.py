"""The world of one run: its bodies, the step loop, events and telemetry.

Everything with state lives here; the physics it calls is pure. Each step of
``h`` seconds (20 ms by default):

1. each awake program that is due runs once (it runs until it hands back);
2. each autopilot steers once;
3. every flying body is advanced (:meth:`World.advance`: RK4, sub-stepped within
   2 m of the ground, or rails where :mod:`rocketsim.sim.schedule` allows);
4. events are detected (liftoff, max-Q, MECO, orbit, handover, impact...);
5. telemetry is sampled at the configured rate.

Mission time is ``k h`` for the integer step count ``k``, never an accumulated
sum. While no program is due and no sample is due, steps are batched inside
the compiled kernels: bit-identical to stepping one at a time. Steps that must
be taken one at a time are flown in windows (:mod:`rocketsim.sim.window`): each
body in compiled runs where it can, going on past sample steps (computing those
samples themselves, written in order) and past other bodies' steps that Python
handles, their programs' wake-ups included (the programs run there). A world is
built from a scenario by :func:`rocketsim.sim.build.build_world`; staging is
:mod:`rocketsim.sim.staging`, the handover :mod:`rocketsim.sim.handover`, the
summary :mod:`rocketsim.sim.summary`.
"""

from __future__ import annotations

import math
from typing import Callable

import numpy as np

from rocketsim.constants import DEG, SECONDS_PER_DAY
from rocketsim.dynamics.central import air_about, nbody_field, next_center, planetocentric
from rocketsim.dynamics.cruise import SOI, advance_cruise
from rocketsim.dynamics.derivative import radial_height
from rocketsim.dynamics.free_body import advance_free
from rocketsim.dynamics.nbody import no_air
from rocketsim.dynamics.prediction import coast
from rocketsim.dynamics.rails import FREE, advance_rails, hold_mode, settle
from rocketsim.dynamics.rk4 import advance
from rocketsim.dynamics.third_bodies import bodies_at, field_of, nbody_flag
from rocketsim.ephemeris.solar_system import BODIES
from rocketsim.errors import InputError
from rocketsim.flight.fc import FlightComputer
from rocketsim.flight.program import ProgramRunner
from rocketsim.sim import sampling, staging
from rocketsim.sim.body import Body
from rocketsim.sim.craft import BodyCraft
from rocketsim.sim.ground_crossing import back_to_ground
from rocketsim.sim.sample_watch import SampleWatch
from rocketsim.sim.handover import hand_over, watch_soi
from rocketsim.sim.schedule import Schedule, inertia, rails_field
from rocketsim.sim.summary import summary
from rocketsim.sim.coast_runs import fly_coast
from rocketsim.sim.window import fly_window
from rocketsim.timescales import Epoch
from rocketsim.vehicle.aero import A_GROUND

NO_AIR = no_air()


class World:
    """One run of a scenario. Build with :func:`rocketsim.sim.build.build_world`,
    then :meth:`run`."""

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
        self.coast_every = None             # steps between a coasting body's samples (None: every)
        self.sample_watch = None            # the telemetry's SampleWatch while it flies with one
        self.on_progress: Callable[[float], None] | None = None
        self.phase = ""                     # the latest event, "<body>: <name>" (progress bars)
        self.schedule = Schedule(self)
        self._build_atmosphere = atmosphere
        self._atmosphere = None
        self._ephemeris = None              # the bodies' positions about Earth (body_state)
        self.seed = 0
        self.sensor_level = "truth"
        self.stage_programs: dict[str, object] = {}      # stage name -> (main, path)
        self.follow: frozenset[str] | None = None       # the bodies flown to the end (None: all)
        self.program_cpu_budget = 1.0
        self.program_time_limit = 10.0      # s of wall time a program's wake-up may take
        self.target = None                  # the mission's target (TargetSpec)
        self.pad_azimuth = math.nan
        self.scenario_file = None           # Path of the scenario's file (None: given as a mapping)
        self.vehicle_file = None            # Path of the vehicle's file (None: written inline)
        self.step_line = None               # line of ``step`` in the scenario's file (None: not written)
        # called before a program acts (a command, a log line, an event): set while a window
        # reads a condition ahead of its queue, to write first what comes first (rocketsim.sim.window)
        self.before_act: Callable[[], None] | None = None

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

    def acting(self) -> None:
        """A program is about to act (see :attr:`before_act`)."""
        if self.before_act is not None:
            self.before_act()

    def attach_program(self, body: Body, main, path) -> None:
        """Fly ``body`` with the program ``main`` (loaded from ``path``)."""
        body.runner = ProgramRunner(main, path, self.program_cpu_budget, self.program_time_limit)
        body.fc = FlightComputer(BodyCraft(self, body))

    # --- staging (rocketsim.sim.staging) -------------------------------------
    def separate(self, body: Body) -> Body:
        """Separate the lowest stage of ``body``; returns the stage's new body."""
        return staging.separate(self, body)

    def jettison_fairing(self, body: Body) -> tuple[Body, Body]:
        """Drop ``body``'s fairing; returns its two halves' new bodies."""
        return staging.jettison_fairing(self, body)

    def deploy_payload(self, body: Body) -> Body:
        """Release ``body``'s payload; returns its new body."""
        return staging.deploy_payload(self, body)

    # --- records ------------------------------------------------------------
    def log(self, body: Body, message: str) -> None:
        if self.telemetry is not None:
            self.telemetry.log(self.t, body.name, message)

    def event(self, body: Body, name: str, figures: dict) -> None:
        """Record an event of ``body`` at the body's own time (SI figures); the summary's
        record of an orbit event (one with a periapsis) names the body it is about."""
        record = {"name": name, "time_s": body.t, **figures}
        if "periapsis_altitude_m" in figures:
            record["central_body"] = body.central
        body.events.append(record)
        self.phase = f"{body.name}: {name}"
        if self.telemetry is not None:
            self.telemetry.event(body.t, body.name, name, figures)

    def end_flight(self, body: Body, name: str, figures: dict) -> None:
        """End ``body``'s flight where it is: the event ``name`` (as :meth:`event`) and,
        with telemetry, its last sample."""
        self.event(body, name, figures)
        body.flying = False
        if self.telemetry is not None:
            self.record(body)

    def sample(self, body: Body) -> dict:
        """The telemetry state message of ``body`` at its time (:mod:`rocketsim.sim.sampling`)."""
        return sampling.message(body, self.gmst0, self.where)

    def record(self, body: Body, leaving: bool = False) -> None:
        """Write ``body``'s telemetry sample: its state message (as :meth:`sample`) and the
        Foxglove messages drawn from it, from the numbers alone (no dictionaries);
        ``leaving``: its last in a frame it leaves at this instant (a handover)."""
        self.telemetry.sample(body.name, *sampling.values(body, self.gmst0, self.where), leaving=leaving)

    def record_rows(self, body: Body, rows: np.ndarray, shape) -> None:
        """Write ``body``'s telemetry samples computed in a compiled run, in order: each row
        the figures :meth:`record` writes at that sample (:func:`rocketsim.sim.sampling.run_sampler`),
        ``shape`` their fields."""
        self.telemetry.sample_rows(body.name, rows, shape)

    def record_interleaved(self, blocks: list[tuple]) -> None:
        """:meth:`record_rows` of several blocks at once, ``(body, rows, shape, first, every,
        rank)`` each: row ``j`` the sample at step ``first + j every``, the samples written by
        step and then rank."""
        self.telemetry.sample_interleaved([(body.name, *rest) for body, *rest in blocks])

    # --- the loop -----------------------------------------------------------
    def run(self, telemetry=None) -> dict:
        """Fly to the end of the mission (or until every body has landed or hit), writing
        ``telemetry`` through a :class:`~rocketsim.sim.sample_watch.SampleWatch` (the flight
        figures of the summary, the coasts thinned)."""
        if telemetry is not None:
            telemetry = self.sample_watch = SampleWatch(telemetry, self.h, self.sample_every, self.coast_every)
        self.telemetry = telemetry
        for body in self.bodies:
            if telemetry is not None:
                telemetry.add_body(body.name)
        self._sample_all()
        self._prepare_programs()
        try:
            while self.k < self.n_steps and any(b.flying for b in self.bodies):
                self.run_programs(range(len(self.bodies)))
                self._run_autopilots()
                n = self.schedule.batch_length()
                if not self._flown_compiled(n):
                    for body in self.bodies:
                        if body.flying:
                            self.advance(body, n)
                        if body.flying and body.watch is not None:
                            body.watch.after_step()
                    self.k += n
                    self.reached()
            if self.sample_watch is not None:
                self.sample_watch.finish()
        finally:
            for body in self.bodies:
                if body.runner is not None:
                    body.runner.close()
        return summary(self)

    def reached(self, sample: Callable[[], None] | None = None) -> None:
        """The loop has flown to step ``k``: at a sample step (every ``sample_every``-th,
        the last, after a cruise step) the finiteness check and the telemetry sample
        (``sample``, when the caller has them to write, else every flying body's from its
        state), then ``on_progress``, which may end the flight earlier (``n_steps``)."""
        if self.k % self.sample_every == 0 or self.k >= self.n_steps or self.schedule.cruise_batch:
            if sample is None:
                self.check_finite()
                self._sample_all()
            else:
                sample()
        if self.on_progress is not None:
            self.on_progress(self.t)

    def _flown_compiled(self, n: int) -> bool:
        """Whether the bodies have been flown on from step ``k`` (``k`` moved on) in
        compiled runs, the next batch being ``n`` steps, their last step sampled and
        reported (:meth:`reached`): whole sample intervals of coasting rigid bodies from
        a sample step (:mod:`rocketsim.sim.coast_runs`), or a window of bodies stepped
        one step at a time (:mod:`rocketsim.sim.window`, which samples and reports itself)."""
        if n == self.sample_every and self.k % n == 0 and fly_coast(self):
            self.reached()
            return True
        return n == 1 and fly_window(self, self.schedule.window_length())

    def _prepare_programs(self) -> None:
        """Compute every reading once before the first step, outside any program's
        CPU budget: the day's air table is built and the compiled kernels behind
        the readings are loaded (or compiled, on a cold cache) here, not in the
        program's first step."""
        for body in self.bodies:
            if body.runner is not None:
                body.fc.warm_up()

    def run_programs(self, indices) -> list[int]:
        """Run the programs due at step ``k`` of the bodies ``indices``, in the bodies'
        order, then those of the bodies they make (a separated stage, a fairing's halves,
        a payload: a stage's program starts in the step it separates); returns the
        indices of the bodies made."""
        first = known = len(self.bodies)
        order = sorted(indices)
        t = self.t
        for i in order:                     # visits the bodies appended on the way too
            body = self.bodies[i]
            if body.flying and body.runner is not None and body.runner.due(t):
                body.runner.resume(body.fc)
            order.extend(range(known, len(self.bodies)))
            known = len(self.bodies)
        return list(range(first, known))

    def _run_autopilots(self) -> None:
        for body in self.bodies:
            self.run_autopilot(body)

    def run_autopilot(self, body: Body) -> None:
        """Run ``body``'s autopilot for the step starting now, if it steers (a vehicle
        with checks runs its compiled step in its advance: :attr:`Body.steering`)."""
        if body.flying and body.attitude_command is not None and body.fc is not None:
            if self.schedule.holding(body):     # held on rails: the autopilot rests, its RCS off
                if body.vehicle is not None:
                    body.vehicle.arrays.aero.rcs_cmd[:] = 0.0
                return
            folded = body.fc.autopilot(fold=body.checks is not None)
            if body.vehicle is not None:
                body.steering = folded

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
            fp = self.schedule.cruise_field(body)
        v = body.velocity if delta_v is None else body.velocity + np.asarray(delta_v, dtype=float)
        return coast(body.position, v, body.t, float(seconds), body.p, fp, periapsis=periapsis)

    def where(self, body: Body) -> tuple[float, float, float]:
        """(latitude rad, longitude rad, height m): geodetic on WGS84 about Earth,
        planetocentric over the central body's ellipsoid elsewhere
        (:func:`rocketsim.dynamics.central.planetocentric`)."""
        if body.central == "earth":
            return body.view().geodetic
        return planetocentric(body.position, body.central, self.epoch.jd_tt() + body.t / SECONDS_PER_DAY)

    def _cruise(self, body: Body, n: int) -> int:
        """Cruise ``body`` up to ``n`` steps; returns the steps taken (the rest fly awake)."""
        p = body.p
        moments = inertia(body)
        k = self.k
        while k < self.k + n:
            y, k_end, reason, _ = advance_cruise(body.y, k, self.h, self.k + n, p,
                                                 self.schedule.cruise_field(body), NO_AIR, moments)
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
            hand_over(self, body, new)
            p = body.p
        return k - self.k

    def advance(self, body: Body, n: int) -> None:
        """Advance ``body`` by ``n`` steps from step ``k`` (fewer if it hits the ground):
        on cruise rails, sleep rails, the tumbling part's drag or RK4, as the schedule
        says; then the handover, the checks and the impact."""
        k0 = self.k
        if self.schedule.cruising(body):
            done = self._cruise(body, n)
            k0, n = k0 + done, n - done
        if n > 0 and self.schedule.on_rails(body):
            mode, code = FREE, None
            if body.attitude_command is not None:   # a new state: a view of the old one stays
                code = body.attitude_command.code
                mode = hold_mode(code)
                body.y = body.y.copy()
                settle(body.y, code, k0 * self.h, mode, body.p)
            # same step, same orbit to the bit; stops below the floor and wakes for the rest
            body.y, done = advance_rails(body.y, k0, self.h, n, body.p, rails_field(body),
                                         NO_AIR, inertia(body), mode,
                                         self.schedule.rails_floor(body), code)
            if body.vehicle is not None:
                body.y[body.vehicle.clocks] += done * self.h     # engine clocks run on
            k0, n = k0 + done, n - done
        if n == 0:
            body.t = k0 * self.h
            watch_soi(self, body)
            return
        if body.vehicle is None and body.drag is not None:     # a tumbling part: gravity and drag
            y, taken = advance_free(body.y, k0, self.h, n, body.p, rails_field(body), self.air_of(body),
                                    *body.drag, nbody_flag(body.p))
        elif body.vehicle is None:
            y, taken = advance(body.y, k0, self.h, n, body.p, None, nbody_flag(body.p))
        elif body.checks is not None:       # with the autopilot's step first, the checks' figures after
            y, taken = body.checks.advance(body, k0, self.h, n, body.steering)
            body.steering = None
        else:
            y, taken = body.kernels.call(advance, body.vehicle.arrays, body.y, k0, self.h, n, body.p,
                                         body.vehicle.arrays, nbody_flag(body.p))
        body.y = y
        self.after_advance(body, k0 + taken, taken < n)

    def air_of(self, body: Body):
        """The air table (its arrays) a tumbling part ``body`` flies through: its central
        body's (:func:`rocketsim.dynamics.central.air_about`), none without the day's air."""
        return NO_AIR if self.atmosphere is None else air_about(body.central, self.atmosphere).arrays()

    def after_advance(self, body: Body, k: int, short: bool = False) -> None:
        """``body`` has been advanced to step ``k`` (its state ``y``): its time, the
        handover, the checks and the impact (also when it stopped ``short`` of the steps
        asked, below the ground)."""
        body.t = k * self.h
        watch_soi(self, body)
        crash = None if body.checks is None else body.checks.after_step(self, body, self.h)
        ground = 0.0 if body.vehicle is None else body.vehicle.arrays.aero.ref[A_GROUND]
        if body.flying and (crash is not None or short or radial_height(body.y, body.p) < ground):
            # the body went below the ground in its last step (the batch's last one
            # included, where advance cannot say so by stopping early): it has hit, where
            # it crossed the ground (its time no longer a whole number of steps); or its
            # first contact was a crash (its speeds at the contact, not after the springs)
            if crash is None:
                tau, body.y = back_to_ground(body.y, body.p, ground, self.h)
                body.t += tau
            lat, lon, _ = self.where(body)
            ground_speed = np.linalg.norm(body.view().surface_velocity)     # over the central body's ground
            figures = {"latitude_deg": lat / DEG, "longitude_deg": lon / DEG,
                       "surface_speed_m_s": float(ground_speed)}
            if crash is not None:
                figures.update(crash, surface_speed_m_s=math.hypot(crash["vertical_speed_m_s"],
                                                           crash["horizontal_speed_m_s"]))
            self.end_flight(body, "impact", figures)

    def check_finite(self) -> None:
        """Stop the flight with an input error when a body's state is no longer finite
        (a step too large for its dynamics, or an unphysical vehicle), naming the
        scenario's file and the vehicle's (every body of the world is part of that
        vehicle). Checked at the telemetry rate, before sampling: the file ends with
        finite samples."""
        for body in self.bodies:
            if body.flying and not math.isfinite(float(body.y.sum())):
                vehicle = "" if self.vehicle_file is None else f" (vehicle file {self.vehicle_file})"
                raise InputError(f"the state of {body.name}{vehicle} is no longer finite at T+{body.t:.2f} s: "
                                 f"the step of {self.h:g} s is too large for its dynamics (stiff contact, "
                                 "a fast spin) or its vehicle is unphysical; fly with a smaller step",
                                 file=self.scenario_file, line=self.step_line, field="step")

    def _sample_all(self) -> None:
        if self.telemetry is None:
            return
        for body in self.bodies:
            if body.flying:
                self.record(body)
