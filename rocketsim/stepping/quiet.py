"""The compiled twins of the Python side's decisions after a step: tests that it surely does nothing.

After every step of a body the Python side may act: a vehicle's checks
(:meth:`rocketsim.sim.vehicle_checks.VehicleChecks.after_step`), the flight
events (:meth:`rocketsim.sim.flight_events.FlightEvents.after_step`), the
handover (:func:`rocketsim.sim.handover.watch_soi`), the impact
(:meth:`rocketsim.sim.world.World.after_advance`), and at a telemetry sample the
finiteness test (:meth:`rocketsim.sim.world.World.check_finite`). A compiled run
(:mod:`rocketsim.stepping.runs`) flies on past a step only where the tests here
say that none of them would do anything there but carry what it carries from
step to step. Each test names the Python decision it mirrors;
:data:`rocketsim.stepping.twins.TWINS` lists every decision of the Python side
with its twin in each run, or why that run needs none.

The tests are conservative: wherever a test here is not exactly the Python
side's (a comparison of numbers that may differ in their last bits, or a
quantity not computed here) it fails with a margin (:data:`MARGIN`, relative)
before the Python side's threshold, so the step goes to Python. What the Python
side carries from step to step is carried in and out (``carry``): the heat
shield's temperature (the same RK4 step of :func:`~rocketsim.vehicle.heating.advance_shield`),
whether the vehicle has been in the air since its last contact, and the
dynamic-pressure peak while max-Q is pending (the step of the peak). The tests
fail after a step where

* the vehicle may have lifted off (its height near or past the liftoff height);
* the vehicle has touched down, or comes within the airborne clearance of the
  ground before a touchdown (the Python side's test of a contact inside the step),
  or a landed vehicle may be tipping over;
* a structural limit may be passed, or the heat shield's limit;
* max-Q may be reached or the peak's comparison is too close to call;
* a stage has run dry, the vehicle has left its launch rail, a solid motor's
  curve may have ended;
* an orbit may have been achieved (the periapsis bound of
  :func:`~rocketsim.sim.flight_events.periapsis_bound` past its threshold);
* the body may be out of the air's reach (the world's one-step rule no longer
  applies) or near a sphere of influence's watch radius (a handover);
* at a telemetry sample step, the state may fail the world's finiteness test.

``watch`` (the figures the tests compare with, slots ``WATCH_*``) and ``carry``
(slots ``CARRY_*``) are float arrays made by
:meth:`rocketsim.sim.vehicle_checks.VehicleChecks.fly_run` (the flight events
fill their slots of ``watch``: :meth:`rocketsim.sim.flight_events.FlightEvents.run_watch`).
"""

import math

from rocketsim.jit import njit
from rocketsim.atmosphere.table import TOP
from rocketsim.constants import DEG, G0
from rocketsim.flight.readings import air_here
from rocketsim.frames.local import where_and_how_fast
from rocketsim.layout import P_POLAR_RADIUS, P_RADIUS, P_SPIN, R, V
from rocketsim.vehicle.contact import axis_up
from rocketsim.vehicle.engines import S_DRY
from rocketsim.vehicle.heating import advance_shield
from rocketsim.vehicle.limits import bending_alpha
from rocketsim.vehicle.rail import RL_ON

MARGIN = 1e-9       # relative: a test here fails this much short of the Python side's threshold

# the slots of ``watch``
WATCH_Q_ALPHA, WATCH_AXIAL = 0, 1       # the structural limits (Pa deg, g0)
WATCH_SHIELD = 2                        # 1: a heat shield, its figures in the next six slots
WATCH_NOSE, WATCH_K, WATCH_CP, WATCH_EMISSIVITY, WATCH_AREA, WATCH_HEAT_CAPACITY = 3, 4, 5, 6, 7, 8
WATCH_HEAT_LIMIT = 9                    # K
WATCH_REACH = 10                        # m over p[P_RADIUS]: the air's reach (the one-step rule)
WATCH_MAX_Q = 11                        # 1: max-Q pending
WATCH_MAX_Q_MIN, WATCH_MAX_Q_DROP = 12, 13  # Pa, ratio (the events' definitions)
WATCH_ORBIT = 14                        # m: the orbit test's periapsis bound (inf: not watched)
WATCH_MU = 15                           # m^3/s^2
WATCH_BURNOUT = 16                      # s: the next end of a solid motor's curve (inf: none)
WATCH_SOI = 17                          # m: the sphere-of-influence watch radius (inf: none)
WATCH_CLEARANCE = 18                    # m: the lowest contact point this high is in the air
WATCH_TIP = 19                          # cosine of the tilt from the radial past which a landed body may
                                        # tip over (-inf: not landed)
WATCH_LIFTOFF = 20                      # m over the ellipsoid (the readings' height): liftoff is reported
                                        # above it (inf: lifted off)
N_WATCH = 21
# the slots of ``carry``
CARRY_TEMPERATURE, CARRY_TOUCHED, CARRY_PEAK_Q, CARRY_PEAK_STEP = 0, 1, 2, 3
N_CARRY = 4


@njit(inline="always")
def max_q_quiet(y, t, p, air, carry, watch):
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
    peak = carry[CARRY_PEAK_Q]
    if math.isnan(peak):            # no peak yet: this is the first
        return True, q
    if q > peak * (1.0 + MARGIN):
        return True, q
    if q >= peak * (1.0 - MARGIN):
        return False, math.nan
    low = watch[WATCH_MAX_Q_MIN]
    if peak < low * (1.0 - MARGIN):
        return True, math.nan
    if peak <= low * (1.0 + MARGIN):
        return False, math.nan
    return q >= watch[WATCH_MAX_Q_DROP] * peak * (1.0 + MARGIN), math.nan


