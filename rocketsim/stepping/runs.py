"""Compiled runs of steps: a body flown many steps in one call, returning where Python may act.

In the air's reach the world steps a vehicle with aerodynamics one step at a
time, because after every step the checks (:class:`rocketsim.sim.vehicle_checks.VehicleChecks`)
and the flight events (:mod:`rocketsim.sim.flight_events`) look at its state, its
autopilot steers before every step, and a program waiting on a condition reads
it. :func:`fly_run` does all of that in one compiled call for as long as nothing
needs Python: each step is the autopilot's step (``steer_step``, when it steers
with the command it holds), the RK4 step (:func:`rocketsim.dynamics.rk4.step`)
and the checks' figures (:func:`~rocketsim.stepping.checked_step.step_figures`),
exactly as the world's one-step path computes them, followed by the tests that
decide whether the Python side would do anything at this step
(:mod:`rocketsim.stepping.quiet`, the Python side's twins). The run returns
after the first step where it might (or after ``n_max`` steps), or where the
program's compiled condition (:func:`rocketsim.flight.conditions.holds_on`) is true
(reason :data:`CONDITION`: the program is due at the next step), and the world
handles that step as it handles every step (:meth:`rocketsim.sim.world.World.advance`).
The telemetry samples of the steps before it are computed in the run (the
sampler's own :func:`rocketsim.stepping.sample_figures.figures`, into rows the world then
writes in order before it handles the last step), with the world's finiteness
test at each: a run goes on past sample steps, and returns at one where the rows
for the samples are full. A new dynamic-pressure peak found in the run comes
back with its state (``y_peak``), from which the world takes the exact figures.

A tumbling part below its rails floor (a fairing half in the air) has only its
liftoff, the orbit test and its impact to watch: :func:`fly_part` flies it the
same way, :func:`~rocketsim.dynamics.free_body.free_step` by step, its samples
computed on the way as a vehicle's.

A rigid body coasting with nothing for Python (a spacecraft in orbit,
:mod:`rocketsim.sim.coast_runs`) is flown whole telemetry intervals at a time by
:func:`coast_run`, each interval's sample figures computed on the way.
"""

import ctypes
import math
import sys

import numpy as np

from rocketsim.jit import copy_into, njit
from rocketsim.dynamics.derivative import radial_height
from rocketsim.dynamics.free_body import free_step
from rocketsim.dynamics.rk4 import N_WORK, advance, near_ground, step_into
from rocketsim.flight.conditions import holds_on
from rocketsim.flight.navigation import ANSWER, hand_into
from rocketsim.flight.steering import steer_on_estimate
from rocketsim.stepping.checked_step import step_figures_into
from rocketsim.stepping.quiet import (CARRY_PEAK_Q, CARRY_PEAK_STEP, CARRY_TEMPERATURE, CARRY_TOUCHED, MARGIN,
                                      WATCH_LIFTOFF, WATCH_MAX_Q, below_liftoff, checks_quiet, events_quiet,
                                      max_q_quiet, orbit_and_soi_quiet, surely_finite)
from rocketsim.stepping.sample_figures import figures as figures_of
from rocketsim.vehicle.aero import A_GROUND, A_REACH
from rocketsim.vehicle.engines import S_DRY
from rocketsim.vehicle.rail import RL_ON

# why a run returned (QUIET: where the Python side asked, after a step with nothing for it)
LIMIT, PYTHON, CONDITION, QUIET = 0, 1, 2, 3
# what fly_run calls to ask the Python side after a step, ask(k): a C function pointer to a
# Python function (ctypes: the GIL taken for the call alone, no object handed over but the
# step's number; what it reads is in the run's hand-over buffer, rocketsim.flight.navigation.hand_into)
ASK = ctypes.CFUNCTYPE(None, ctypes.c_int64)


def _nobody(k: int) -> None:
    """What a run that asks nobody is given to call (it never calls it)."""


NOBODY = ASK(_nobody)


class asking:
    """Context manager: ``ask``, the :data:`ASK` a :func:`fly_run` calls ``question(k)``
    through after step ``k`` (a program's condition read in Python). An exception ``question``
    raises there (the program's budget, Ctrl-C) cannot cross the compiled code: ctypes
    hands it to ``sys.unraisablehook`` and the run, finding no answer, ends at that step;
    the hook set while inside keeps it, and it is raised on leaving, where the run has
    returned. Exceptions of other sources go to the hook set before."""

    def __init__(self, question):
        self.question = question
        self.ask = ASK(question)
        self.failed: BaseException | None = None
        self._previous = None
        self._hook = self._kept         # one bound method: the hook set is this object

    def __enter__(self):
        self._previous = sys.unraisablehook
        sys.unraisablehook = self._hook
        return self

    def _kept(self, unraisable) -> None:
        if unraisable.object is self.question and self.failed is None:
            self.failed = unraisable.exc_value
        else:
            self._previous(unraisable)

    def __exit__(self, kind, error, traceback) -> bool:
        if sys.unraisablehook is self._hook:       # another thread's run may have set its own since
            sys.unraisablehook = self._previous
        if self.failed is not None and error is None:
            raise self.failed
        return False


