"""The telemetry sample of one body: its state message, every number of it from one compiled call.

:func:`figures` computes, for one body at its time, the state and everything
derived from it (geodetic position, speed, orbit elements, mass,
accelerations, air data; for a staged vehicle the engines, propellant and
heating) into one flat float64 array; :func:`values` returns that array with
the function that lays it out as the state message (keys in the order of
:data:`rocketsim.telemetry.schemas.BODY_STATE`), one per message shape, with a
layout worked out once per vehicle model. The flight writes the array as it
is (:meth:`rocketsim.telemetry.writer.TelemetryWriter.sample` splices its
numbers into a byte template of the message): a sample costs one compiled call
for its numbers and one for its bytes, no dictionary; :func:`message` builds
the dictionary for those who read it.

Read-only: nothing here changes the state, the engines' commands or the checks,
and no sensor is read (the figures are the truth). The computations are those
of the flight itself: the readings' geodetic position and the day's air
(:func:`rocketsim.frames.local.where_and_how_fast`, ``air_here``), the
derivative the integrator uses (:func:`rocketsim.sim.vehicle_checks.accelerations`),
the engine model (:func:`rocketsim.vehicle.engines.thrusts`, ``engine_state``).

Fields of every body (SI units; degrees where the name ends in ``_deg``; the
names and what each means: :mod:`rocketsim.telemetry.names`):
position, velocity (ECI of the central body, m, m/s), attitude (quaternion
w, x, y, z, body -> ECI), body rates (rad/s), latitude, longitude and
``altitude`` (geodetic over WGS84 about Earth; planetocentric over the central
body's ellipsoid elsewhere, :func:`rocketsim.dynamics.central.planetocentric`),
``height_agl`` (the altitude less the ground's: a vehicle's site's
``ground_height``, else 0), ``inertial_speed``, ``surface_speed`` (over the
central body's turning ground, :func:`rocketsim.frames.local.where_and_how_fast`),
the nose's (body x axis) ``pitch_deg`` above the local horizontal and
``heading_deg`` from north towards east (the local east-north-up axes of the
same call), the osculating elements (RAAN from the equinox about Earth, from the
node of the body's equator on the J2000 equator elsewhere; altitudes over the
central body's equatorial radius; apoapsis and period missing unless
elliptic), mass (kg), inertial acceleration ``|dv/dt|`` and sensed acceleration
``|dv/dt - g|`` (m/s^2), airspeed (m/s), the total ``angle_of_attack_deg``
between the nose and the air-relative velocity (missing at zero airspeed), Mach
and dynamic pressure (Pa) in the readings' air (the day's air about Earth, none
elsewhere).

Fields of a staged vehicle:

* ``throttle``: the throttle actually flown (after the slew limit and the
  flow-separation floor, 0-1 of vacuum thrust), averaged over the engines
  running; missing when none runs. ``group_throttle`` is the same by engine
  group (``<stage>_<group>``, missing for a group with no engine running);
* ``thrust`` (N) in total and ``group_thrust`` (N) by engine group, at the
  ambient pressure of the state message's air; solid motors count in the total;
* ``mass_flow``: propellant drawn by all engines and burnt by solid motors, kg/s;
* ``engines_running``: engines whose spool fraction is above zero on a stage
  with usable propellant left (spooling up, at thrust, or tailing off), and
  solid motors inside their curve;
* ``propellant``: all propellant on board, kg (the unusable reserve and the
  solid motors' included), and ``propellant_tanks`` by tank (``<stage>_<tank>``, kg).

Fields of a staged vehicle with a heat shield:

* ``heat_flux``: cold-wall stagnation-point convective heat flux, W/m^2, by
  Sutton-Graves (:func:`rocketsim.vehicle.heating.sutton_graves`) on the
  shield's nose radius, in the air the shield's checks read (the vehicle's
  air table at the radial height; the air-relative speed of its aerodynamics);
* ``shield_temperature``: the lumped shield's temperature, K (as the checks
  integrate it after every step).

A missing value is nan in the figures, None in :func:`message`'s dictionary, and
left out of the file's message (:meth:`rocketsim.telemetry.writer.TelemetryWriter.sample`),
so that every field written has its schema's type.

Names with characters other than letters, digits, ``-`` and ``_`` have them
replaced by ``_``, so Foxglove's message paths (``/<body>/state.group_thrust.booster_Merlin_1D_ring``)
and CSV columns can name them.
"""