@njit(borrows=True)
def checks_quiet(y, h, figures, carry, watch):
    """``(quiet, temperature, touched)``: whether the checks of the Python side surely
    do nothing at this step but carry the shield's temperature and the contact flag
    (their new values): the breakup, the touchdown and the tip-over of
    :meth:`~rocketsim.sim.vehicle_checks.VehicleChecks.after_step`, the heat shield's
    failure of :meth:`~rocketsim.sim.vehicle_checks.VehicleChecks._heat`, on the
    figures ``figures`` of :func:`~rocketsim.stepping.checked_step.step_figures`."""
    rho, air_temperature, speed, q, alpha, axial, lowest = figures
    temperature, touched = carry[CARRY_TEMPERATURE], carry[CARRY_TOUCHED]
    if q * bending_alpha(alpha) / DEG > watch[WATCH_Q_ALPHA] * (1.0 - MARGIN) \
            or abs(axial) / G0 > watch[WATCH_AXIAL] * (1.0 - MARGIN):
        return False, temperature, touched
    if watch[WATCH_SHIELD] > 0.5 and rho > 0.0:
        temperature = advance_shield(temperature, h, rho, speed, air_temperature, watch[WATCH_NOSE],
                                     watch[WATCH_K], watch[WATCH_CP], watch[WATCH_EMISSIVITY], watch[WATCH_AREA],
                                     watch[WATCH_HEAT_CAPACITY])
        if not temperature <= watch[WATCH_HEAT_LIMIT] * (1.0 - MARGIN):
            return False, temperature, touched
    if lowest > watch[WATCH_CLEARANCE]:
        touched = 0.0
    elif touched < 0.5:             # a contact may be due (lowest <= 0 or reached inside the step)
        return False, temperature, touched
    elif axis_up(y) < watch[WATCH_TIP]:
        return False, temperature, touched
    return True, temperature, touched


@njit(borrows=True)
def events_quiet(y, t, p, veh, watch, dry, on_rail):
    """Whether the flight events other than liftoff and max-Q surely do nothing at this
    state, nor the world's one-step rule and handover change: no stage newly dry
    (``dry``: the stages' flags at the run's start; the MECO, SECO and stage_dry of
    :meth:`~rocketsim.sim.flight_events.FlightEvents._stages_dry`), still on the rail
    or off it as at the start (``on_rail``; :meth:`~rocketsim.sim.flight_events.FlightEvents._off_rail`),
    before the next motor burn-out (:meth:`~rocketsim.sim.flight_events.FlightEvents._burnouts`),
    below the orbit test's bound and inside the sphere-of-influence watch radius
    (:func:`orbit_and_soi_quiet`), in the air's reach
    (:meth:`~rocketsim.sim.vehicle_checks.VehicleChecks.every_step`)."""
    for s in range(veh.stage.shape[0]):
        if veh.stage[s, S_DRY] != dry[s]:
            return False
    if veh.rail[RL_ON] != on_rail or t >= watch[WATCH_BURNOUT] - MARGIN:
        return False
    if not orbit_and_soi_quiet(y, p, watch[WATCH_ORBIT], watch[WATCH_MU], watch[WATCH_SOI]):
        return False
    x, y_, z = y[R], y[R + 1], y[R + 2]
    return math.sqrt(x * x + y_ * y_ + z * z) - p[P_RADIUS] < watch[WATCH_REACH] - MARGIN * p[P_RADIUS]


@njit(borrows=True)
def orbit_and_soi_quiet(y, p, orbit_bound, mu, soi):
    """Whether the orbit test's periapsis bound (:func:`~rocketsim.sim.flight_events.periapsis_bound`,
    the same operations) stays below ``orbit_bound`` (m; inf: not watched), so that
    :meth:`~rocketsim.sim.flight_events.FlightEvents._orbit` is not called, and the
    distance from the centre below the sphere-of-influence watch radius ``soi`` (m),
    so that :func:`~rocketsim.sim.handover.watch_soi` hands nothing over
    (:func:`~rocketsim.sim.handover.hand_over`)."""
    x, y_, z, u, v, w = y[R], y[R + 1], y[R + 2], y[V], y[V + 1], y[V + 2]
    hx, hy, hz = y_ * w - z * v, z * u - x * w, x * v - y_ * u
    return (hx * hx + hy * hy + hz * hz) / mu <= orbit_bound * (1.0 - MARGIN) and \
        math.sqrt(x * x + y_ * y_ + z * z) < soi * (1.0 - MARGIN)


@njit
def below_liftoff(y, t, p, liftoff):
    """Whether state ``y`` at mission time ``t`` (s) is surely not past the liftoff height
    ``liftoff`` (m over the ellipsoid, the readings' height; inf: lifted off), with the
    margin of the readings' height against the one here: the liftoff test of
    :meth:`~rocketsim.sim.flight_events.FlightEvents.after_step`."""
    if liftoff == math.inf:
        return True
    geodetic = where_and_how_fast(y[R:R + 3], y[V:V + 3], t, p[P_SPIN], p[P_RADIUS], p[P_POLAR_RADIUS])[2]
    return geodetic <= liftoff - MARGIN * p[P_RADIUS]


@njit(borrows=True)
def surely_finite(y):
    """Whether the world's finiteness test (the sum of the state finite:
    :meth:`rocketsim.sim.world.World.check_finite`) surely passes on ``y``: every
    number under 1e300 in size, so no order of summing them can overflow."""
    for x in y:
        if not abs(x) < 1e300:
            return False
    return True
