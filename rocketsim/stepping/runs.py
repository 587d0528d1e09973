"""Compiled runs of steps: a vehicle with aerodynamics flown many steps in one call.

In the air's reach the world steps a vehicle with aerodynamics one step at a
time, because after every step the checks (:class:`rocketsim.sim.vehicle_checks.VehicleChecks`)
and the flight events (:mod:`rocketsim.sim.flight_events`) look at its state, its
autopilot steers before every step, and a program waiting on a condition reads
it. :func:`fly_run` does all of that in one compiled call for as long as nothing
needs Python: each step is the autopilot's step (``steer_step``, when it steers
with the command it holds), the RK4 step (:func:`rocketsim.dynamics.rk4.step`)
and the checks' figures (:func:`~rocketsim.stepping.checked_step.step_figures`),
exactly as the world's one-step path computes them, followed by the tests that
decide whether the Python side would do anything at this step. The run returns
after the first step where it might (or after ``n_max`` steps), and the world
handles that step as it handles every step (:meth:`rocketsim.sim.world.World.advance`).
The telemetry samples of the steps before it are computed in the run (the
sampler's own :func:`rocketsim.stepping.sample_figures.figures`, into rows the world then
writes in order before it handles the last step), with the world's finiteness
test at each: a run goes on past sample steps.

The tests are conservative: wherever the test here is not exactly the Python
side's (a comparison of numbers that may differ in their last bits, or a
quantity not computed here) the run stops with a margin (:data:`MARGIN`, relative)
before the Python side's threshold, so the step goes to Python. What the Python
side carries from step to step is carried in and out (``carry``): the heat
shield's temperature (the same RK4 step of :func:`~rocketsim.vehicle.heating.advance_shield`),
whether the vehicle has been in the air since its last contact, and the
dynamic-pressure peak while max-Q is pending (the step of the peak; its state
``y_peak``, from which the world takes the exact figures). A run stops after a
step where

* the vehicle may have lifted off (its height near or past the liftoff height);
* the vehicle has touched down or gone below the ground (an impact), or comes
  within the airborne clearance of the ground before a touchdown (the Python side's
  test of a contact inside the step);
* a structural limit may be passed, or the heat shield's limit;
* max-Q may be reached or the peak's comparison is too close to call;
* a stage has run dry, the vehicle has left its launch rail, a solid motor's
  curve may have ended;
* an orbit may have been achieved (the periapsis bound of
  :func:`~rocketsim.sim.flight_events.periapsis_bound` past its threshold);
* the body may be out of the air's reach (the world's one-step rule no longer
  applies) or near a sphere of influence's watch radius (a handover);
* the program's compiled condition (:mod:`rocketsim.flight.conditions`) is true:
  reason :data:`CONDITION`, the program is due at the next step;
* at a telemetry sample step, the state may fail the world's finiteness test, or
  the rows for the samples are full.

``watch`` (the figures the tests compare with, slots ``W_*``) and ``carry``
(slots ``C_*``) are float arrays made by
:meth:`rocketsim.sim.vehicle_checks.VehicleChecks.fly_run`.

A tumbling part below its rails floor (a fairing half in the air) has only the
orbit test and the handover to watch: :func:`fly_part` flies it the same way,
:func:`~rocketsim.dynamics.free_body.free_step` by step, its samples computed on the
way as a vehicle's.

A rigid body coasting with nothing for Python (a spacecraft in orbit,
:mod:`rocketsim.sim.coast_runs`) is flown whole telemetry intervals at a time by
:func:`coast_run`, each interval's sample figures computed on the way.
"""

import math

import numpy as np

from rocketsim._jit import copy_into, njit
from rocketsim.atmosphere.table import TOP
from rocketsim.constants import DEG, G0
from rocketsim.dynamics.derivative import radial_height
from rocketsim.dynamics.free_body import free_step
from rocketsim.dynamics.rk4 import N_WORK, advance, near_ground, step_into
from rocketsim.flight.conditions import holds
from rocketsim.flight.readings import air_here
from rocketsim.flight.steering import steer_step
from rocketsim.frames.local import where_and_how_fast
from rocketsim.layout import P_POLAR_RADIUS, P_RADIUS, P_SPIN, Q, R, V, W
from rocketsim.stepping.checked_step import step_figures_into
from rocketsim.stepping.sample_figures import figures as figures_of
from rocketsim.vehicle.aero import A_GROUND, A_REACH
from rocketsim.vehicle.contact import axis_up
from rocketsim.vehicle.engines import S_DRY
from rocketsim.vehicle.heating import advance_shield
from rocketsim.vehicle.limits import bending_alpha
from rocketsim.vehicle.rail import RL_ON