from __future__ import annotations

import math
import weakref
from functools import lru_cache
from typing import NamedTuple

import numpy as np

from rocketsim._jit import entry_point, njit
from rocketsim.atmosphere.table import air_in
from rocketsim.constants import DEG
from rocketsim.dynamics.derivative import radial_height
from rocketsim.frames.local import body_air_velocity
from rocketsim.dynamics.nbody import FIELD_JD0, FIELD_ROT
from rocketsim.dynamics.soi import frame_rotation
from rocketsim.layout import N_STATE, P_MASS, P_POLAR_RADIUS, P_RADIUS, P_SPIN, Q, R, V
from rocketsim.dynamics.third_bodies import P_BUCKET, field_of, hold_field, nbody_flag
from rocketsim.flight.readings import air_here
from rocketsim.frames.local import where_and_how_fast
from rocketsim.frames.elements import elements_tuple
from rocketsim.frames.quaternion import rotate_components
from rocketsim.dynamics.central import air_about
from rocketsim.sim.vehicle_checks import accelerations
from rocketsim.telemetry.frames import CentralFrame, central_frame
from rocketsim.vehicle.aero import A_GROUND
from rocketsim.vehicle.engines import E_MDOT, E_STAGE, S_DRY, engine_state, thrusts
from rocketsim.vehicle.heating import sutton_graves, sutton_graves_constant
from rocketsim.vehicle.mass_properties import vehicle_mass_properties
from rocketsim.vehicle.motors import M_IMPULSE, M_PROPELLANT, motor_thrust

_TWO_PI = 2.0 * math.pi

# the flat array of figures(): the state (position, velocity, attitude, rates), then
# deg, deg, m, m, m/s, m/s, deg, deg
LAT, LON, HEIGHT, HEIGHT_AGL, SPEED, SURFACE_SPEED, PITCH, HEADING = range(N_STATE, N_STATE + 8)
ORBIT = HEADING + 1                               # ORBIT_KEYS, in order
ORBIT_KEYS = ("semi_major_axis", "eccentricity", "inclination_deg", "raan_deg", "arg_periapsis_deg",
              "true_anomaly_deg", "periapsis_altitude", "apoapsis_altitude", "period")
MASS = ORBIT + len(ORBIT_KEYS)                    # kg, then FLIGHT_KEYS in order
FLIGHT_KEYS = ("mass", "acceleration", "sensed_acceleration", "airspeed", "angle_of_attack_deg", "mach",
               "dynamic_pressure")
SENSED, AIRSPEED, ALPHA, MACH, DYNAMIC_PRESSURE = range(MASS + 2, MASS + 7)   # m/s^2, m/s, deg, -, Pa
VEHICLE = MASS + len(FLIGHT_KEYS)                 # a staged vehicle: VEHICLE_KEYS, then by group
VEHICLE_KEYS = ("throttle", "thrust", "mass_flow", "engines_running", "propellant", "heat_flux")
ENGINES_RUNNING = VEHICLE + 3                     # a count
GROUPS = VEHICLE + len(VEHICLE_KEYS)              # throttle by group, thrust by group, tanks
RIGID_WIDTH = VEHICLE + 2                         # a rigid body's figures: t and nan (no shield) end them


