"""A window of steps flown without the world's loop: compiled runs where nothing needs Python.

While any body must be stepped one step at a time (a vehicle in the air's reach,
an autopilot steering, a program waiting on a condition:
:meth:`rocketsim.sim.schedule.Schedule.one_step`), the world's loop would run
every body's Python once per step. Up to the next step where the loop itself
has something to decide (the end, and while more than one body flies a
progress report every few samples:
:meth:`~rocketsim.sim.schedule.Schedule.window_length`) the bodies do not
interact but through what their programs do, so :func:`fly_window` flies each
on its own:

* a vehicle with aerodynamics, on its pad or in flight, steered by the autopilot's
  compiled step or not at all, its program asleep or waiting on a compiled
  condition (:mod:`rocketsim.flight.conditions`), no parachutes, in compiled runs
  (:meth:`rocketsim.sim.vehicle_checks.VehicleChecks.fly_run`,
  :mod:`rocketsim.stepping.runs`), each returning at a step where its checks or
  events may act, its program wakes or its condition is true, and that step
  handled as the loop handles every step;
* a tumbling part below its rails floor (a fairing half) in compiled runs of its
  free steps (:func:`rocketsim.stepping.runs.fly_part`), returning where its liftoff,
  orbit or impact may be; a rigid body with no event to watch and out of the
  ground's reach in the loop's own batch (bit-identical to its steps one by one);
* every other body one step at a time, exactly as the loop steps it (its
  autopilot, :meth:`~rocketsim.sim.world.World.advance`, its events).

At a step the Python side handles for some bodies, their programs that are due
run there (:meth:`~rocketsim.sim.world.World.run_programs`, as the loop runs
them), after that step's events and samples; the other bodies' runs go on past
it. A program acts on its own body only, or makes new ones (a separated
stage, a fairing's halves, a payload), which fly on from that step; a
vehicle whose program then waits on a condition read in Python (a lambda) or
wakes at every step (``fc.step()``) is flown in compiled runs that read the
program between their steps, once a step as the loop reads it, and resume it
there when it is due, the run going on while it only reads
(:meth:`_Window._steps`; one such vehicle at a time), and a body that cruises
one step at a time.
Everything the Python side does that others can see (events, logs, telemetry)
happens in the loop's order: by step, and within a step in the order of the
bodies. The window ends early once no body needs one step at a time (the loop
batches from there).

A vehicle's compiled runs go on past telemetry sample steps, computing the
samples of the steps they fly through (up to :data:`RUN_SAMPLES` of them),
with the sampler's own compiled figures (:func:`rocketsim.sim.sampling.run_sampler`)
and the world's finiteness test, and so do a tumbling part's; a batch ends
at the next sample step at most. The samples are written in the loop's order: those
the runs computed before a step the Python side handles are written before it,
by step and then body; at a sample step it handles, every flying body is
sampled in order, a body whose run goes on past the step from its run's rows,
the others from their state (:meth:`_Window._sample_with_runs`). Where every
body is at a sample step the Python side handles (always so with one body) the
world samples and reports progress as its loop does
(:meth:`rocketsim.sim.world.World.reached`); a flight that ``on_progress``
shortens ends there or at its new end.
"""

from __future__ import annotations

import heapq
import math

import numpy as np

from rocketsim.jit import compile_beside
from rocketsim.dynamics.third_bodies import field_of, nbody_flag
from rocketsim.flight.conditions import NO_CONDITION
from rocketsim.layout import N_STATE
from rocketsim.sim import sampling
from rocketsim.sim.flight_events import ORBIT_PERIAPSIS_BOUND
from rocketsim.sim.schedule import rails_field
from rocketsim.sim.window_plans import BATCH, PART, STEPS, VEHICLE, one_of_steps, plan, wake_step
from rocketsim.stepping import runs
from rocketsim.stepping.sample_figures import N_SAMPLE_RIGID