@njit(nogil=True)
def fly_part(y, k0, h, n_max, p, fp, air, area_mass, length, floor, liftoff, orbit_bound, mu, soi, every, rows,
             record, sampler, nbody=None):
    """Fly a tumbling part (:mod:`rocketsim.dynamics.free_body`: the field ``fp``, the air
    table ``air``, its area over mass and length) from state ``y`` at step ``k0`` for up
    to ``n_max`` steps of ``h`` s, as :func:`~rocketsim.dynamics.free_body.advance_free`
    flies it (``nbody`` as its), returning ``(y, steps taken, rows filled)`` after the
    first step that ends below the ground (the impact of
    :meth:`~rocketsim.sim.world.World.after_advance`), above ``floor`` (m: its rails
    floor, sleep rails from the next step), near or above the liftoff height ``liftoff``
    (m over the ellipsoid, the readings' height; inf: lifted off), past the orbit test's
    bound or the watch radius (:func:`~rocketsim.stepping.quiet.orbit_and_soi_quiet`).

    At each telemetry sample step (a multiple of ``every``) before the last step, as
    :func:`fly_run` does: the world's finiteness test and, with ``record``, the sample's
    figures (:func:`rocketsim.stepping.sample_figures.figures` with the arguments ``sampler``) in
    the next row of ``rows``, returning at that step where the test may fail or the
    rows are full."""
    fp = fp.copy()
    filled = 0
    for j in range(1, n_max + 1):
        y = free_step(y, (k0 + j - 1) * h, h, p, fp, air, area_mass, length, nbody)
        height = radial_height(y, p)
        if not (0.0 <= height < floor * (1.0 - MARGIN)) or not orbit_and_soi_quiet(y, p, orbit_bound, mu, soi):
            return y, j, filled
        if not below_liftoff(y, (k0 + j) * h, p, liftoff):
            return y, j, filled
        if j < n_max and (k0 + j) % every == 0:
            if not surely_finite(y) or (record and filled == rows.shape[0]):
                return y, j, filled
            if record:
                copy_into(rows[filled], 0, figures_of((k0 + j) * h, y, p, *sampler))
                filled += 1
    return y, n_max, filled


