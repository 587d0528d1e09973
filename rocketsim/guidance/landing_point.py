"""Where a falling stage comes down: the landing-point prediction of a return's guidance.

A guidance model, compiled, cheap enough to call several times every guidance
cycle. It integrates a point mass in
the Earth-fixed frame (ECEF: position ``r`` and velocity ``v`` over the rotating
ground) and its mass ``m``::

    dv/dt = g(r) - 2 w x v - w x (w x r) + a_drag + a_lift + a_thrust,   dm/dt = -flow

* ``g``: the point mass and J2 (:func:`rocketsim.bodies.gravity.point_mass_j2`),
  ``w`` the Earth's rotation about +z;
* drag through the day's air: ``a_drag = -rho(h) |v_a| v_a C_D A(M) / (2 m)`` with
  the air-relative velocity ``v_a = v - u(h)``, ``u`` the wind (east, north) at the
  height ``h`` turned into ECEF with the local east and north of the geocentric
  position, ``M = |v_a| / c(h)``; ``rho``, ``c`` and ``u`` from an air table
  (:func:`rocketsim.atmosphere.table.air_at`: the day's forecast, ``fc.forecast``)
  and ``C_D A`` (m^2, the drag area) from a table against Mach: the body's own drag
  (:class:`rocketsim.guidance.drag.DragArea` learns its scale in flight);
* lift: a body falling tail first and leaning turns part of its drag sideways,
  the more the more it leans; how far it may lean is bounded by the bending load
  it takes (``q alpha``) and by an angle. The model holds a horizontal force of
  the drag's size times the lift-to-drag ratio at the largest lean allowed there,
  ``k(M) min(alpha_max, (q alpha)_max / q)`` (``k`` the ratio per radian, a table
  against Mach), times ``lean`` (east, north; a share, its length at most 1: the
  control a descent's guidance solves for), while no engine burns;
* two burns, each as a return's program flies it (either may be left out):

  - the **entry burn**, lit falling through ``entry[ENTRY_ALTITUDE]`` (inf: burning
    now) while the airspeed is above ``entry[ENTRY_SPEED]``: thrust
    ``entry[ENTRY_THRUST]`` (N) along ``-v_a / |v_a| + lean`` (``lean`` horizontal,
    the east and north shares of the thrust), the mass falling at
    ``entry[ENTRY_FLOW]`` (kg/s), until the airspeed is down to
    ``entry[ENTRY_SPEED]`` or the mass to ``entry[ENTRY_FLOOR]`` (what the landing
    burn keeps);
  - the **landing burn**, of one engine of vacuum thrust ``landing[LANDING_THRUST]``
    (N) and nozzle exit area ``landing[LANDING_EXIT_AREA]`` (m^2), whose full thrust in
    the air is ``T = T_vac - p(h) A_e`` (docs/physics.md#propulsion: the ambient pressure
    ``p`` pushes on the exit whatever the throttle), lit once stopping the fall at a
    constant deceleration needs the throttle ``landing[LANDING_PLAN]`` (the margin the
    burn keeps), below ``landing[LANDING_CEILING]`` (m), and the drag alone would not
    stop it (its deceleration less gravity short of ``v^2 / 2h``: the rule of
    :func:`rocketsim.guidance.powered_descent.ignition_due`), then braking
    along the airflow's reverse (no angle of attack: no normal force) with the
    thrust ``F`` whose vertical part stops the fall at the ground (at most ``T``); the
    throttle that gives it is ``u = (F + p A_e) / T_vac``
    (:func:`rocketsim.guidance.powered_descent.throttle_for`) and the mass falls at
    ``u landing[LANDING_FLOW]`` (the mass flow is the throttle's share of the full flow,
    whatever the air: a throttled engine at sea level draws more per newton than its
    thrust's share of ``T`` says), until the fall has slowed to ``landing[LANDING_TOUCH]``
    (m/s: the point returned) or the mass is down to ``landing[LANDING_EMPTY]``
    (the engines stop: the stage falls on).

  Under thrust the model has no drag: flying tail first into its own plume a
  stage loses nearly all of it (docs/physics.md#plume-shielding: a few percent
  left at ``T / (q S)`` of 3, what a landing burn has; far less for an entry burn),
  and no normal force: its thrust stays along the airflow.

Integrated by the midpoint (second-order Runge-Kutta) rule in steps of
``STEP_SHARE`` of the time to fall to the ground at the present rate, between
MIN_STEP and MAX_STEP (MAX_BURN_STEP under thrust). Every change of phase (a
burn lit or ended, the ground: the WGS84 ellipsoid, ``h`` along the radius,
:func:`rocketsim.vehicle.contact.point_height`) is placed within its step by
linear interpolation of the quantity that crosses its threshold, and the step
is taken again to that instant: the point predicted is a smooth function of the
starting state (what a guidance's finite-difference Jacobians need), not one
that jumps by a step's worth of flight as a burn's start crosses a step's end.
After MAX_STEPS steps the point reached is returned. Units SI.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from rocketsim.jit import njit
from rocketsim.atmosphere.table import air_at
from rocketsim.bodies.gravity import point_mass_j2
from rocketsim.guidance.powered_descent import throttle_for
from rocketsim.constants import (EARTH_J2, EARTH_MU, EARTH_OMEGA, EARTH_RADIUS_EQ,
                                 EARTH_RADIUS_POLAR)
from rocketsim.vehicle.aero import interp
from rocketsim.vehicle.contact import point_height

# the steps: a share of the time to the ground at the present rate of fall, within bounds
STEP_SHARE = 0.03
MIN_STEP = 0.05             # s
MAX_STEP = 2.0              # s
MAX_BURN_STEP = 0.5         # s
MAX_STEPS = 20000

# the entry burn's numbers (an array of N_ENTRY floats; thrust 0: no entry burn)
ENTRY_ALTITUDE, ENTRY_SPEED, ENTRY_THRUST, ENTRY_FLOW, ENTRY_FLOOR, ENTRY_LEAN_E, ENTRY_LEAN_N = range(7)
N_ENTRY = 7
# the landing burn's numbers (an array of N_LANDING floats; thrust 0: no landing burn)
LANDING_THRUST, LANDING_FLOW, LANDING_PLAN, LANDING_TOUCH, LANDING_EMPTY, LANDING_CEILING, LANDING_EXIT_AREA = range(7)
N_LANDING = 7

NO_ENTRY = np.zeros(N_ENTRY)
NO_LANDING = np.zeros(N_LANDING)

# the lean of the aerodynamic descent (an array of N_LEAN floats)
LEAN_E, LEAN_N, LEAN_Q_ALPHA, LEAN_MAX_ALPHA = range(4)
N_LEAN = 4
# the columns of the body's aerodynamic table (rows by increasing Mach)
AERO_MACH, AERO_AREA, AERO_LIFT_SLOPE = range(3)

# the phases of the prediction, and how it ends
COAST, ENTRY, LANDING, DOWN = 0, 1, 2, 3


def entry_burn(altitude: float, speed: float, thrust: float, flow: float, floor: float,
               lean=(0.0, 0.0)) -> np.ndarray:
    """The entry burn's numbers for :func:`fall`: lit falling through ``altitude`` (m; inf:
    burning now), ending at the airspeed ``speed`` (m/s) or the mass ``floor`` (kg), of
    ``thrust`` (N) and mass ``flow`` (kg/s), leaned by ``lean`` (east, north shares)."""
    return np.array((altitude, speed, thrust, flow, floor, lean[0], lean[1]), dtype=float)


def landing_burn(thrust: float, flow: float, plan: float, touch_speed: float, empty: float,
                 ceiling: float, exit_area: float = 0.0) -> np.ndarray:
    """The landing burn's numbers for :func:`fall`: vacuum ``thrust`` (N) and mass ``flow``
    (kg/s) at full throttle of an engine of nozzle ``exit_area`` (m^2), lit below
    ``ceiling`` (m) at the throttle ``plan``, ending at ``touch_speed`` (m/s) down, its
    engines stopping at the mass ``empty`` (kg)."""
    return np.array((thrust, flow, plan, touch_speed, empty, ceiling, exit_area), dtype=float)


# the figures of the state a step reads (:func:`_frame`), by position in its tuple
F_HEIGHT, F_FALL, F_GRAVITY, F_DENSITY, F_SOUND, F_PRESSURE = range(6)
F_EAST = 6                  # east x, y (its z is 0), then north x, y, z
F_NORTH = 8
F_AIR = 11                  # the air-relative velocity x, y, z, then the airspeed
F_AIRSPEED = 14


@njit(borrows=True)
def _frame(s, air):
    """The figures at the state ``s`` (x, y, z, vx, vy, vz, mass) in the air table ``air``
    (:meth:`~rocketsim.atmosphere.table.AtmosphereTable.arrays`), in the order of the
    ``F_*`` positions: the height along the radius (m), the speed down the geocentric
    radius (m/s), the point-mass gravity (m/s^2), the air's density, speed of sound and
    pressure (Pa), the local east (x, y; ``east = z x up`` normalised, its z 0) and north
    (``north = up x east``), the air-relative velocity (m/s) and the airspeed."""
    x, y, z = s[0], s[1], s[2]
    rr = math.sqrt(x * x + y * y + z * z)
    ux, uy, uz = x / rr, y / rr, z / rr
    h = point_height(x, y, z, EARTH_RADIUS_EQ, EARTH_RADIUS_POLAR)
    rho, p, _, c, ue, un = air_at(air[0], air[1], air[2], air[3], air[4], air[5], air[6], air[7], h)
    across = math.sqrt(ux * ux + uy * uy)
    ex, ey = -uy / across, ux / across
    nx, ny, nz = -uz * ey, uz * ex, ux * ey - uy * ex
    ax = s[3] - ue * ex - un * nx
    ay = s[4] - ue * ey - un * ny
    az = s[5] - ue * 0.0 - un * nz
    return (h, -(s[3] * ux + s[4] * uy + s[5] * uz), EARTH_MU / (rr * rr), rho, c, p, ex, ey, nx, ny, nz,
            ax, ay, az, math.sqrt(ax * ax + ay * ay + az * az))


@njit(borrows=True)
def _landing_throttle(h, fall, g, mass, p, landing):
    """The throttle (0 to 1) of the landing burn's engine at the ambient pressure ``p`` (Pa)
    that stops ``fall`` at the ground ``h`` below at a constant deceleration (1 when it
    cannot)."""
    if h <= 0.0 or fall <= 0.0:
        return 1.0
    loss = p * landing[LANDING_EXIT_AREA]
    return min(1.0, throttle_for((fall * fall / (2.0 * h) + g) * mass, landing[LANDING_THRUST] - loss, loss))


@njit(borrows=True)
def _drag(rho, c, airspeed, mass, aero):
    """The drag's deceleration (m/s^2) at the air's density ``rho`` and speed of sound ``c``."""
    if rho <= 0.0 or airspeed <= 0.0:
        return 0.0
    return rho * airspeed * airspeed * interp(aero[:, AERO_MACH], aero[:, AERO_AREA], airspeed / c) / (2.0 * mass)


@njit(borrows=True)
def _rates(s, f, phase, aero, lean, entry, landing):
    """The rates of the state ``s`` (velocity, acceleration, -flow) in ``phase`` (see the
    module), ``f`` its :func:`_frame`."""
    h, fall, g, rho, c, p = f[F_HEIGHT], f[F_FALL], f[F_GRAVITY], f[F_DENSITY], f[F_SOUND], f[F_PRESSURE]
    ex, ey, nx, ny, nz = f[F_EAST], f[F_EAST + 1], f[F_NORTH], f[F_NORTH + 1], f[F_NORTH + 2]
    ax, ay, az, airspeed = f[F_AIR], f[F_AIR + 1], f[F_AIR + 2], f[F_AIRSPEED]
    w = EARTH_OMEGA
    gx, gy, gz = point_mass_j2(s[0], s[1], s[2], EARTH_MU, EARTH_RADIUS_EQ, EARTH_J2)
    dvx = gx + 2.0 * w * s[4] + w * w * s[0]
    dvy = gy - 2.0 * w * s[3] + w * w * s[1]
    dvz = gz
    flow = 0.0
    mass = s[6]
    if phase == ENTRY:
        dx = -ax / airspeed + entry[ENTRY_LEAN_E] * ex + entry[ENTRY_LEAN_N] * nx
        dy = -ay / airspeed + entry[ENTRY_LEAN_E] * ey + entry[ENTRY_LEAN_N] * ny
        dz = -az / airspeed + entry[ENTRY_LEAN_E] * 0.0 + entry[ENTRY_LEAN_N] * nz
        k = entry[ENTRY_THRUST] / mass / math.sqrt(dx * dx + dy * dy + dz * dz)
        dvx, dvy, dvz = dvx + k * dx, dvy + k * dy, dvz + k * dz
        flow = -entry[ENTRY_FLOW]
    elif phase == LANDING:
        # the vertical part the profile needs, along the airflow's reverse (no angle of attack)
        loss = p * landing[LANDING_EXIT_AREA]
        full = (landing[LANDING_THRUST] - loss) / mass
        up = _landing_throttle(h, fall, g, mass, p, landing) * landing[LANDING_THRUST] / mass - loss / mass
        r = math.sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2])
        fall_air = -(ax * s[0] + ay * s[1] + az * s[2]) / r
        k = -up / max(fall_air, 1e-3)
        px, py, pz = k * ax, k * ay, k * az
        size = math.sqrt(px * px + py * py + pz * pz)
        if size > full:
            k = full / size
            px, py, pz = px * k, py * k, pz * k
            size = full
        dvx, dvy, dvz = dvx + px, dvy + py, dvz + pz
        flow = -throttle_for(size * mass, full * mass, loss) * landing[LANDING_FLOW]
    else:
        drag = _drag(rho, c, airspeed, mass, aero)
        if drag > 0.0:
            k = drag / airspeed
            dvx, dvy, dvz = dvx - k * ax, dvy - k * ay, dvz - k * az
            if lean[LEAN_E] != 0.0 or lean[LEAN_N] != 0.0:
                q = 0.5 * rho * airspeed * airspeed
                ratio = interp(aero[:, AERO_MACH], aero[:, AERO_LIFT_SLOPE], airspeed / c) * min(
                    lean[LEAN_MAX_ALPHA], lean[LEAN_Q_ALPHA] / q)
                k = drag * ratio
                dvx = dvx + k * (lean[LEAN_E] * ex + lean[LEAN_N] * nx)
                dvy = dvy + k * (lean[LEAN_E] * ey + lean[LEAN_N] * ny)
                dvz = dvz + k * (lean[LEAN_E] * 0.0 + lean[LEAN_N] * nz)
    return s[3], s[4], s[5], dvx, dvy, dvz, flow


@njit(borrows=True)
def _events(s, f, phase, entering, aero, entry, landing):
    """The phase's event quantities at the state ``s`` (``f`` its :func:`_frame`), each
    positive before its event: (the ground, the entry burn lit / ended, the landing burn
    lit / its touch speed, the landing burn's engines empty); inf where an event cannot
    happen in this phase."""
    h, fall, g, airspeed = f[F_HEIGHT], f[F_FALL], f[F_GRAVITY], f[F_AIRSPEED]
    entry_event = landing_event = empty = np.inf
    if phase == COAST:
        if entering and fall > 0.0:
            entry_event = h - entry[ENTRY_ALTITUDE]
        if landing[LANDING_THRUST] > 0.0 and fall > 0.0 and h > 0.0:
            landing_event = max(landing[LANDING_PLAN] - _landing_throttle(h, fall, g, s[6], f[F_PRESSURE], landing),
                                _drag(f[F_DENSITY], f[F_SOUND], airspeed, s[6], aero) - g - fall * fall / (2.0 * h),
                                (h - landing[LANDING_CEILING]) / landing[LANDING_CEILING])
    elif phase == ENTRY:
        entry_event = min(airspeed - entry[ENTRY_SPEED], s[6] - entry[ENTRY_FLOOR])
    elif phase == LANDING:
        landing_event = fall - landing[LANDING_TOUCH]
        empty = s[6] - landing[LANDING_EMPTY]
    return h, entry_event, landing_event, empty


@njit(inline="always")
def _ahead(s, dt, rates):
    """The state ``s`` moved on by ``dt`` times ``rates``."""
    return (s[0] + dt * rates[0], s[1] + dt * rates[1], s[2] + dt * rates[2], s[3] + dt * rates[3],
            s[4] + dt * rates[4], s[5] + dt * rates[5], s[6] + dt * rates[6])


@njit(borrows=True)
def _midpoint(s, dt, start, phase, air, aero, lean, entry, landing):
    """The state ``s`` ``dt`` s on by the midpoint rule in ``phase``, ``start`` its rates."""
    half = _ahead(s, 0.5 * dt, start)
    return _ahead(s, dt, _rates(half, _frame(half, air), phase, aero, lean, entry, landing))


@njit
def fall(x, y, z, vx, vy, vz, mass, h0, dh, density, pressure, temperature, sound, wind_e, wind_n,
         aero, lean, entry, landing):
    """Where the stage at Earth-fixed ``(x, y, z)`` (m) moving at ``(vx, vy, vz)`` (m/s over
    the rotating ground) with ``mass`` (kg) comes down (see the module).

    The air: an air table's arrays (``h0``, ``dh``, density, pressure, temperature, speed
    of sound, wind east, wind north: :meth:`~rocketsim.atmosphere.table.AtmosphereTable.arrays`);
    the body's ``aero`` table (rows of Mach, increasing, the drag area ``C_D A`` m^2 and the
    lift-to-drag ratio per radian of angle of attack); ``lean`` (N_LEAN floats: the share
    east and north, the bending load ``q alpha`` allowed, Pa rad, and the largest angle,
    rad); ``entry`` (N_ENTRY floats) and ``landing`` (N_LANDING floats) the burns (thrust
    0: none).

    Returns ``(x, y, z, t, mass, lit, peak_q)``: the Earth-fixed point (m), the time (s)
    from now and the mass (kg) there, the mass when the landing burn was lit (nan if it
    was not) and the highest dynamic pressure (Pa) met off the engines.

    Each step reads the air at its middle and its end (:func:`_frame`); the figures at its
    end serve the next step's start, its events and its dynamic pressure."""
    air = (h0, dh, density, pressure, temperature, sound, wind_e, wind_n)
    state = (float(x), float(y), float(z), float(vx), float(vy), float(vz), float(mass))
    entering = entry[ENTRY_THRUST] > 0.0
    phase = COAST
    if entering and entry[ENTRY_ALTITUDE] == np.inf:
        phase = ENTRY
    t = 0.0
    lit = np.nan
    peak = 0.0
    here = _frame(state, air)
    events = _events(state, here, phase, entering, aero, entry, landing)
    for _ in range(MAX_STEPS):
        if phase == COAST or phase == DOWN:
            peak = max(peak, 0.5 * here[F_DENSITY] * here[F_AIRSPEED] * here[F_AIRSPEED])
        if phase == COAST and events[2] <= 0.0:
            phase, lit = LANDING, state[6]  # lit at the start (the margin already used up)
            events = _events(state, here, phase, entering, aero, entry, landing)
            continue
        h, fall_speed = events[0], -(state[3] * state[0] + state[4] * state[1] + state[5] * state[2]) \
            / math.sqrt(state[0] * state[0] + state[1] * state[1] + state[2] * state[2])
        dt = MAX_STEP if phase == COAST else MAX_BURN_STEP
        if fall_speed > 0.0:
            dt = min(dt, max(MIN_STEP, STEP_SHARE * max(h, 0.0) / fall_speed))
        start = _rates(state, here, phase, aero, lean, entry, landing)
        after = _midpoint(state, dt, start, phase, air, aero, lean, entry, landing)
        there = _frame(after, air)
        later = _events(after, there, phase, entering, aero, entry, landing)
        first, share = -1, 1.0
        for k in range(4):
            if later[k] <= 0.0:
                if events[k] <= 0.0:
                    f = 0.0
                elif events[k] == np.inf:       # an event that became possible within the step
                    f = 1.0
                else:
                    f = events[k] / (events[k] - later[k])
                if f < share or first < 0:
                    first, share = k, f
        if first < 0:
            state, here, events, t = after, there, later, t + dt
            continue
        if first == 0:                      # the ground, within the step: interpolated
            return (state[0] + share * (after[0] - state[0]), state[1] + share * (after[1] - state[1]),
                    state[2] + share * (after[2] - state[2]), t + share * dt,
                    state[6] + share * (after[6] - state[6]), lit, peak)
        state = _midpoint(state, share * dt, start, phase, air, aero, lean, entry, landing)
        t += share * dt
        if phase == COAST and first == 1:
            phase = ENTRY
        elif phase == COAST:
            phase, lit = LANDING, state[6]
        elif phase == ENTRY:
            phase, entering = COAST, False
        elif first == 2:                    # slowed to the touch speed: there
            return state[0], state[1], state[2], t, state[6], lit, peak
        else:                               # the landing burn's engines empty: the stage falls
            phase = DOWN
        here = _frame(state, air)
        events = _events(state, here, phase, entering, aero, entry, landing)
    return state[0], state[1], state[2], t, state[6], lit, peak