@njit
def orbit_into(out, k, r, v, mu, radius, node):
    """Write the osculating elements of ``r`` (m), ``v`` (m/s) about ``mu`` (m^3/s^2) into
    ``out[k:k + 9]`` in the order of ``ORBIT_KEYS``: angles in degrees, RAAN turned by
    ``node`` (rad), periapsis and apoapsis radii less ``radius`` (m); apoapsis and
    period nan unless elliptic (the formulas of :class:`rocketsim.frames.elements.Elements`)."""
    a, e, i, raan, argp, nu, p = elements_tuple(r, v, mu)
    out[k] = a
    out[k + 1] = e
    out[k + 2] = i / DEG
    out[k + 3] = np.fmod(raan + node, _TWO_PI) / DEG      # exact, as math.fmod
    out[k + 4] = argp / DEG
    out[k + 5] = nu / DEG
    out[k + 6] = p / (1.0 + e) - radius
    apoapsis = p / (1.0 - e) if e < 1.0 else math.inf
    period = _TWO_PI * math.sqrt(a ** 3.0 / mu) if e < 1.0 else math.inf
    out[k + 7] = apoapsis - radius if math.isfinite(apoapsis) else math.nan
    out[k + 8] = period if math.isfinite(period) else math.nan


@njit
def orbit_figures(r, v, mu, radius, node):
    """The elements of :func:`orbit_into` as an array of 9."""
    out = np.empty(9)
    orbit_into(out, 0, r, v, mu, radius, node)
    return out


@njit
def _vehicle_into(out, t, y, p, p_a, veh, group, n_groups, nose_radius, k_heat):
    """The engine, propellant and heating figures of a staged vehicle into ``out[VEHICLE:]``
    (see the module): nan for a throttle with no engine running and for the heat flux
    without a heat shield (``nose_radius`` 0)."""
    eng, cmd, stage = veh.eng, veh.cmd, veh.stage
    g_tau, g_thrust, tanks = GROUPS, GROUPS + n_groups, GROUPS + 2 * n_groups
    thrust = thrusts(t, y, veh.first_clock, eng, cmd, stage, p_a)
    counts = np.zeros(n_groups)
    out[g_tau:tanks] = 0.0
    total, total_tau, flow, running = 0.0, 0.0, 0.0, 0
    for e in range(eng.shape[0]):
        total += thrust[e]
        if stage[int(eng[e, E_STAGE]), S_DRY] > 0.5:
            continue
        f, tau, _, _ = engine_state(t, e, y[veh.first_clock + e], eng, cmd, p_a)
        if f <= 0.0:
            continue
        g = group[e]
        total_tau += tau
        running += 1
        out[g_tau + g] += tau
        counts[g] += 1.0
        out[g_thrust + g] += thrust[e]
        flow += f * tau * eng[e, E_MDOT]
    for g in range(n_groups):
        out[g_tau + g] = out[g_tau + g] / counts[g] if counts[g] > 0.0 else math.nan
    propellant = 0.0
    for j in range(veh.tank_bottom.shape[0]):
        out[tanks + j] = y[N_STATE + j]
        propellant += y[N_STATE + j]
    burning = 0
    for i in range(veh.motor.shape[0]):     # solid motors: in the totals (no group, no throttle)
        motor = motor_thrust(t, veh.motor, veh.curve, i)
        if motor > 0.0:
            total += motor
            flow += veh.motor[i, M_PROPELLANT] * motor / veh.motor[i, M_IMPULSE]
            burning += 1
        propellant += y[veh.first_motor + i]
    out[VEHICLE] = total_tau / running if running > 0 else math.nan
    out[VEHICLE + 1] = total
    out[VEHICLE + 2] = flow
    out[VEHICLE + 3] = running + burning
    out[VEHICLE + 4] = propellant
    out[VEHICLE + 5] = math.nan
    if nose_radius > 0.0:
        rho = air_in(veh.air, radial_height(y, p))[0]
        u, v, w = body_air_velocity(y, veh.aero.wind, p[P_SPIN])
        out[VEHICLE + 5] = sutton_graves(rho, math.sqrt(u * u + v * v + w * w), nose_radius, k_heat)