QUIET = "quiet"         # a vehicle's segment that ended on a quiet step
RUN_SAMPLES = 128       # telemetry samples a vehicle's compiled run computes at most


def fly_window(world, length: int) -> bool:
    """Fly the world's bodies ``length`` steps from its step ``k`` (fewer when the window
    ends early, see the module), with the loop's programs and autopilots already run for
    the first; leaves the world's step count at the window's end, its sample and progress
    made there (:meth:`~rocketsim.sim.world.World.reached`). False (nothing done) when the
    window has less than two steps."""
    if length < 2:
        return False
    k = world.k
    flying = [(i, body) for i, body in enumerate(world.bodies) if body.flying]
    plans = one_of_steps({i: plan(world, body, True, length * world.h) for i, body in flying})
    window = _Window(world, k + length)
    window.start(k, [i for i, _ in flying], plans)
    window.fly()
    return True


class _Window:
    """The bodies' queue of steps where the Python side acts (see the module)."""

    def __init__(self, world, end: int):
        self.world = world
        self.end = end
        self.queue: list[tuple] = []        # (step, body index, run: see start; None: one step to fly)
        # the samples computed in runs, not yet written: [first step, body index, rows, shape,
        # rows written] for each run, a row per sample step from the first
        self.samples: list[list] = []
        # step -> the bodies whose sample there is written already, and the bodies a program's
        # condition made there (their programs start at that step), by steps of one (_steps)
        self.presampled: dict[int, set] = {}
        self.made: dict[int, list] = {}

    def start(self, k: int, indices: list[int], plans: dict) -> None:
        """Start a segment of each body of ``indices`` at step ``k`` as ``plans[i]`` says
        (:func:`~rocketsim.sim.window_plans.plan`; None: one step), none past the step its program wakes at. A run's
        end goes on the queue: ``(VEHICLE, its last state)``, ``(QUIET, its last state)``
        (steps of one, :meth:`_steps`, flown last, to the queue's first step at most),
        ``(PART, its last state, its first step and state)``, ``(BATCH, k)``; the samples
        computed in a run go on :attr:`samples`."""
        world = self.world
        steps = [i for i in indices if plans[i] is not None and plans[i][0] == STEPS]
        for i in [i for i in indices if i not in steps] + steps:
            plan = plans[i]
            if plan is None:
                heapq.heappush(self.queue, (k + 1, i, None))
                continue
            body = world.bodies[i]
            top = min(self.end, wake_step(world, body))
            if plan[0] == VEHICLE:
                samples, rows, shape = _samples(world, body)
                y, taken, _, filled = body.checks.fly_run(body, k, world.h, top - k, plan[1], body.watch,
                                                          plan[2], samples)
                body.steering = None
                self._computed(k, i, rows[:filled], shape)
                heapq.heappush(self.queue, (k + taken, i, (VEHICLE, y)))
            elif plan[0] == STEPS:
                self._steps(k, i, plan[1])
            elif plan[0] == PART:
                samples, rows, shape = _samples(world, body)
                y, taken, filled = self._part(body, k, body.y, top - k, samples)
                self._computed(k, i, rows[:filled], shape)
                heapq.heappush(self.queue, (k + taken, i, (PART, y, k, body.y)))
            else:                           # BATCH: to the next sample at most, where the world samples
                top = min(top, k + world.sample_every - k % world.sample_every)
                heapq.heappush(self.queue, (top, i, (BATCH, k)))

    def _steps(self, k: int, i: int, steering) -> None:
        """Fly the vehicle ``i``, whose program waits on a condition read in Python or wakes
        at every step, in a compiled run from step ``k`` that reads the program between its
        steps as the world's loop reads it
        (:meth:`~rocketsim.sim.vehicle_checks.VehicleChecks.fly_run`'s ``between``;
        :meth:`~rocketsim.flight.program.ProgramRunner.check`: its condition or wake time
        once a step and, where it is due, the program resumed there (``resume_due``), ahead of the step's
        :meth:`~rocketsim.sim.world.World.run_programs`; its budget and time limit armed
        once, :meth:`~rocketsim.flight.program.ProgramRunner.watched`): to the queue's first
        step (where another body's Python comes first) or the window's end at most, ending
        at a step the Python side must handle, or one where the program raises, acts (a
        command, a log line, an event, a new body: what comes before it in the loop's order,
        the samples computed up to that step, is written first) or, resumed, waits on what
        the run does not read (a compiled condition, a later wake time). The run's end goes
        on the queue, ``(QUIET, its state)`` where it ended on a quiet step (its sample there
        computed in the run, or written already, with those of the other bodies' runs going
        on past it and of the bodies the program made: :attr:`presampled`), else
        ``(VEHICLE, its state)``."""
        world = self.world
        body = world.bodies[i]
        top = min(self.end, self.queue[0][0] if self.queue else self.end)
        samples, rows, shape = _samples(world, body)
        self._computed(k, i, rows, shape)           # all its rows: written as far as computed
        entry = self.samples[-1] if len(rows) else None
        runner, fc, known, acted, sampled = body.runner, body.fc, len(world.bodies), [], {i}
        check, resume_due = runner.check, runner.resume_due

        def act() -> None:                  # the program acts at step world.k: what comes first
            if not acted:
                acted.append(world.k)
                # the samples there, this body's and those of other bodies' runs going on past it
                sampled.update(run[1] for run in self.samples if _rows_before(run, world.k + 1, every)
                               > _rows_before(run, world.k, every))
                self._write_samples(world.k + 1)

        def between(step: int) -> bool:
            world.k = step
            t = step * h
            return check(t) and resume_due(fc, t, (step + 1) * h) or bool(acted)

        h, every = world.h, world.sample_every
        world.before_act = act
        try:
            with runner.watched():
                y, taken, reason, filled = body.checks.fly_run(body, k, h, top - k, steering, body.watch,
                                                               NO_CONDITION, samples, between)
        finally:
            world.before_act = None
        world.k = k
        body.steering = None
        if entry is not None:
            entry[2] = rows[:filled]
            self._drop_written()
        end = k + taken
        if acted:
            made = list(range(known, len(world.bodies)))
            self.presampled.setdefault(end, set()).update(sampled, made)
            self.made.setdefault(end, []).extend(made)
        heapq.heappush(self.queue, (end, i, (QUIET if reason == runs.QUIET else VEHICLE, y)))

    def _computed(self, k: int, i: int, rows: np.ndarray, shape) -> None:
        """The samples of body ``i`` a run from step ``k`` computed, one row per sample step
        from the first after ``k``, onto :attr:`samples`."""
        if len(rows):
            every = self.world.sample_every
            self.samples.append([k + every - k % every, i, rows, shape, 0])

    def fly(self) -> None:
        """Handle the queue's steps in order (by step, then body) to the window's end,
        with the world's sample and progress (:meth:`~rocketsim.sim.world.World.reached`)
        at each sample step the Python side handles for every body and at the end (a
        flight that ``on_progress`` has shortened ends there), and the samples alone
        (:meth:`_sample_with_runs`) at one where some bodies' runs go on past it; then
        the programs due there (:meth:`~rocketsim.sim.world.World.run_programs`) and the
        next segments of the bodies at that step still flying (a split may end some)."""
        world = self.world
        last = world.k
        reached = None                      # the step the world's sample and progress were last made at
        while self.queue:
            s = self.queue[0][0]
            due = []
            while self.queue and self.queue[0][0] == s:
                due.append(heapq.heappop(self.queue))
            self._write_samples(s)
            for _, i, run in due:
                self._finish(i, s, run)
            last = world.k = s
            if s >= self.end:
                continue
            movers = [i for _, i, _ in due if world.bodies[i].flying] + self.made.pop(s, [])
            if not self._one_step(movers):
                self._close(s)              # nobody needs one step at a time: the loop batches from here
                continue
            if s % world.sample_every == 0 and self.queue:
                self._sample_with_runs(s)   # some bodies' runs go on past this step
            elif s % world.sample_every == 0:     # every body is at this step
                world.reached(lambda: self._sample_with_runs(s))
                reached = s
                if world.n_steps < self.end:
                    self.end = max(world.n_steps, s)
                    if s >= self.end:
                        self._close(s)
                        continue
            movers = [i for i in movers + world.run_programs(movers) if world.bodies[i].flying]
            plans = one_of_steps({i: plan(world, world.bodies[i], False, (self.end - s) * world.h)
                                   for i in movers})
            for i in movers:
                if plans[i] is None:
                    world.run_autopilot(world.bodies[i])
            self.start(s, movers, plans)
        world.k = last
        if reached != last:
            world.reached(lambda: self._sample_with_runs(last))

    def _finish(self, i: int, s: int, run) -> None:
        """The step ``s`` of body ``i`` as the loop ends it (after a compiled run's last
        step, or flying the one step or the batch first), its events included."""
        world = self.world
        body = world.bodies[i]
        world.k = s - 1
        if run is None:
            world.advance(body, 1)
        elif run[0] == BATCH:
            world.k = run[1]
            world.advance(body, s - run[1])
        elif run[0] == QUIET:           # taken as a run's steps: the checks and events quiet, done
            body.y, body.t = run[1], s * world.h
            return
        else:
            body.y = run[1]
            world.after_advance(body, s)
        if body.flying and body.watch is not None:
            body.watch.after_step()

    def _write_samples(self, s: int) -> None:
        """Write the samples the runs computed before step ``s``, in the loop's order (by
        step, then body: as the world samples every body at a sample step), handed on
        together (:meth:`~rocketsim.sim.world.World.record_interleaved`)."""
        every = self.world.sample_every
        blocks = []
        for run in self.samples:
            first, i, rows, shape, done = run
            end = max(done, _rows_before(run, s, every))
            if end > done:
                blocks.append((self.world.bodies[i], rows[done:end], shape, first + done * every, every, i))
                run[4] = end
        if len(blocks) > 1:
            self.world.record_interleaved(blocks)
        elif blocks:
            self.world.record_rows(*blocks[0][:3])
        self._drop_written()

    def _sample_with_runs(self, s: int) -> None:
        """The world's sample at step ``s`` (its finiteness test, then every flying body's
        sample in order), the samples before ``s`` written already: from the row a run
        computed at ``s`` (a run going on past it, steps of one that ended there), else
        from the body's state; none again for a body whose sample there is written
        (:attr:`presampled`)."""
        world = self.world
        world.check_finite()
        every = world.sample_every
        written = self.presampled.pop(s, ())
        rows = {run[1]: run for run in self.samples if run[4] < len(run[2]) and run[0] + run[4] * every == s}
        for i, body in enumerate(world.bodies):
            if body.flying and world.telemetry is not None and i not in written:
                run = rows.get(i)
                if run is not None:
                    world.record_rows(body, run[2][run[4]:run[4] + 1], run[3])
                    run[4] += 1
                else:
                    world.record(body)
        self._drop_written()

    def _drop_written(self) -> None:
        """Forget the runs whose samples are all written."""
        self.samples = [run for run in self.samples if run[4] < len(run[2])]

    def _one_step(self, movers: list[int]) -> bool:
        """Whether the loop would step the next step one step at a time: a vehicle's
        compiled run goes on (its checks run every step), or a body at this step needs it."""
        schedule = self.world.schedule
        return any(run is not None and run[0] in (VEHICLE, QUIET) for _, _, run in self.queue) or \
            any(schedule.one_step(self.world.bodies[i]) for i in movers)

    def _close(self, s: int) -> None:
        """End the window at step ``s``: the tumbling parts and batches under way are
        brought to it (their steps to ``s`` have nothing for Python, and a part's run
        is flown again to ``s`` from where it started: the same steps, the same bits;
        its samples from ``s`` on are dropped)."""
        self.end = s
        world = self.world
        for _, i, run in sorted(self.queue):
            body = world.bodies[i]
            if run[0] == PART:
                k0, y0 = run[2], run[3]
                for sampled in self.samples:
                    if sampled[1] == i:     # its rows before s only
                        sampled[2] = sampled[2][:_rows_before(sampled, s, world.sample_every)]
                self._drop_written()
                run = (PART, self._part(body, k0, y0, s - k0, _samples(world, body, False)[0])[0])
            self._finish(i, s, run)
        self.queue = []

    def _part(self, body, k: int, y, n: int, samples: tuple) -> tuple:
        """A tumbling part's run from state ``y`` at step ``k``, up to ``n`` steps, computing
        ``samples`` (:func:`_samples`)."""
        world = self.world
        watch = body.watch          # None: no events to watch
        return runs.fly_part(y, k, world.h, n, body.p, rails_field(body), world.air_of(body), *body.drag,
                             world.schedule.rails_floor(body),
                             math.inf if watch is None else watch.liftoff_height(),
                             math.inf if watch is None or watch.in_orbit else ORBIT_PERIAPSIS_BOUND, body.mu,
                             math.inf, *samples, nbody_flag(body.p))