class Prediction(NamedTuple):
    """Where and how a stage comes down (:func:`fall`): the Earth-fixed ``point`` (m), the
    ``time`` (s) from now and the ``mass`` (kg) there, the mass when the landing burn was
    lit (``ignition_mass``, nan if it was not) and the highest dynamic pressure met off
    the engines (``peak_q``, Pa)."""

    point: np.ndarray
    time: float
    mass: float
    ignition_mass: float
    peak_q: float


class LandingPoint:
    """The prediction of :func:`fall` for one stage: the day's ``air`` (an
    :class:`~rocketsim.atmosphere.table.AtmosphereTable`) and the body's aerodynamics,
    ``mach`` (increasing), the drag area ``area`` (m^2) and the lift-to-drag ratio per
    radian ``lift_slope`` against it, with the largest lean: ``q_alpha`` (Pa rad) and
    ``max_alpha`` (rad). The drag area is multiplied by :attr:`scale`, which a program may
    update in flight (:class:`rocketsim.guidance.drag.DragArea`)."""

    def __init__(self, air, mach, area, lift_slope, q_alpha: float, max_alpha: float):
        self.air = air.arrays()
        self.aero = np.ascontiguousarray(np.column_stack((mach, area, lift_slope)), dtype=float)
        self.area = self.aero[:, AERO_AREA].copy()
        self.q_alpha, self.max_alpha = float(q_alpha), float(max_alpha)
        self.scale = 1.0

    def set_scale(self, scale: float) -> None:
        """Multiply the drag area table by ``scale`` from now on."""
        self.scale = float(scale)
        self.aero[:, AERO_AREA] = self.area * self.scale

    def __call__(self, r, v, mass: float, lean=(0.0, 0.0), entry=NO_ENTRY, landing=NO_LANDING) -> Prediction:
        """The :class:`Prediction` for the stage at Earth-fixed ``r`` (m) moving at ``v`` (m/s)
        with ``mass`` (kg), the descent's ``lean`` (east, north shares) held (see :func:`fall`)."""
        x, y, z = r
        vx, vy, vz = v
        h0, dh, density, pressure, temperature, sound, wind_e, wind_n = self.air
        shares = np.array((lean[0], lean[1], self.q_alpha, self.max_alpha), dtype=float)
        px, py, pz, t, m, lit, peak = fall(float(x), float(y), float(z), float(vx), float(vy), float(vz),
                                           float(mass), h0, dh, density, pressure, temperature, sound, wind_e,
                                           wind_n, self.aero, shares, entry, landing)
        return Prediction(np.array((px, py, pz)), t, m, lit, peak)