@njit
def figures(t, y, p, mu, node, geodetic, h0, dh, density, pressure, temperature, sound, wind_east,
            wind_north, veh, group, n_groups, nose_radius, k_heat, nbody, shield_temperature):
    """Every number of the state message of a body in state ``y`` (parameters ``p``,
    central body's ``mu`` m^3/s^2) at mission time ``t`` (s), in the flat layout of this
    module (the state's ECI axes; the geodetic position is WGS84's).

    ``node``: rad added to the RAAN; ``geodetic``: the body flies about Earth (the air is
    read at the WGS84 height, else at the height over the central body's ellipsoid along
    the radius, as the derivative reads it); ``h0`` ... ``wind_north``: the central body's
    air table (:meth:`~rocketsim.atmosphere.table.AtmosphereTable.arrays`, turning at
    ``p[P_SPIN]``); ``veh``: the vehicle's
    arrays (None: a rigid body, whose figures end before ``VEHICLE``), ``group`` the
    engine group of each engine (``n_groups`` groups), ``nose_radius`` the heat shield's
    (m, 0: none) and ``k_heat`` the Sutton-Graves constant of the central body's air;
    ``nbody`` True when ``p`` carries an n-body field, else None (the derivative's switch,
    :func:`~rocketsim.dynamics.third_bodies.nbody_flag`).
    The array ends with ``t`` and ``shield_temperature`` (K, nan: no shield): every
    number of the message, for :func:`rocketsim.telemetry.splice.records`."""
    if veh is None:
        out = np.empty(RIGID_WIDTH)
        out[MASS] = p[P_MASS]
    else:
        n_tanks = veh.tank_bottom.shape[0]
        out = np.empty(GROUPS + 2 * n_groups + n_tanks + 2)
        out[MASS] = vehicle_mass_properties(veh, y)[0]
    for k in range(N_STATE):        # a loop: no broadcast (and its error message) to compile
        out[k] = y[k]
    r, v = y[R:R + 3], y[V:V + 3]
    lat, lon, height, enu, surface = where_and_how_fast(r, v, t, p[P_SPIN], p[P_RADIUS], p[P_POLAR_RADIUS])
    out[LAT] = lat / DEG
    out[LON] = lon / DEG
    out[HEIGHT] = height
    out[HEIGHT_AGL] = height - (0.0 if veh is None else veh.aero.ref[A_GROUND])
    out[SPEED] = math.sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2])
    out[SURFACE_SPEED] = math.sqrt(surface[0] * surface[0] + surface[1] * surface[1] + surface[2] * surface[2])
    nx, ny, nz = rotate_components(y[Q], y[Q + 1], y[Q + 2], y[Q + 3], 1.0, 0.0, 0.0)    # the nose
    up = nx * enu[2, 0] + ny * enu[2, 1] + nz * enu[2, 2]
    out[PITCH] = math.asin(min(1.0, max(-1.0, up))) / DEG
    out[HEADING] = np.fmod(math.atan2(nx * enu[0, 0] + ny * enu[0, 1] + nz * enu[0, 2],
                                        nx * enu[1, 0] + ny * enu[1, 1] + nz * enu[1, 2]) + _TWO_PI, _TWO_PI) / DEG
    orbit_into(out, ORBIT, r, v, mu, p[P_RADIUS], node)
    rho, p_a, _, a_sound, _, air = air_here(h0, dh, density, pressure, temperature, sound,
                                            wind_east, wind_north, lat, lon,
                                            height if geodetic else radial_height(y, p), t, r, v,
                                            p[P_SPIN])
    ax, ay, az, sx, sy, sz = accelerations(t, y, p, veh, nbody)
    out[MASS + 1] = math.sqrt(ax * ax + ay * ay + az * az)
    out[SENSED] = math.sqrt(sx * sx + sy * sy + sz * sz)
    airspeed = math.sqrt(air[0] * air[0] + air[1] * air[1] + air[2] * air[2])
    out[AIRSPEED] = airspeed
    along = (nx * air[0] + ny * air[1] + nz * air[2]) / airspeed if airspeed > 0.0 else math.nan
    out[ALPHA] = math.acos(min(1.0, max(-1.0, along))) / DEG if airspeed > 0.0 else math.nan
    out[MACH] = airspeed / a_sound
    out[DYNAMIC_PRESSURE] = 0.5 * rho * airspeed * airspeed
    if veh is not None:
        _vehicle_into(out, t, y, p, p_a, veh, group, n_groups, nose_radius, k_heat)
    out[-2] = t
    out[-1] = shield_temperature
    return out


