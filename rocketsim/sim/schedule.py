"""How the world advances its bodies: how many steps at once, and with which integrator.

Each batch of steps is as long as nothing needs deciding: no program due, no
telemetry sample due, no autopilot to run, no check that runs every step.
Within a batch a body is advanced by one of four integrators
(:meth:`rocketsim.sim.world.World.advance`):

* **cruise rails** (:mod:`rocketsim.dynamics.cruise`) while ``fc.cruise`` allows
  them and the body is far from every body;
* **sleep rails** (:mod:`rocketsim.dynamics.rails`) for a body nobody steers
  (or whose held attitude has settled) that coasts above the rails floor, its
  attitude the exact torque-free (or held) one;
* the tumbling part's point-mass drag (:mod:`rocketsim.dynamics.free_body`);
* RK4 (:mod:`rocketsim.dynamics.rk4`), sub-stepped near the ground, with a
  vehicle's checks folded in (:mod:`rocketsim.sim.vehicle_checks`).

A batch ends at the next telemetry sample; where every flying body coasts
alone (:meth:`Schedule.coasts_alone`, a spacecraft in orbit) the world flies
many batches and their samples in one compiled call (:mod:`rocketsim.sim.coast_runs`).

Every choice here is bit-neutral: the same step on rails or awake flies the
same orbit to the bit (docs/physics.md#sleep-rails).
"""

from __future__ import annotations

import math
import numpy as np

from rocketsim.atmosphere.table import TOP
from rocketsim.constants import G0
from rocketsim.dynamics.cruise import DONE, plan_step
from rocketsim.dynamics.derivative import radial_height
from rocketsim.dynamics.nbody import make_field
from rocketsim.dynamics.rails import hold_offsets, rails_floor
from rocketsim.dynamics.third_bodies import field_of
from rocketsim.flight.steering import OMEGA_N, ZETA
from rocketsim.layout import P_IXX, P_IYY, P_IZZ, V, W
from rocketsim.sim.body import Body
from rocketsim.vehicle.engines import C_ON, E_TAIL

# parking-orbit rails about Earth: Kepler + J2, no third bodies; a rigid body with
# drag goes on them only above the air (free_body flies it below)
RAILS_FIELD = make_field("earth", 0.0, bodies=())
# a held attitude goes on sleep rails once the autopilot has settled on it:
HOLD_SETTLED_ERROR = math.radians(0.01)    # rad, attitude off the command (less the law's lag)
HOLD_SETTLED_RATE = 1e-4                   # rad/s, every body rate off the frame's turn rate
# telemetry samples a window of several bodies spans at most: the world reports its progress
# at its end (1 s at 10 Hz), the bodies' compiled runs computing the samples between
WINDOW_SAMPLES = 10


