"""Classical fourth-order Runge-Kutta at a fixed step, as the flight model flies.

docs/physics.md#integrator: every body is advanced by classical RK4 at
a fixed step (20 ms by default, any headless step up to 0.1 s). Within 2 m of
the ground the step is split into four equal sub-steps so stiff contact stays
stable. The attitude quaternion is normalised after each (sub-)step, not
inside the stages.

Every function takes an optional ``veh``, the arrays of a staged vehicle
(:class:`~rocketsim.vehicle.build.VehicleArrays`): its engines and mass
properties are then evaluated at each of the four stages. A stage whose
usable propellant runs out inside a step is handled exactly: the step is
split at the instant the propellant left reaches the unusable reserve
(found by a safeguarded secant on the length of the first part, to 1e-13 of
the stage's load), the stage is marked dry in ``veh.stage`` with that
instant (its engines stop at once), and the rest of the step is flown
without them. Steps are also split at every kink of an engine's thrust (end
of dead time, spool-up, tail-off, slews), so a burn converges at fourth
order through them. Without ``veh`` (a rigid body) the vehicle branches are
compiled away.

On the classic range (``p[P_CLASSIC] = 1``) the same step flies the original
model: each RK4 step's start is the hold of
:func:`~rocketsim.dynamics.derivative.held_derivative` (thrust, mass and the
density above 86 km held for the step), which makes powered flight first
order in the step; everything else here is the same code.
"""

import math

import numpy as np

from rocketsim.jit import njit
from rocketsim.atmosphere.table import air_in, wind_earth_fixed
from rocketsim.constants import (GROUND_SUBSTEP_HEIGHT, GROUND_SUBSTEP_MAX, GROUND_SUBSTEPS,
                                UNUSABLE_PROPELLANT)
from rocketsim.dynamics.derivative import flight_dynamic_pressure, held_derivative, radial_height
from rocketsim.layout import P_RADIUS, P_SPIN, Q, R
from rocketsim.dynamics.third_bodies import hold_field
from rocketsim.frames.geodetic import ecef_to_geodetic_njit
from rocketsim.vehicle.aero import A_GROUND, A_REACH, A_WIND
from rocketsim.vehicle.engines import (S_DRY, S_DRY_AT, S_RESERVE, S_TANK0, S_TANKS, hold_q_law, next_kink,
                                       q_law_on)
from rocketsim.vehicle.motors import next_motor_kink
from rocketsim.vehicle.parachutes import next_canopy_kink
from rocketsim.vehicle.rail import RL_OFF_AT, RL_OFF_SPEED, RL_ON, RL_TRAVEL, rail_travel

DRY_TOLERANCE = 1e-13      # relative to the stage's load: where the split of a step is placed
RAIL_EXIT_TOLERANCE = 1e-9  # m of travel: where the step is split as the vehicle leaves its rail
# the rows of step_into's ``work``: an RK4 stage's state, a part's end, the state between
# parts, a trial of the cut instant's search, a sub-step's start
WK_TMP, WK_TRIAL, WK_STATE, WK_SCRATCH, WK_START = 0, 1, 2, 3, 4
N_WORK = 5


@njit
def rk4_step(y, t, h, p, veh=None, nbody=None):
    """One classical RK4 step of size ``h`` (s) from ``(t, y)``; returns the new state.

    Parameters
    ----------
    y : array
        The state (slots of :mod:`rocketsim.layout`: m, m/s, quaternion body ->
        inertial, rad/s in body axes; a staged vehicle's tank masses in kg and
        engine clocks in s after slot 13).
    t : float
        Mission time at the step's start, s.
    h : float
        Step, s.
    p : array
        The body's parameters (:mod:`rocketsim.layout`, SI units), with its
        n-body field when it carries one.
    veh : VehicleArrays or None
        A staged vehicle's arrays (:class:`~rocketsim.vehicle.build.VehicleArrays`),
        None for a rigid body.
    nbody : True or None
        True when ``p`` carries an n-body field, None when it does not (as
        :func:`~rocketsim.dynamics.derivative.derivative`'s).
    """
    n = y.shape[0]
    out = np.empty(n)
    _rk4_into(out, np.empty((4, n)), np.empty(n), y, t, h, p, veh, nbody)
    return out