# --- the message ---------------------------------------------------------------
_NO_GROUPS = np.zeros(0, dtype=np.int64)


def values(body, gmst0: float, where) -> tuple[np.ndarray, "Shape"]:
    """Every number of the state message of ``body`` (a :class:`rocketsim.sim.world.Body`)
    at its time, in the layout of :func:`figures`, and the function that lays them out
    as the message: ``fields(values, integer)`` (``integer``: how a count is written,
    ``int`` for a message of numbers), one object per message shape.

    ``gmst0`` (rad): the Earth's sidereal angle at the epoch (the RAAN's origin about
    Earth); ``where(body)``: its (latitude rad, longitude rad, height m) away from Earth."""
    plan = _plan(body, gmst0)
    _, entry, fixed, shape, shield, earth = plan
    y, p = body.y, _held(body)
    args = (body.t, y, p) + _with_shield(body, fixed, shield)
    if not (y.flags.c_contiguous and p.flags.c_contiguous):
        v = figures(*args)
    else:
        if entry is None:
            entry = plan[1] = _entry(body.vehicle, args)
        v = entry(*args)
    if not earth:
        ground = v[HEIGHT] - v[HEIGHT_AGL]
        lat, lon, v[HEIGHT] = where(body)
        v[LAT], v[LON], v[HEIGHT_AGL] = lat / DEG, lon / DEG, v[HEIGHT] - ground
    return v, shape


def arguments(body, gmst0: float) -> tuple[tuple, "Shape"]:
    """``(the arguments of figures() after the state and parameters, shape)`` of
    ``body``'s state message at its time (see :func:`values`), for a compiled caller
    that computes figures itself (:mod:`rocketsim.sim.coast_runs`)."""
    _, _, fixed, shape, shield, _ = _plan(body, gmst0)
    return _with_shield(body, fixed, shield), shape


def _with_shield(body, fixed: tuple, shield: bool) -> tuple:
    """``fixed`` and the shield's temperature (K; nan: none), figures' last argument."""
    return fixed + ((float(body.checks.temperature) if shield else math.nan),)


def run_sampler(body, gmst0: float) -> tuple[tuple, "Shape", int, bool]:
    """``(arguments, shape, length, whole)`` for a compiled run of the staged vehicle
    ``body`` to compute its samples in (:func:`rocketsim.sim.runs.fly_run`): ``figures(t,
    y, body.p, *arguments, shield_temperature)`` is what :func:`values` computes for
    the body in state ``y`` at time ``t`` (s), ``shape`` its ``fields``, ``length`` the
    number of its figures; ``whole``: they are the whole message (about Earth; elsewhere
    :func:`values` places the body in Python)."""
    _, _, fixed, shape, _, earth = _plan(body, gmst0)
    n_groups = len(_layout(body.vehicle)[1])
    return fixed, shape, GROUPS + 2 * n_groups + body.vehicle.arrays.tank_bottom.shape[0] + 2, earth


# id(body) -> [weak reference to the body, what values() works out once for it while its
# parameters, vehicle model and checks, the air it flies in and the epoch's sidereal
# angle stay the same objects]
_PLANS: dict[int, list] = {}


def _plan(body, gmst0: float) -> tuple:
    """``[what it was worked out for, figures' entry (None until :func:`values` binds it), the
    arguments after the state and parameters but for the shield's temperature, shape, has a
    shield, flies about Earth]``
    of ``body``
    (see :data:`_PLANS`): the frame, the shape, the layout and the air looked up once,
    not at every sample."""
    earth = body.central == "earth"
    table = air_about(body.central, body.atmosphere() if earth else None)
    model = body.vehicle
    key = (body.p, model, None if model is None else model.arrays, body.checks, table, gmst0)
    found = _PLANS.get(id(body))
    if found is not None and found[0]() is body and all(a is b for a, b in zip(found[1][0], key)):
        return found[1]
    frame = _frame_of(body, gmst0)
    head = _head(body, gmst0, table)
    if model is None:
        fixed = _rigid(head, body.p)
        shape, shield = _shape(frame, None, None, False), None
    else:
        group, groups, tanks = _layout(model)
        shield = body.checks.shield if body.checks is not None else None
        fixed = head + (model.arrays, group, len(groups), shield.nose_radius if shield is not None else 0.0,
                        sutton_graves_constant(body.mu), nbody_flag(body.p))
        shape = _shape(frame, groups, tanks, shield is not None)
    plan = [key, None, fixed, shape, shield is not None, earth]     # figures' entry bound by values()
    for gone in [k for k, (ref, _) in _PLANS.items() if ref() is None]:
        del _PLANS[gone]            # bodies gone with their runs
    _PLANS[id(body)] = [weakref.ref(body), plan]
    return plan