class Schedule:
    """The batch and integrator decisions of one :class:`~rocketsim.sim.world.World`
    (its step ``h``, step count ``k``, sample rate and bodies are read from it)."""

    def __init__(self, world):
        self.world = world
        self.cruise_batch = False           # the last batch was one cruise step
        self._cruise_field = None           # Earth's point mass and J2, built on first use

    def batch_length(self) -> int:
        """Steps that can be taken before anything needs deciding."""
        world = self.world
        self.cruise_batch = False
        if any(b.flying and b.checks is not None and b.checks.every_step(b) for b in world.bodies):
            return 1                        # limits, heating and touchdown are checked every step
        if any(b.flying and b.attitude_command is not None and not self.holding(b) for b in world.bodies):
            return 1                        # the autopilot runs once per step
        n = min(world.n_steps - world.k, world.sample_every - world.k % world.sample_every)
        flying = [b for b in world.bodies if b.flying]
        cruise = [self.cruise_steps(b) for b in flying if self.cruising(b)]
        self.cruise_batch = len(cruise) == len(flying) and all(c > 0 for c in cruise)
        if self.cruise_batch:
            # every body cruises: one cruise step per batch, sampled at its end
            n = min([world.n_steps - world.k] + cruise)
        for body in world.bodies:
            runner = body.runner
            if not body.flying or runner is None or runner.finished:
                continue
            if runner.waiting_on_predicate:
                return 1
            n = min(n, max(1, self.wake_steps(runner)))
        return max(1, n)

    def wake_steps(self, runner) -> int:
        """Steps from now to the wake-up of the program of ``runner``."""
        return math.ceil((runner.wake_time() - self.world.t) / self.world.h - 1e-9)

    def one_step(self, body: Body) -> bool:
        """Whether the world's loop steps one step at a time for ``body``'s sake (as
        :meth:`batch_length` decides): its checks run every step, its autopilot steers
        every step, or its program waits on a condition."""
        runner = body.runner
        return body.flying and (
            (body.checks is not None and body.checks.every_step(body))
            or (body.attitude_command is not None and not self.holding(body))
            or (runner is not None and not runner.finished and runner.waiting_on_predicate))

    def window_length(self) -> int:
        """Steps before the world's loop must decide anything while it steps one step at
        a time: to the end, and while more than one body flies to the next multiple of
        :data:`WINDOW_SAMPLES` telemetry samples (where the world reports its progress
        with every body at the same step); 1 while a body cruises. Within them the bodies
        are flown in compiled runs where nothing needs Python, and the programs run at
        their wake-ups (:mod:`rocketsim.sim.window`: a vehicle's runs compute its samples
        on the way; a program's condition read in Python is read at every step)."""
        world = self.world
        flying = [body for body in world.bodies if body.flying]
        n = world.n_steps - world.k
        if len(flying) > 1:
            span = WINDOW_SAMPLES * world.sample_every
            n = min(n, span - world.k % span)
        if any(self.cruising(body) for body in flying):
            return 1
        return n

    @staticmethod
    def coasts_alone(body: Body, seconds: float) -> bool:
        """Whether none of the next ``seconds`` (s) of ``body``'s steps has anything for
        Python: a rigid body with no drag, no program running, no n-body field (no
        handover), no event to watch (none, or lifted off and in orbit), and the ground
        out of its reach (at its speed and twice the surface gravity: no impact to
        record out of turn)."""
        runner, watch = body.runner, body.watch
        if body.vehicle is not None or body.drag is not None or field_of(body.p) is not None \
                or (runner is not None and not runner.finished) \
                or (watch is not None and not (watch.lifted and watch.in_orbit)):
            return False
        v = body.y[V:V + 3]
        return radial_height(body.y, body.p) > math.sqrt(v @ v) * seconds + G0 * seconds * seconds

    def on_rails(self, body: Body) -> bool:
        """Sleep rails for a body nobody flies or whose program sleeps beyond the next
        step, axisymmetric (the exact torque-free attitude), above the rails floor, with
        no attitude command: a rigid body, or a staged vehicle coasting
        (:meth:`coasting`); or holding an attitude once settled (:meth:`holding`)."""
        if body.attitude_command is not None:
            return self.holding(body)
        return (self.asleep(body) and self.coasting(body)
                and radial_height(body.y, body.p) > self.rails_floor(body))

    def rails_floor(self, body: Body) -> float:
        """Height (m) below which ``body`` cannot stay on rails: :func:`rails_floor`, or
        the air's top (600 km) for a tumbling rigid body about a body with air, Earth or
        Mars (its drag is flown awake, :mod:`rocketsim.dynamics.free_body`)."""
        if body.drag is not None and body.central in ("earth", "mars"):
            return TOP
        return rails_floor(body.central)

    def asleep(self, body: Body) -> bool:
        """Nobody flies ``body`` or its program sleeps beyond the next step."""
        runner = body.runner
        world = self.world
        return runner is None or runner.finished or (
            not runner.waiting_on_predicate and runner.wake_time() - world.t > world.h * (1 + 1e-9))

    def holding(self, body: Body) -> bool:
        """Sleep rails for a held attitude: ``body`` is asleep (:meth:`asleep`), coasts
        but for the autopilot's own RCS (:meth:`coasting`; the RCS stops on rails), is
        above the rails floor, and the autopilot has settled on its command
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
        if command is None or not (self.coasting(body, rcs_free=True) and self.asleep(body)
                                   and radial_height(body.y, body.p) > rails_floor(body.central)):
            return False
        error, turn = hold_offsets(command.code, body.y, body.t, self.world.h, body.p)
        lagging = error - (2.0 * ZETA / OMEGA_N) * turn
        return (min(math.sqrt(error @ error), math.sqrt(lagging @ lagging)) < HOLD_SETTLED_ERROR
                and float(np.max(np.abs(body.y[W:W + 3] - turn))) < HOLD_SETTLED_RATE)

    @staticmethod
    def coasting(body: Body, rcs_free: bool = False) -> bool:
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
        return bool(inertia(body)[1] == vehicle.mass_properties(body.y)[4])

    def cruising(self, body: Body) -> bool:
        """fc.cruise allows cruise rails now (they run wherever no shell is near:
        a body inside one flies 20 ms steps and cruises again once clear)."""
        return body.cruise_until > self.world.t and body.attitude_command is None

    def cruise_steps(self, body: Body) -> int:
        """Flight-model steps of ``body``'s next cruise step (0: it cannot cruise here)."""
        world = self.world
        k_end = world.k + math.ceil((body.cruise_until - world.t) / world.h - 1e-9)
        steps, _, reason = plan_step(body.y, world.k, world.h, k_end, body.p, self.cruise_field(body))
        return steps if reason == DONE else 0

    def cruise_field(self, body: Body) -> np.ndarray:
        """The field cruise rails integrate: the awake flight's own (the n-body field
        ``body`` carries, or Earth's point mass and J2 in the mission's ECI)."""
        fp = field_of(body.p)
        if fp is not None:
            return fp
        if self._cruise_field is None:
            self._cruise_field = make_field("earth", self.world.epoch.jd_tt(), bodies=())
        return self._cruise_field


def rails_field(body: Body) -> np.ndarray:
    """The field of sleep rails: the n-body field the body carries (so a sleeping
    body follows the awake path to the bit), else Kepler + J2 about Earth."""
    fp = field_of(body.p)
    return RAILS_FIELD if fp is None else fp


def inertia(body: Body) -> np.ndarray:
    """``(I_xx, I_t, I_t)`` kg m^2 of the torque-free attitude on rails (a staged
    vehicle's from the propellant it carries)."""
    if body.vehicle is None:
        return body.p[P_IXX:P_IZZ + 1]
    _, _, ixx, iyy, _ = body.vehicle.mass_properties(body.y)
    return np.array((ixx, iyy, iyy))