@njit(borrows=True)
def _rk4_into(out, k, tmp, y, t, h, p, veh, nbody):
    """:func:`rk4_step` written into ``out`` (n,), its four stages' rates in ``k`` (4, n)
    and each stage's state in ``tmp`` (n,)."""
    n = y.shape[0]
    # the four stages: k_s at t + c_s h from y + c_s h k_(s-1), c = (0, 1/2, 1/2, 1); the
    # step's start is the hold of the classic range's model (ignored by the realistic one)
    for s in range(4):
        at, ys = t, y
        if s > 0:
            c = 1.0 if s == 3 else 0.5
            for i in range(n):
                tmp[i] = y[i] + c * h * k[s - 1, i]
            at, ys = t + c * h, tmp
        held_derivative(at, ys, p, k[s], veh, t, y, nbody)
    for i in range(n):
        out[i] = y[i] + h / 6.0 * (k[0, i] + 2.0 * k[1, i] + 2.0 * k[2, i] + k[3, i])
    norm = math.sqrt(out[Q] ** 2 + out[Q + 1] ** 2 + out[Q + 2] ** 2 + out[Q + 3] ** 2)
    for i in range(4):
        out[Q + i] /= norm


@njit(inline="always")     # small: typed in its callers, no kernel of its own
def near_ground(y, p, reach=0.0):
    """True when the body is within 2 m of its central body's reference ellipsoid.

    ``reach`` (m): how far from the centre of mass a part that can touch the
    ground may be (a vehicle's legs, base and nose; 0 for a point): the test
    is then on the centre of mass's height less ``reach``, so the sub-steps
    begin before any of those parts is 2 m above the ground. The bound
    ``|r| - a`` (a = equatorial radius) rules out almost every step before
    :func:`radial_height` is computed.
    """
    r = math.sqrt(y[R] ** 2 + y[R + 1] ** 2 + y[R + 2] ** 2)
    if r - p[P_RADIUS] > GROUND_SUBSTEP_HEIGHT + reach:
        return False
    return radial_height(y, p) < GROUND_SUBSTEP_HEIGHT + reach


@njit(inline="always")
def hold_wind(y, t, p, veh):
    """Sample the day's wind at the vehicle's position at time ``t`` (s) and hold it
    (inertial, m/s) in ``veh.aero.wind`` for the step (docs/physics.md#wind):
    :func:`wind_at` in the vehicle's air table."""
    veh.aero.wind[0], veh.aero.wind[1], veh.aero.wind[2] = wind_at(y, t, p, veh.air)


@njit
def wind_at(y, t, p, air):
    """The wind (m/s, frame axes) of the air table ``air`` (the tuple of
    :meth:`~rocketsim.atmosphere.table.AtmosphereTable.arrays`) at the position of state
    ``y`` at mission time ``t`` (s); the table's east and north turn with the central
    body at ``p[P_SPIN]``."""
    theta = p[P_SPIN] * t
    c = math.cos(theta)
    s = math.sin(theta)
    x = c * y[R] + s * y[R + 1]
    yy = -s * y[R] + c * y[R + 1]
    lat, lon, h = ecef_to_geodetic_njit(x, yy, y[R + 2])
    east, north = air_in(air, h)[4:6]
    wind = wind_earth_fixed(east, north, lat, lon)
    return c * wind[0] - s * wind[1], s * wind[0] + c * wind[1], wind[2]


@njit(borrows=True)
def stage_left(y, veh, s):
    """Propellant (kg) above the unusable reserve in stage ``s`` of state ``y``."""
    k0 = veh.first_tank + int(veh.stage[s, S_TANK0])
    left = -veh.stage[s, S_RESERVE]
    for k in range(int(veh.stage[s, S_TANKS])):
        left += y[k0 + k]
    return left


@njit(borrows=True, inline="always")
def _first_dry(y, veh):
    """Index of a stage not yet marked dry whose usable propellant is gone in ``y``, or -1."""
    for s in range(veh.stage.shape[0]):
        if veh.stage[s, S_DRY] < 0.5 and veh.stage[s, S_TANKS] > 0 and stage_left(y, veh, s) < 0.0:
            return s
    return -1


@njit(borrows=True)
def _left(y, t, p, veh, kind, s):
    """What is left before a cut of the step: the usable propellant (kg) of stage ``s``
    (``kind`` 0), or the travel (m) to the end of the launch rail (``kind`` 1)."""
    if kind == 0:
        return stage_left(y, veh, s)
    return veh.rail[RL_TRAVEL] - rail_travel(y, t, p[P_SPIN], veh.rail)[0]