def _head(body, gmst0: float, table) -> tuple:
    """figures' arguments after the state and parameters that every body has: its
    central body's gravity, the sidereal angle (about Earth), the air ``table``."""
    earth = body.central == "earth"
    return (body.mu, gmst0 if earth else 0.0, earth, *table.arrays())


def _rigid(head: tuple, p: np.ndarray) -> tuple:
    """A rigid body's arguments of figures after ``head`` (:func:`_head`), but for the
    shield's temperature."""
    return head + (None, _NO_GROUPS, 0, 0.0, 0.0, nbody_flag(p))


def part_arguments(body, gmst0: float) -> tuple:
    """The arguments of figures (as :func:`arguments`) of a rigid body that separates
    from the vehicle ``body`` about Earth (a fairing's half: the same central body,
    air and epoch), for a compiled caller to be typed before the body exists."""
    return _rigid(_head(body, gmst0, air_about(body.central, body.atmosphere())), body.p) + (math.nan,)


def message(body, gmst0: float, where) -> dict:
    """The state message of ``body`` at its time (see :func:`values`), as a dictionary."""
    v, fields = values(body, gmst0, where)
    return fields(v.tolist(), int)


def _held(body) -> np.ndarray:
    """``body.p``, with the other bodies' positions held for the body's time if it carries
    an n-body field that no step has held them in yet (its first sample, the sample after
    a handover): the positions the step's derivative reads
    (:func:`rocketsim.dynamics.third_bodies.hold_field`), so its accelerations are defined."""
    p = body.p
    if len(p) > P_BUCKET and p[P_BUCKET] != p[P_BUCKET]:
        p = p.copy()
        hold_field(p, body.t)
    return p


def _entry(model, args):
    """The compiled entry of ``figures(*args)``, bound once per vehicle model and n-body
    switch (and once per switch for every rigid body): :meth:`rocketsim._jit.Entries.call`
    without its look at every argument, to call with contiguous state and parameters (a
    view is called through the dispatcher). The switch (``args[-2]``, True or None) is a
    type of the entry: a body with an n-body field and one without need two."""
    nbody = args[-2]
    if model is None:
        if nbody not in _RIGID:
            _RIGID[nbody] = entry_point(figures, *args)
        return _RIGID[nbody]
    record = _model(model)
    if record[2] is None or record[2][0] is not model.arrays or record[2][1] is not nbody:
        record[2] = (model.arrays, nbody, entry_point(figures, *args))
    return record[2][2]


_RIGID: dict = {}       # the n-body switch -> the rigid bodies' entry


class Shape(NamedTuple):
    """The ``fields`` of :func:`values`: the state message of one shape from its numbers
    (``fields(values, integer)``), and the inertial frame it is expressed in."""

    frame: CentralFrame
    groups: tuple | None
    tanks: tuple | None
    shield: bool

    def __call__(self, v, integer) -> dict:
        return _fields(v, integer, self.frame.center, self.groups, self.tanks, self.shield)


@lru_cache(maxsize=64)
def _shape(frame: CentralFrame, groups, tanks, shield: bool) -> Shape:
    """The ``fields`` of :func:`values` for one message shape, the same object each time."""
    return Shape(frame, groups, tanks, shield)


def _frame_of(body, gmst0: float) -> CentralFrame:
    """The inertial frame of ``body``'s state: its field's (centre, axes, epoch), else
    Earth's ECI of the mission epoch (``gmst0``, rad)."""
    fp = field_of(body.p)
    if fp is None:
        return _earth_frame(gmst0)
    return central_frame(body.central, fp[FIELD_ROT:FIELD_ROT + 9], fp[FIELD_JD0])