def _rows_before(run: list, s: int, every: int) -> int:
    """How many of a run's computed samples (an item of :attr:`_Window.samples`, a row per
    sample step from its first) are at steps before ``s``."""
    return min(len(run[2]), max(0, -(-(s - run[0]) // every)))


def _samples(world, body, record: bool = True) -> tuple:
    """``(samples, rows, shape)``: the telemetry samples of a compiled run of ``body`` (a
    vehicle's, ``samples`` for :meth:`~rocketsim.sim.vehicle_checks.VehicleChecks.fly_run`;
    a tumbling part's, for :func:`rocketsim.stepping.runs.fly_part`), the rows it fills and
    the shape to write them with; ``record`` with telemetry. Without telemetry the run
    makes only the finiteness test; away from Earth it returns at its first sample step
    (the world places the body in Python)."""
    if body.vehicle is None:
        sampler, shape = sampling.arguments(body, world.gmst0)
        length, whole = N_SAMPLE_RIGID, body.central == "earth"
    else:
        sampler, shape, length, whole = sampling.run_sampler(body, world.gmst0)
    record = record and world.telemetry is not None
    rows = np.empty((RUN_SAMPLES if record and whole else 0, length))
    return (world.sample_every, rows, record, sampler), rows, shape


def compile_runs_beside(world) -> None:
    """On a cold cache, queue the kernels of the world's vehicles with aerodynamics and checks
    for a second process to compile while this one compiles the first sample's
    (:meth:`rocketsim.sim.vehicle_checks.VehicleChecks.compile_beside`): their one-step
    advance and, without parachutes, their compiled runs; with a fairing, the runs its
    halves will tumble in (:func:`rocketsim.stepping.runs.fly_part`)."""
    for body in world.bodies:
        if body.vehicle is not None and body.checks is not None and body.watch is not None:
            body.checks.compile_beside(body, world.h,
                                       None if body.vehicle.parachutes else _samples(world, body)[0])
            if body.vehicle.has_fairing and field_of(body.p) is None:
                # its halves will tumble in compiled runs: a rigid part's state and parameters
                # (float arrays as the vehicle's), the same field and air
                compile_beside(runs.fly_part, (body.y[:N_STATE].copy(), 0, world.h, 1, body.p, rails_field(body),
                                               world.air_of(body), 1.0, 1.0, 1.0, math.inf,
                                               ORBIT_PERIAPSIS_BOUND, body.mu, math.inf, world.sample_every,
                                               np.empty((0, N_SAMPLE_RIGID)), True,
                                               sampling.part_arguments(body, world.gmst0), nbody_flag(body.p)))