@njit(borrows=True)
def _cut_instant(y, t, h, p, veh, kind, s, left_at_h, tolerance, nbody, k, work):
    """Length of the part of the step from ``(t, y)`` after which nothing is left
    (:func:`_left`): stage ``s`` is dry (``kind`` 0) or the vehicle leaves its rail
    (``kind`` 1).

    Safeguarded secant (Illinois) on ``g(x) = _left(rk4_step(y, t, x))``,
    ``g(0) > 0 >= g(h) = left_at_h``, to ``tolerance`` (kg: :data:`DRY_TOLERANCE` of
    the stage's load; m: :data:`RAIL_EXIT_TOLERANCE`); each trial step computed in
    ``k`` and ``work`` (:func:`step_into`'s).
    """
    a, ga = 0.0, _left(y, t, p, veh, kind, s)
    if ga <= 0.0:
        return 0.0
    b, gb = h, left_at_h
    x = b
    for _ in range(100):
        x = b - gb * (b - a) / (gb - ga)
        if not a < x < b:
            x = 0.5 * (a + b)
        trial = work[WK_SCRATCH]
        _rk4_into(trial, k, work[WK_TMP], y, t, x, p, veh, nbody)
        gx = _left(trial, t + x, p, veh, kind, s)
        if abs(gx) <= tolerance:
            return x
        if gx > 0.0:
            a, ga = x, gx
            gb *= 0.5
        else:
            b, gb = x, gx
            ga *= 0.5
    return x


@njit(borrows=True)
def _powered_into(out, k, work, y, t, h, p, veh, nbody):
    """An RK4 step of a staged vehicle, split at engine kinks and where a stage runs dry,
    written into ``out`` (``k`` and ``work`` as :func:`step_into`'s).

    The step is cut at every instant an engine's thrust has a kink
    (:func:`~rocketsim.vehicle.engines.next_kink`) or a solid motor's curve has a
    point (:func:`~rocketsim.vehicle.motors.next_motor_kink`), at the instant a
    stage's usable propellant is gone and at the instant the vehicle leaves its
    launch rail (:func:`_cut_instant`); each part is one RK4 step over a smooth stretch.
    ``y`` is read before ``out`` is written: they may be the same array.
    """
    n = y.shape[0]
    now, trial, tmp = work[WK_STATE], work[WK_TRIAL], work[WK_TMP]
    for i in range(n):
        now[i] = y[i]
    done = 0.0
    while True:
        rest = h - done
        part = next_kink(t + done, rest, now, veh.first_clock, veh.eng, veh.cmd, veh.stage)
        if veh.motor.shape[0] > 0:      # the points of a solid motor's thrust curve
            part = min(part, next_motor_kink(t + done, rest, veh.motor, veh.curve))
        if veh.chute.shape[0] > 0:      # a parachute's inflation starting or ending
            part = min(part, next_canopy_kink(t + done, rest, veh.chute))
        _rk4_into(trial, k, tmp, now, t + done, part, p, veh, nbody)
        leaves = False
        if veh.rail[RL_ON] > 0.5:
            left = _left(trial, t + done + part, p, veh, 1, 0)
            if left <= 0.0:
                part = _cut_instant(now, t + done, part, p, veh, 1, 0, left, RAIL_EXIT_TOLERANCE, nbody, k, work)
                _rk4_into(trial, k, tmp, now, t + done, part, p, veh, nbody)
                leaves = True
        s = _first_dry(trial, veh)
        if s >= 0:
            part = _cut_instant(now, t + done, part, p, veh, 0, s, stage_left(trial, veh, s),
                                DRY_TOLERANCE * veh.stage[s, S_RESERVE] / UNUSABLE_PROPELLANT, nbody, k, work)
            _rk4_into(trial, k, tmp, now, t + done, part, p, veh, nbody)
            veh.stage[s, S_DRY] = 1.0
            veh.stage[s, S_DRY_AT] = t + done + part
            leaves = leaves and rail_travel(trial, t + done + part, p[P_SPIN], veh.rail)[0] >= \
                veh.rail[RL_TRAVEL] * (1.0 - DRY_TOLERANCE)
        if leaves:
            veh.rail[RL_ON] = 0.0
            veh.rail[RL_OFF_AT] = t + done + part
            veh.rail[RL_OFF_SPEED] = rail_travel(trial, t + done + part, p[P_SPIN], veh.rail)[1]
        for i in range(n):
            now[i] = trial[i]
        if part == rest:
            for i in range(n):
                out[i] = now[i]
            return
        done += part