MARGIN = 1e-9       # relative: a test here stops this much short of the Python side's threshold

# the slots of ``watch``
W_Q_ALPHA, W_AXIAL = 0, 1           # the structural limits (Pa deg, g0)
W_SHIELD = 2                        # 1: a heat shield, its figures in the next six slots
W_NOSE, W_K, W_CP, W_EMISSIVITY, W_AREA, W_HEAT_CAPACITY = 3, 4, 5, 6, 7, 8
W_HEAT_LIMIT = 9                    # K
W_WATCHED = 10                      # m over p[P_RADIUS]: the air's reach (the one-step rule)
W_MAX_Q = 11                        # 1: max-Q pending
W_MAX_Q_MIN, W_MAX_Q_DROP = 12, 13  # Pa, ratio (the events' definitions)
W_ORBIT = 14                        # m: the orbit test's periapsis bound (inf: not watched)
W_MU = 15                           # m^3/s^2
W_BURNOUT = 16                      # s: the next end of a solid motor's curve (inf: none)
W_SOI = 17                          # m: the sphere-of-influence watch radius (inf: none)
W_CLEARANCE = 18                    # m: the lowest contact point this high is in the air
W_TIP = 19                          # cosine of the tilt from the radial past which a landed body may
                                    # tip over (-inf: not landed)
W_LIFTOFF = 20                      # m over the ellipsoid (the readings' height): liftoff is reported
                                    # above it (inf: lifted off)
N_WATCH = 21
# the slots of ``carry``
C_TEMPERATURE, C_TOUCHED, C_PEAK_Q, C_PEAK_STEP = 0, 1, 2, 3
N_CARRY = 4
# why a run returned
LIMIT, PYTHON, CONDITION = 0, 1, 2


@njit(inline="always")
def _max_q_quiet(y, t, p, air, carry, watch):
    """``(quiet, q)``: whether the max-Q watch of the Python side surely does nothing at
    this state but carry a new peak (``q`` > the peak: the new peak's dynamic pressure,
    else nan), as :meth:`rocketsim.sim.flight_events.FlightEvents._max_q` decides on
    the view's air (the same compiled functions; the square of the airspeed may
    differ in its last bit, hence the margins)."""
    lat, lon, height, _, _ = where_and_how_fast(y[R:R + 3], y[V:V + 3], t, p[P_SPIN], p[P_RADIUS],
                                                p[P_POLAR_RADIUS])
    if abs(height - TOP) <= MARGIN * TOP:
        return False, math.nan
    if math.isnan(height) or height > TOP:
        return True, math.nan
    rho, _, _, _, _, v_air = air_here(*air, lat, lon, height, t, y[R:R + 3], y[V:V + 3], p[P_SPIN])
    speed = math.sqrt(v_air @ v_air)
    q = 0.5 * rho * (speed * speed)
    peak = carry[C_PEAK_Q]
    if math.isnan(peak):            # no peak yet: this is the first
        return True, q
    if q > peak * (1.0 + MARGIN):
        return True, q
    if q >= peak * (1.0 - MARGIN):
        return False, math.nan
    low = watch[W_MAX_Q_MIN]
    if peak < low * (1.0 - MARGIN):
        return True, math.nan
    if peak <= low * (1.0 + MARGIN):
        return False, math.nan
    return q >= watch[W_MAX_Q_DROP] * peak * (1.0 + MARGIN), math.nan


@njit(borrows=True)
def _checks_quiet(y, h, figures, carry, watch):
    """``(quiet, temperature, touched)``: whether the checks of the Python side
    (:meth:`~rocketsim.sim.vehicle_checks.VehicleChecks.after_step`) surely do
    nothing at this step but carry the shield's temperature and the contact flag
    (their new values)."""
    rho, air_temperature, speed, q, alpha, axial, lowest = figures
    temperature, touched = carry[C_TEMPERATURE], carry[C_TOUCHED]
    if q * bending_alpha(alpha) / DEG > watch[W_Q_ALPHA] * (1.0 - MARGIN) \
            or abs(axial) / G0 > watch[W_AXIAL] * (1.0 - MARGIN):
        return False, temperature, touched
    if watch[W_SHIELD] > 0.5 and rho > 0.0:
        temperature = advance_shield(temperature, h, rho, speed, air_temperature, watch[W_NOSE], watch[W_K],
                                     watch[W_CP], watch[W_EMISSIVITY], watch[W_AREA], watch[W_HEAT_CAPACITY])
        if not temperature <= watch[W_HEAT_LIMIT] * (1.0 - MARGIN):
            return False, temperature, touched
    if lowest > watch[W_CLEARANCE]:
        touched = 0.0
    elif touched < 0.5:             # a contact may be due (lowest <= 0 or reached inside the step)
        return False, temperature, touched
    elif axis_up(y) < watch[W_TIP]:
        return False, temperature, touched
    return True, temperature, touched


