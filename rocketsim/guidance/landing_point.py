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


@njit
def _frame(y, h0, dh, density, pressure, temperature, sound, wind_e, wind_n):
    """``(h, fall, g, rho, c, east (3), north (3), air-relative velocity (3), airspeed, p)`` at
    the state ``y``: the height along the radius (m), the speed down the geocentric
    radius (m/s), the point-mass gravity (m/s^2), the air's density, speed of sound and
    pressure (Pa, last),
    the local east and north (``east = z x up`` normalised, ``north = up x east``)."""
    x, yy, z = y[0], y[1], y[2]
    rr = math.sqrt(x * x + yy * yy + z * z)
    ux, uy, uz = x / rr, yy / rr, z / rr
    h = point_height(x, yy, z, EARTH_RADIUS_EQ, EARTH_RADIUS_POLAR)
    rho, p, _, c, ue, un = air_at(h0, dh, density, pressure, temperature, sound, wind_e, wind_n, h)
    s = math.sqrt(ux * ux + uy * uy)
    east = np.array((-uy / s, ux / s, 0.0))
    north = np.array((-uz * east[1], uz * east[0], ux * east[1] - uy * east[0]))
    air = y[3:6] - ue * east - un * north
    return (h, -(y[3] * ux + y[4] * uy + y[5] * uz), EARTH_MU / (rr * rr), rho, c, east, north, air,
            math.sqrt(air[0] * air[0] + air[1] * air[1] + air[2] * air[2]), p)


@njit
def _dynamic_pressure(y, h0, dh, density, pressure, temperature, sound, wind_e, wind_n):
    """``rho |v_a|^2 / 2`` (Pa) at the state ``y``."""
    _, _, _, rho, _, _, _, _, airspeed, _ = _frame(y, h0, dh, density, pressure, temperature, sound, wind_e, wind_n)
    return 0.5 * rho * airspeed * airspeed


@njit
def _landing_throttle(h, fall, g, mass, p, landing):
    """The throttle (0 to 1) of the landing burn's engine at the ambient pressure ``p`` (Pa)
    that stops ``fall`` at the ground ``h`` below at a constant deceleration (1 when it
    cannot)."""
    if h <= 0.0 or fall <= 0.0:
        return 1.0
    loss = p * landing[LANDING_EXIT_AREA]
    return min(1.0, throttle_for((fall * fall / (2.0 * h) + g) * mass, landing[LANDING_THRUST] - loss, loss))


@njit
def _rates(y, phase, h0, dh, density, pressure, temperature, sound, wind_e, wind_n, aero, lean,
           entry, landing):
    """The state's rates (velocity, acceleration, -flow) in ``phase`` (see the module)."""
    h, fall, g, rho, c, east, north, air, airspeed, p = _frame(y, h0, dh, density, pressure, temperature,
                                                               sound, wind_e, wind_n)
    w = EARTH_OMEGA
    gx, gy, gz = point_mass_j2(y[0], y[1], y[2], EARTH_MU, EARTH_RADIUS_EQ, EARTH_J2)
    out = np.empty(7)
    out[0], out[1], out[2] = y[3], y[4], y[5]
    out[3] = gx + 2.0 * w * y[4] + w * w * y[0]
    out[4] = gy - 2.0 * w * y[3] + w * w * y[1]
    out[5] = gz
    out[6] = 0.0
    mass = y[6]
    if phase == ENTRY:
        d = -air / airspeed + entry[ENTRY_LEAN_E] * east + entry[ENTRY_LEAN_N] * north
        out[3:6] += entry[ENTRY_THRUST] / mass / math.sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) * d
        out[6] = -entry[ENTRY_FLOW]
    elif phase == LANDING:
        # the vertical part the profile needs, along the airflow's reverse (no angle of attack)
        loss = p * landing[LANDING_EXIT_AREA]
        full = (landing[LANDING_THRUST] - loss) / mass
        up = _landing_throttle(h, fall, g, mass, p, landing) * landing[LANDING_THRUST] / mass - loss / mass
        r = math.sqrt(y[0] * y[0] + y[1] * y[1] + y[2] * y[2])
        fall_air = -(air[0] * y[0] + air[1] * y[1] + air[2] * y[2]) / r
        push = -up / max(fall_air, 1e-3) * air
        size = math.sqrt(push[0] * push[0] + push[1] * push[1] + push[2] * push[2])
        if size > full:
            push *= full / size
            size = full
        out[3:6] += push
        out[6] = -throttle_for(size * mass, full * mass, loss) * landing[LANDING_FLOW]
    else:
        drag = _drag(rho, c, airspeed, mass, aero)
        if drag > 0.0:
            out[3:6] -= drag / airspeed * air
            if lean[LEAN_E] != 0.0 or lean[LEAN_N] != 0.0:
                q = 0.5 * rho * airspeed * airspeed
                ratio = interp(aero[:, AERO_MACH], aero[:, AERO_LIFT_SLOPE], airspeed / c) * min(
                    lean[LEAN_MAX_ALPHA], lean[LEAN_Q_ALPHA] / q)
                out[3:6] += drag * ratio * (lean[LEAN_E] * east + lean[LEAN_N] * north)
    return out