@njit
def step(y, t, h, p, veh=None, nbody=None):
    """Advance one flight-model step of ``h`` seconds (sub-stepped near the ground).

    ``y`` (state), ``t`` (s), ``p`` and ``veh`` as :func:`rk4_step`'s; returns the
    new state: :func:`step_into` a new array.
    """
    n = y.shape[0]
    out = np.empty(n)
    step_into(out, np.empty((4, n)), np.empty((N_WORK, n)), y, t, h, p, veh, nbody)
    return out


@njit(borrows=True)
def step_into(out, k, work, y, t, h, p, veh=None, nbody=None):
    """Advance one flight-model step of ``h`` seconds (sub-stepped near the ground) from
    state ``y`` at ``t`` (s), writing the new state into ``out`` (not ``y``); ``k`` (4, n)
    and ``work`` (:data:`N_WORK`, n) hold the stages and the parts of the step. ``p`` and
    ``veh`` as :func:`rk4_step`'s. A caller flying many steps makes the arrays once.

    A vehicle with wind in its day's air samples it here, once per step, and an
    engine with a dynamic-pressure throttle law is commanded here, once per step
    (:func:`~rocketsim.vehicle.engines.hold_q_law`, on the dynamic pressure at the
    step's start: :func:`~rocketsim.dynamics.derivative.flight_dynamic_pressure`); a body
    in the n-body field holds the other bodies' positions here (per 5 s bucket
    of the step's start time, :func:`~rocketsim.dynamics.third_bodies.hold_field`).
    ``nbody`` says which: True when ``p`` carries an n-body field, None when it
    does not (:func:`~rocketsim.dynamics.third_bodies.nbody_flag`). It is a switch
    on the argument's type, like ``veh``: with None the hold, and the ephemeris
    it evaluates, are not compiled at all.
    """
    if nbody is not None:
        hold_field(p, t)            # the other bodies of an n-body field, held per 5 s
    reach = 0.0
    if veh is not None:
        reach = veh.aero.ref[A_REACH] + veh.aero.ref[A_GROUND]     # from the ellipsoid
        if veh.aero.ref[A_WIND] > 0.5:
            hold_wind(y, t, p, veh)
        if q_law_on(veh.cmd):
            hold_q_law(veh.eng, veh.cmd, t, flight_dynamic_pressure(y, p, veh))
    n_sub, sub = 1, h
    if near_ground(y, p, reach):
        # four 5 ms sub-steps at 20 ms; a larger headless step keeps sub-steps of 5 ms
        # at most, so stiff legs stay inside RK4's stability region
        n_sub = max(GROUND_SUBSTEPS, int(math.ceil(h / GROUND_SUBSTEP_MAX - 1e-9)))
        sub = h / n_sub
    for j in range(n_sub):          # one step far from the ground: t + 0 * h is t
        if veh is None:
            _rk4_into(out, k, work[WK_TMP], y, t + j * sub, sub, p, None, nbody)
        else:
            _powered_into(out, k, work, y, t + j * sub, sub, p, veh, nbody)
        if j + 1 < n_sub:           # the next sub-step starts where this one ended
            y = work[WK_START]
            for i in range(out.shape[0]):
                y[i] = out[i]


@njit
def advance(y, k0, h, n_steps, p, veh=None, nbody=None):
    """Advance up to ``n_steps`` flight-model steps; returns ``(y, steps_taken)``.

    Step ``k`` starts at mission time ``k h`` (``k`` counted from ``k0``, so
    time never accumulates rounding). Identical, bit for bit, to calling
    :func:`step` once per step: a coast with nothing to decide between steps
    is batched this way. Stops early, after the step that took the body below
    its central body's ellipsoid, or a vehicle's ground (``aero.ref[A_GROUND]``
    above it): an impact. ``nbody`` as :func:`step`'s.
    """
    ground = 0.0
    if veh is not None:
        ground = veh.aero.ref[A_GROUND]
    n = y.shape[0]
    k, work = np.empty((4, n)), np.empty((N_WORK, n))
    for j in range(n_steps):
        out = np.empty(n)
        step_into(out, k, work, y, (k0 + j) * h, h, p, veh, nbody)
        y = out
        if radial_height(y, p) < ground:
            return y, j + 1
    return y, n_steps