@njit(borrows=True)
def _events_quiet(y, t, p, veh, watch, dry, on_rail):
    """Whether the flight events other than max-Q surely do nothing at this state, nor
    the world's one-step rule and handover change: no stage newly dry (``dry``: the
    stages' flags at the run's start), still on the rail or off it as at the start
    (``on_rail``), before the next motor burn-out, below the orbit test's bound, in
    the air's reach, inside the sphere-of-influence watch radius."""
    for s in range(veh.stage.shape[0]):
        if veh.stage[s, S_DRY] != dry[s]:
            return False
    if veh.rail[RL_ON] != on_rail or t >= watch[W_BURNOUT] - MARGIN:
        return False
    if not _orbit_and_soi_quiet(y, p, watch[W_ORBIT], watch[W_MU], watch[W_SOI]):
        return False
    x, y_, z = y[R], y[R + 1], y[R + 2]
    return math.sqrt(x * x + y_ * y_ + z * z) - p[P_RADIUS] < watch[W_WATCHED] - MARGIN * p[P_RADIUS]


@njit(borrows=True)
def _orbit_and_soi_quiet(y, p, orbit_bound, mu, soi):
    """Whether the orbit test's periapsis bound (:func:`~rocketsim.sim.flight_events.periapsis_bound`,
    the same operations) stays below ``orbit_bound`` (m; inf: not watched) and the
    distance from the centre below the sphere-of-influence watch radius ``soi`` (m)."""
    x, y_, z, u, v, w = y[R], y[R + 1], y[R + 2], y[V], y[V + 1], y[V + 2]
    hx, hy, hz = y_ * w - z * v, z * u - x * w, x * v - y_ * u
    return (hx * hx + hy * hy + hz * hz) / mu <= orbit_bound * (1.0 - MARGIN) and \
        math.sqrt(x * x + y_ * y_ + z * z) < soi * (1.0 - MARGIN)


@njit
def _below(y, t, p, liftoff):
    """Whether state ``y`` at mission time ``t`` (s) is surely not past the liftoff height
    ``liftoff`` (m over the ellipsoid, the readings' height; inf: lifted off), with the
    margin of the readings' height against the one here."""
    if liftoff == math.inf:
        return True
    geodetic = where_and_how_fast(y[R:R + 3], y[V:V + 3], t, p[P_SPIN], p[P_RADIUS], p[P_POLAR_RADIUS])[2]
    return geodetic <= liftoff - MARGIN * p[P_RADIUS]


@njit(borrows=True)
def _surely_finite(y):
    """Whether the world's finiteness test (the sum of the state finite:
    :meth:`rocketsim.sim.world.World.check_finite`) surely passes on ``y``: every
    number under 1e300 in size, so no order of summing them can overflow."""
    for x in y:
        if not abs(x) < 1e300:
            return False
    return True