@lru_cache(maxsize=4)
def _earth_frame(gmst0: float) -> CentralFrame:
    return central_frame("earth", frame_rotation("earth", 0.0, gmst0), math.nan)


def _fields(v, integer, central: str, groups, tanks, shield: bool) -> dict:
    """The state message (keys in the order of :data:`rocketsim.telemetry.schemas.BODY_STATE`)
    from the numbers ``v`` of :func:`figures` (a list, or slots standing for them)."""
    out = {"t": v[-2], "position": v[0:3], "velocity": v[3:6], "attitude": v[6:10],
           "body_rates": v[10:13], "latitude_deg": v[LAT], "longitude_deg": v[LON],
           "altitude": v[HEIGHT], "height_agl": v[HEIGHT_AGL], "inertial_speed": v[SPEED],
           "surface_speed": v[SURFACE_SPEED], "pitch_deg": v[PITCH], "heading_deg": v[HEADING],
           "orbit": _orbit(v[ORBIT:MASS]), "central_body": central}
    out.update(zip(FLIGHT_KEYS, v[MASS:VEHICLE]))
    alpha = v[ALPHA]
    out["angle_of_attack_deg"] = alpha if alpha == alpha else None
    if groups is not None:
        n = len(groups)
        throttle = v[VEHICLE]
        out["throttle"] = throttle if throttle == throttle else None
        out["group_throttle"] = {g: x if x == x else None for g, x in zip(groups, v[GROUPS:GROUPS + n])}
        out["thrust"] = v[VEHICLE + 1]
        out["group_thrust"] = dict(zip(groups, v[GROUPS + n:GROUPS + 2 * n]))
        out["mass_flow"] = v[VEHICLE + 2]
        out["engines_running"] = integer(v[VEHICLE + 3])
        out["propellant"] = v[VEHICLE + 4]
        out["propellant_tanks"] = dict(zip(tanks, v[GROUPS + 2 * n:-2]))
        if shield:
            out["heat_flux"] = v[VEHICLE + 5]
            out["shield_temperature"] = v[-1]
    return out


def orbit(body, gmst0: float) -> dict:
    """The ``orbit`` field of ``body``'s state message (see :func:`message`)."""
    return _orbit(orbit_figures(body.position, body.velocity, body.mu, body.p[P_RADIUS],
                                gmst0 if body.central == "earth" else 0.0).tolist())


def _orbit(values: list) -> dict:
    """The orbit's fields from its figures, null for an apoapsis and period not elliptic."""
    out = dict(zip(ORBIT_KEYS, values))
    if values[7] != values[7]:
        out["apoapsis_altitude"] = None
    if values[8] != values[8]:
        out["period"] = None
    return out


@lru_cache(maxsize=64)
def _keys(names: tuple[str, ...]) -> tuple[str, ...]:
    """Field names of tanks or engine groups (``stage/name`` -> ``stage_name``)."""
    return tuple("".join(c if c.isalnum() or c in "-_" else "_" for c in n) for n in names)


# id(model) -> [weak reference to the model, its layout, (its arrays, figures' entry) or None]
_MODELS: dict[int, list] = {}


def _layout(model) -> tuple:
    """``(engine group index of each engine, group keys, tank keys)`` of ``model``,
    worked out once per model (a staging builds new ones)."""
    return _model(model)[1]


def _model(model) -> list:
    """What is worked out once per vehicle model (see :data:`_MODELS`)."""
    found = _MODELS.get(id(model))
    if found is not None and found[0]() is model:
        return found
    keys = _keys(tuple(model.engine_groups))
    groups = tuple(dict.fromkeys(keys))
    layout = (np.array([groups.index(k) for k in keys], dtype=np.int64), groups,
              _keys(tuple(model.tank_names)))
    for key in [k for k, (ref, _, _) in _MODELS.items() if ref() is None]:
        del _MODELS[key]            # models gone with their runs
    found = _MODELS[id(model)] = [weakref.ref(model), layout, None]
    return found