@njit
def _drag(rho, c, airspeed, mass, aero):
    """The drag's deceleration (m/s^2) at the air's density ``rho`` and speed of sound ``c``."""
    if rho <= 0.0 or airspeed <= 0.0:
        return 0.0
    return rho * airspeed * airspeed * interp(aero[:, AERO_MACH], aero[:, AERO_AREA], airspeed / c) / (2.0 * mass)


@njit
def _events(y, phase, entering, h0, dh, density, pressure, temperature, sound, wind_e, wind_n,
            aero, entry, landing):
    """The phase's event quantities, each positive before its event: (the ground, the
    entry burn lit / ended, the landing burn lit / its touch speed, the landing burn's
    engines empty); inf where an event cannot happen in this phase."""
    h, fall, g, rho, c, _, _, _, airspeed, p = _frame(y, h0, dh, density, pressure, temperature, sound,
                                                      wind_e, wind_n)
    out = np.full(4, np.inf)
    out[0] = h
    if phase == COAST:
        if entering and fall > 0.0:
            out[1] = h - entry[ENTRY_ALTITUDE]
        if landing[LANDING_THRUST] > 0.0 and fall > 0.0 and h > 0.0:
            out[2] = max(landing[LANDING_PLAN] - _landing_throttle(h, fall, g, y[6], p, landing),
                         _drag(rho, c, airspeed, y[6], aero) - g - fall * fall / (2.0 * h),
                         (h - landing[LANDING_CEILING]) / landing[LANDING_CEILING])
    elif phase == ENTRY:
        out[1] = min(airspeed - entry[ENTRY_SPEED], y[6] - entry[ENTRY_FLOOR])
    elif phase == LANDING:
        out[2] = fall - landing[LANDING_TOUCH]
        out[3] = y[6] - landing[LANDING_EMPTY]
    return out


@njit
def _step(y, dt, phase, h0, dh, density, pressure, temperature, sound, wind_e, wind_n, aero, lean,
          entry, landing):
    """The state ``dt`` s on (the midpoint rule) in ``phase``."""
    k1 = _rates(y, phase, h0, dh, density, pressure, temperature, sound, wind_e, wind_n, aero, lean,
                entry, landing)
    k2 = _rates(y + 0.5 * dt * k1, phase, h0, dh, density, pressure, temperature, sound, wind_e, wind_n,
                aero, lean, entry, landing)
    return y + dt * k2


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
    was not) and the highest dynamic pressure (Pa) met off the engines."""
    state = np.array((x, y, z, vx, vy, vz, mass))
    entering = entry[ENTRY_THRUST] > 0.0
    phase = COAST
    if entering and entry[ENTRY_ALTITUDE] == np.inf:
        phase = ENTRY
    t = 0.0
    lit = np.nan
    peak = 0.0
    for _ in range(MAX_STEPS):
        if phase == COAST or phase == DOWN:
            peak = max(peak, _dynamic_pressure(state, h0, dh, density, pressure, temperature, sound, wind_e,
                                               wind_n))
        events = _events(state, phase, entering, h0, dh, density, pressure, temperature, sound, wind_e,
                         wind_n, aero, entry, landing)
        if phase == COAST and events[2] <= 0.0:
            phase, lit = LANDING, state[6]  # lit at the start (the margin already used up)
            continue
        h, fall_speed = events[0], -(state[3] * state[0] + state[4] * state[1] + state[5] * state[2]) \
            / math.sqrt(state[0] * state[0] + state[1] * state[1] + state[2] * state[2])
        dt = MAX_STEP if phase == COAST else MAX_BURN_STEP
        if fall_speed > 0.0:
            dt = min(dt, max(MIN_STEP, STEP_SHARE * max(h, 0.0) / fall_speed))
        after = _step(state, dt, phase, h0, dh, density, pressure, temperature, sound, wind_e, wind_n,
                      aero, lean, entry, landing)
        later = _events(after, phase, entering, h0, dh, density, pressure, temperature, sound, wind_e,
                        wind_n, aero, entry, landing)
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
            state, t = after, t + dt
            continue
        if first == 0:                      # the ground, within the step: interpolated
            point = state + share * (after - state)
            return point[0], point[1], point[2], t + share * dt, point[6], lit, peak
        state = _step(state, share * dt, phase, h0, dh, density, pressure, temperature, sound, wind_e,
                      wind_n, aero, lean, entry, landing)
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