@njit(nogil=True)
def fly_run(y, k0, h, n_max, p, veh, in_flight, steer, code, fins, errors, j0, gauges, watch, carry, condition,
            asks, ask, handed, every, rows, record, sampler, nbody=None):
    """Fly the staged vehicle with aerodynamics ``veh`` (its arrays; ``in_flight`` the same
    without contact points) from state ``y`` at step ``k0`` (of ``h`` s) for up to
    ``n_max`` steps, returning after the first step where the Python side may have
    something to do (see the module): its tests of :mod:`rocketsim.stepping.quiet`, and
    a step that ends below the vehicle's ground (the impact of
    :meth:`~rocketsim.sim.world.World.after_advance`). With ``steer`` the autopilot's
    step runs before each step, as
    :func:`~rocketsim.stepping.checked_step.advance_checked` runs it (the command
    ``code``, the grid fins when ``fins``); ``condition`` is the program's compiled
    condition (no rows: none). Both read the navigation estimate: the truth, or with
    the sensors' ``errors`` (:meth:`rocketsim.flight.sensors.Sensors.run_errors`) those
    of row ``j0 + i`` at step ``k0 + i`` (the run takes at most ``len(errors) - 1 - j0``
    steps), the tanks' gauges from column ``gauges`` on (the state slot of the
    vehicle's first tank). ``carry`` is updated in place to its values before the
    last step's checks. ``nbody`` as :func:`rocketsim.dynamics.rk4.step`'s.

    With ``asks`` the Python side is asked after every step ``k`` but the last that it
    has nothing to do at (a program's condition read in Python: its checks' state,
    ``carry``, and sample as after that step) whether the run ends there: the step's
    state goes to the buffer ``handed`` with its navigation estimate
    (:func:`rocketsim.flight.navigation.hand_into`), then ``ask(k)`` (an :data:`ASK`)
    is called, which answers in the buffer's answer slot; anything but 0 (no answer:
    the call failed) ends the run there, with reason :data:`QUIET`.

    At each telemetry sample step (a multiple of ``every``) before the last step the
    world's finiteness test is made (:func:`~rocketsim.stepping.quiet.surely_finite`) and,
    with ``record``, the sample's figures (:func:`rocketsim.stepping.sample_figures.figures`
    of the state, its time, the arguments ``sampler`` and the shield's temperature after
    the step) go to the next row of ``rows``; the run returns at a sample step where the test may fail or
    (with ``record``) the rows are full, leaving that step and its sample to the world.

    Returns ``(y, y_before, steps taken, figures, reason, y_peak, rows filled)``: the
    state after the last step and before it, the checks' figures at the last state
    (:func:`~rocketsim.stepping.checked_step.step_figures`, the flight loads without
    contact forces), :data:`LIMIT`,
    :data:`PYTHON`, :data:`CONDITION` or :data:`QUIET`, the state of the new dynamic-pressure peak
    (``carry[CARRY_PEAK_STEP]`` steps into the run; 0: none), and the samples in ``rows``.
    """
    if errors.shape[0] > 0:
        n_max = min(n_max, errors.shape[0] - 1 - j0)
    dry = veh.stage[:, S_DRY].copy()
    on_rail = veh.rail[RL_ON]
    reach = veh.aero.ref[A_REACH] + veh.aero.ref[A_GROUND]
    ground = veh.aero.ref[A_GROUND]
    y_peak = y
    j = 0
    filled = 0
    n = y.shape[0]
    k, work = np.empty((4, n)), np.empty((N_WORK, n))     # the steps' stages and parts
    dy = np.empty(n)                                        # the checks' derivative
    while True:
        j += 1
        before = y
        t0 = (k0 + j - 1) * h
        if steer:
            steer_on_estimate(veh, y, p, t0, errors, j0 + j - 1, code, fins)
        y = np.empty(n)
        step_into(y, k, work, before, t0, h, p, veh, nbody)
        t = (k0 + j) * h
        # the flight loads without the contact forces: out of the contact points' reach the
        # derivative adds none, within it the arrays without them (as the checks compute them)
        figures = step_figures_into(dy, t, y, p, in_flight if near_ground(y, p, reach) else veh,
                                    veh.aero.contact, nbody)
        if condition.shape[0] > 0 and holds_on(condition, t, y, p, errors, j0 + j, gauges):
            return y, before, j, figures, CONDITION, y_peak, filled
        if j == n_max or radial_height(y, p) < ground:
            return y, before, j, figures, LIMIT if j == n_max else PYTHON, y_peak, filled
        quiet, temperature, touched = checks_quiet(y, h, figures, carry, watch)
        if not quiet or not events_quiet(y, t, p, veh, watch, dry, on_rail) \
                or not below_liftoff(y, t, p, watch[WATCH_LIFTOFF]):
            return y, before, j, figures, PYTHON, y_peak, filled
        peak = math.nan
        if watch[WATCH_MAX_Q] > 0.5:
            quiet, peak = max_q_quiet(y, t, p, veh.air, carry, watch)
            if not quiet:
                return y, before, j, figures, PYTHON, y_peak, filled
        if (k0 + j) % every == 0:
            if not surely_finite(y):
                return y, before, j, figures, PYTHON, y_peak, filled
            if record:
                if filled == rows.shape[0]:
                    return y, before, j, figures, LIMIT, y_peak, filled
                copy_into(rows[filled], 0, figures_of(t, y, p, *sampler, temperature))
                filled += 1
        carry[CARRY_TEMPERATURE], carry[CARRY_TOUCHED] = temperature, touched
        if not math.isnan(peak):
            carry[CARRY_PEAK_Q], carry[CARRY_PEAK_STEP] = peak, j
            y_peak = y
        if asks:
            hand_into(handed, y, errors, j0 + j, t, p)
            ask(k0 + j)
            if handed[ANSWER] != 0.0:
                return y, before, j, figures, QUIET, y_peak, filled


@njit(nogil=True)
def coast_run(y, k0, h, every, m, p, nbody, rows, fixed):
    """Fly a rigid body (state ``y``, parameters ``p``, ``nbody`` as
    :func:`~rocketsim.dynamics.rk4.advance`'s) ``m`` intervals of ``every`` steps of
    ``h`` s from step ``k0``, each as the world flies it, filling row ``j`` of ``rows``
    (while ``j < rows.shape[0]``) with :func:`~rocketsim.stepping.sample_figures.figures` at the
    end of interval ``j`` (``fixed``: its arguments after the state and parameters).
    Returns ``(y, intervals flown)``: fewer than ``m`` after an interval whose state is
    not finite (its row not filled), where the world's finiteness test
    (:meth:`~rocketsim.sim.world.World.check_finite`) raises its error."""
    for j in range(m):
        k = k0 + j * every
        y, _ = advance(y, k, h, every, p, None, nbody)
        for x in y:
            if not math.isfinite(x):
                return y, j + 1
        if j < rows.shape[0]:
            row = figures_of((k + every) * h, y, p, *fixed)
            for c in range(row.shape[0]):   # a loop: no broadcast (and its error message) to compile
                rows[j, c] = row[c]
    return y, m