@njit(nogil=True)
def fly_part(y, k0, h, n_max, p, fp, air, area_mass, length, floor, liftoff, orbit_bound, mu, soi, every, rows,
             record, sampler, nbody=None):
    """Fly a tumbling part (:mod:`rocketsim.dynamics.free_body`: the field ``fp``, the air
    table ``air``, its area over mass and length) from state ``y`` at step ``k0`` for up
    to ``n_max`` steps of ``h`` s, as :func:`~rocketsim.dynamics.free_body.advance_free`
    flies it (``nbody`` as its), returning ``(y, steps taken, rows filled)`` after the
    first step that ends below the ground, above ``floor`` (m: its rails floor, sleep
    rails from the next step), near or above the liftoff height ``liftoff`` (m over the
    ellipsoid, the readings' height; inf: lifted off), past the orbit test's bound or
    the watch radius (see :func:`_orbit_and_soi_quiet`).

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
        if not (0.0 <= height < floor * (1.0 - MARGIN)) or not _orbit_and_soi_quiet(y, p, orbit_bound, mu, soi):
            return y, j, filled
        if not _below(y, (k0 + j) * h, p, liftoff):
            return y, j, filled
        if j < n_max and (k0 + j) % every == 0:
            if not _surely_finite(y) or (record and filled == rows.shape[0]):
                return y, j, filled
            if record:
                copy_into(rows[filled], 0, figures_of((k0 + j) * h, y, p, *sampler))
                filled += 1
    return y, n_max, filled


@njit(nogil=True)
def fly_run(y, k0, h, n_max, p, veh, in_flight, steer, code, fins, watch, carry, condition, every, rows, record,
            sampler, nbody=None):
    """Fly the staged vehicle with aerodynamics ``veh`` (its arrays; ``in_flight`` the same
    without contact points) from state ``y`` at step ``k0`` (of ``h`` s) for up to
    ``n_max`` steps, returning after the first step where the Python side may have
    something to do (see the module). With ``steer``
    the autopilot's step runs before each step, as
    :func:`~rocketsim.stepping.checked_step.advance_checked` runs it (the command
    ``code``, the grid fins when ``fins``); ``condition`` is the program's compiled
    condition (no rows: none). ``carry`` is updated in place to its values before
    the last step's checks. ``nbody`` as :func:`rocketsim.dynamics.rk4.step`'s.

    At each telemetry sample step (a multiple of ``every``) before the last step the
    world's finiteness test is made (:func:`_surely_finite`) and, with ``record``, the
    sample's figures (:func:`rocketsim.stepping.sample_figures.figures` of the state, its time,
    the arguments ``sampler`` and the shield's temperature after the step) go to the
    next row of ``rows``; the run returns at a sample step where the test may fail or
    (with ``record``) the rows are full, leaving that step and its sample to the world.

    Returns ``(y, y_before, steps taken, figures, reason, y_peak, rows filled)``: the
    state after the last step and before it, the checks' figures at the last state
    (:func:`step_figures`, the flight loads without contact forces), :data:`LIMIT`,
    :data:`PYTHON` or :data:`CONDITION`, the state of the new dynamic-pressure peak
    (``carry[C_PEAK_STEP]`` steps into the run; 0: none), and the samples in ``rows``.
    """
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
            steer_step(veh, y, p, t0, t0, y[R:R + 3], y[V:V + 3], y[Q:Q + 4], y[W:W + 3], math.nan, veh.air,
                       code, fins, False)
        y = np.empty(n)
        step_into(y, k, work, before, t0, h, p, veh, nbody)
        t = (k0 + j) * h
        # the flight loads without the contact forces: out of the contact points' reach the
        # derivative adds none, within it the arrays without them (as the checks compute them)
        figures = step_figures_into(dy, t, y, p, in_flight if near_ground(y, p, reach) else veh,
                                    veh.aero.contact, nbody)
        if condition.shape[0] > 0 and holds(condition, t, y, p):
            return y, before, j, figures, CONDITION, y_peak, filled
        if j == n_max or radial_height(y, p) < ground:
            return y, before, j, figures, LIMIT if j == n_max else PYTHON, y_peak, filled
        quiet, temperature, touched = _checks_quiet(y, h, figures, carry, watch)
        if not quiet or not _events_quiet(y, t, p, veh, watch, dry, on_rail) \
                or not _below(y, t, p, watch[W_LIFTOFF]):
            return y, before, j, figures, PYTHON, y_peak, filled
        peak = math.nan
        if watch[W_MAX_Q] > 0.5:
            quiet, peak = _max_q_quiet(y, t, p, veh.air, carry, watch)
            if not quiet:
                return y, before, j, figures, PYTHON, y_peak, filled
        if (k0 + j) % every == 0:
            if not _surely_finite(y):
                return y, before, j, figures, PYTHON, y_peak, filled
            if record:
                if filled == rows.shape[0]:
                    return y, before, j, figures, LIMIT, y_peak, filled
                copy_into(rows[filled], 0, figures_of(t, y, p, *sampler, temperature))
                filled += 1
        carry[C_TEMPERATURE], carry[C_TOUCHED] = temperature, touched
        if not math.isnan(peak):
            carry[C_PEAK_Q], carry[C_PEAK_STEP] = peak, j
            y_peak = y


@njit(nogil=True)
def coast_run(y, k0, h, every, m, p, nbody, rows, fixed):
    """Fly a rigid body (state ``y``, parameters ``p``, ``nbody`` as
    :func:`~rocketsim.dynamics.rk4.advance`'s) ``m`` intervals of ``every`` steps of
    ``h`` s from step ``k0``, each as the world flies it, filling row ``j`` of ``rows``
    (while ``j < rows.shape[0]``) with :func:`~rocketsim.stepping.sample_figures.figures` at the
    end of interval ``j`` (``fixed``: its arguments after the state and parameters).
    Returns ``(y, intervals flown)``: fewer than ``m`` after an interval whose state is
    not finite (its row not filled)."""
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
