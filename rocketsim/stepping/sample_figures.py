"""The numbers of one body's telemetry sample, every one of them from one compiled call.

:func:`figures` computes, for one body at its time, the state and everything
derived from it (geodetic position, speed, orbit elements, mass,
accelerations, air data; for a staged vehicle the engines, propellant and
heating) into one flat float64 array, in the slots named here;
:mod:`rocketsim.sim.sampling` lays that array out as the state message, and the
compiled runs (:mod:`rocketsim.stepping.runs`) compute it at the sample steps
they fly through.

Read-only: nothing here changes the state, the engines' commands or the checks,
and no sensor is read (the figures are the truth). The computations are those
of the flight itself: the readings' geodetic position and the day's air
(:func:`rocketsim.frames.local.where_and_how_fast`, ``air_here``), the
derivative the integrator uses (:func:`rocketsim.stepping.checked_step.accelerations`),
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

The accelerations are those of the body's flight model: a staged vehicle's
derivative (thrust, aerodynamics, contact); a tumbling part's gravity and
point-mass drag, its ``C_D A/m`` (:mod:`rocketsim.dynamics.free_body`) times the
dynamic pressure, against the air-relative velocity, in the readings' air; a
rigid body's gravity alone (in free fall it senses nothing). The airspeed, angle
of attack and Mach are the body's motion through the readings' air; the dynamic
pressure is the air's on a body it acts on (a staged vehicle with aerodynamics, a
tumbling part), missing for a body the flight model flies without air (a rigid
body with no drag area, a vehicle with ``aerodynamics: false``), whatever air it
passes through.

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

A missing value is nan in the figures.
"""

import math

import numpy as np

from rocketsim.jit import njit
from rocketsim.atmosphere.table import air_in
from rocketsim.constants import DEG
from rocketsim.dynamics.derivative import radial_height
from rocketsim.dynamics.free_body import drag_factor
from rocketsim.flight.readings import air_here
from rocketsim.frames.elements import elements_tuple
from rocketsim.frames.local import body_air_velocity, where_and_how_fast
from rocketsim.frames.quaternion import rotate_components
from rocketsim.layout import N_STATE, P_MASS, P_POLAR_RADIUS, P_RADIUS, P_SPIN, Q, R, V
from rocketsim.stepping.checked_step import accelerations
from rocketsim.vehicle.aero import A_GROUND, A_ON
from rocketsim.vehicle.engines import E_MDOT, E_STAGE, S_DRY, engine_state, thrusts
from rocketsim.vehicle.heating import sutton_graves
from rocketsim.vehicle.mass_properties import vehicle_mass_properties
from rocketsim.vehicle.motors import M_IMPULSE, M_PROPELLANT, motor_thrust

_TWO_PI = 2.0 * math.pi

# the flat array of figures(): the state (position, velocity, attitude, rates), then
# deg, deg, m (altitude), m (height above the ground), m/s (inertial), m/s (over the ground), deg, deg
(SAMPLE_LAT, SAMPLE_LON, SAMPLE_HEIGHT, SAMPLE_HEIGHT_AGL, SAMPLE_SPEED, SAMPLE_SURFACE_SPEED, SAMPLE_PITCH,
 SAMPLE_HEADING) = range(N_STATE, N_STATE + 8)
SAMPLE_ORBIT = SAMPLE_HEADING + 1                       # ORBIT_KEYS, in order
ORBIT_KEYS = ("semi_major_axis", "eccentricity", "inclination_deg", "raan_deg", "arg_periapsis_deg",
              "true_anomaly_deg", "periapsis_altitude", "apoapsis_altitude", "period")
SAMPLE_MASS = SAMPLE_ORBIT + len(ORBIT_KEYS)            # kg, then FLIGHT_KEYS in order
FLIGHT_KEYS = ("mass", "acceleration", "sensed_acceleration", "airspeed", "angle_of_attack_deg", "mach",
               "dynamic_pressure")
# m/s^2, m/s, deg, -, Pa
SAMPLE_SENSED, SAMPLE_AIRSPEED, SAMPLE_ALPHA, SAMPLE_MACH, SAMPLE_DYNAMIC_PRESSURE = range(SAMPLE_MASS + 2,
                                                                                          SAMPLE_MASS + 7)
SAMPLE_VEHICLE = SAMPLE_MASS + len(FLIGHT_KEYS)         # a staged vehicle: VEHICLE_KEYS, then by group
VEHICLE_KEYS = ("throttle", "thrust", "mass_flow", "engines_running", "propellant", "heat_flux")
SAMPLE_ENGINES_RUNNING = SAMPLE_VEHICLE + 3             # a count
SAMPLE_GROUPS = SAMPLE_VEHICLE + len(VEHICLE_KEYS)      # throttle by group, thrust by group, tanks
N_SAMPLE_RIGID = SAMPLE_VEHICLE + 2                     # a rigid body's figures: t and nan (no shield) end them


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
    """The engine, propellant and heating figures of a staged vehicle into ``out[SAMPLE_VEHICLE:]``
    (see the module): nan for a throttle with no engine running and for the heat flux
    without a heat shield (``nose_radius`` 0)."""
    eng, cmd, stage = veh.eng, veh.cmd, veh.stage
    g_tau, g_thrust, tanks = SAMPLE_GROUPS, SAMPLE_GROUPS + n_groups, SAMPLE_GROUPS + 2 * n_groups
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
    out[SAMPLE_VEHICLE] = total_tau / running if running > 0 else math.nan
    out[SAMPLE_VEHICLE + 1] = total
    out[SAMPLE_VEHICLE + 2] = flow
    out[SAMPLE_ENGINES_RUNNING] = running + burning
    out[SAMPLE_VEHICLE + 4] = propellant
    out[SAMPLE_VEHICLE + 5] = math.nan
    if nose_radius > 0.0:
        rho = air_in(veh.air, radial_height(y, p))[0]
        u, v, w = body_air_velocity(y, veh.aero.wind, p[P_SPIN])
        out[SAMPLE_VEHICLE + 5] = sutton_graves(rho, math.sqrt(u * u + v * v + w * w), nose_radius, k_heat)


@njit
def figures(t, y, p, mu, node, geodetic, h0, dh, density, pressure, temperature, sound, wind_east,
            wind_north, veh, group, n_groups, nose_radius, k_heat, area_mass, length, nbody,
            shield_temperature):
    """Every number of the state message of a body in state ``y`` (parameters ``p``,
    central body's ``mu`` m^3/s^2) at mission time ``t`` (s), in the flat layout of this
    module (the state's ECI axes; the geodetic position is WGS84's).

    ``node``: rad added to the RAAN; ``geodetic``: the body flies about Earth (the air is
    read at the WGS84 height, else at the height over the central body's ellipsoid along
    the radius, as the derivative reads it); ``h0`` ... ``wind_north``: the central body's
    air table (:meth:`~rocketsim.atmosphere.table.AtmosphereTable.arrays`, turning at
    ``p[P_SPIN]``); ``veh``: the vehicle's
    arrays (None: a rigid body, whose figures end before ``SAMPLE_VEHICLE``), ``group`` the
    engine group of each engine (``n_groups`` groups), ``nose_radius`` the heat shield's
    (m, 0: none) and ``k_heat`` the Sutton-Graves constant of the central body's air;
    ``area_mass`` (m^2/kg; 0: none) and ``length`` (m) a rigid body's tumbling drag
    (:class:`rocketsim.sim.body.Part`; 0 for a staged vehicle: its aerodynamics are ``veh``'s);
    ``nbody`` True when ``p`` carries an n-body field, else None (the derivative's switch,
    :func:`~rocketsim.dynamics.third_bodies.nbody_flag`).
    The array ends with ``t`` and ``shield_temperature`` (K, nan: no shield): every
    number of the message, for :func:`rocketsim.telemetry.splice.records`."""
    if veh is None:
        out = np.empty(N_SAMPLE_RIGID)
        out[SAMPLE_MASS] = p[P_MASS]
    else:
        n_tanks = veh.tank_bottom.shape[0]
        out = np.empty(SAMPLE_GROUPS + 2 * n_groups + n_tanks + 2)
        out[SAMPLE_MASS] = vehicle_mass_properties(veh, y)[0]
    for k in range(N_STATE):        # a loop: no broadcast (and its error message) to compile
        out[k] = y[k]
    r, v = y[R:R + 3], y[V:V + 3]
    lat, lon, height, enu, surface = where_and_how_fast(r, v, t, p[P_SPIN], p[P_RADIUS], p[P_POLAR_RADIUS])
    out[SAMPLE_LAT] = lat / DEG
    out[SAMPLE_LON] = lon / DEG
    out[SAMPLE_HEIGHT] = height
    out[SAMPLE_HEIGHT_AGL] = height - (0.0 if veh is None else veh.aero.ref[A_GROUND])
    out[SAMPLE_SPEED] = math.sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2])
    out[SAMPLE_SURFACE_SPEED] = math.sqrt(surface[0] * surface[0] + surface[1] * surface[1]
                                          + surface[2] * surface[2])
    nx, ny, nz = rotate_components(y[Q], y[Q + 1], y[Q + 2], y[Q + 3], 1.0, 0.0, 0.0)    # the nose
    up = nx * enu[2, 0] + ny * enu[2, 1] + nz * enu[2, 2]
    out[SAMPLE_PITCH] = math.asin(min(1.0, max(-1.0, up))) / DEG
    out[SAMPLE_HEADING] = np.fmod(math.atan2(nx * enu[0, 0] + ny * enu[0, 1] + nz * enu[0, 2],
                                             nx * enu[1, 0] + ny * enu[1, 1] + nz * enu[1, 2]) + _TWO_PI,
                                  _TWO_PI) / DEG
    orbit_into(out, SAMPLE_ORBIT, r, v, mu, p[P_RADIUS], node)
    rho, p_a, _, a_sound, wind, air = air_here(h0, dh, density, pressure, temperature, sound,
                                            wind_east, wind_north, lat, lon,
                                            height if geodetic else radial_height(y, p), t, r, v,
                                            p[P_SPIN])
    ax, ay, az, sx, sy, sz = accelerations(t, y, p, veh, nbody)
    if veh is None:
        in_air = area_mass > 0.0
    else:
        in_air = veh.aero.ref[A_ON] > 0.5
    airspeed = math.sqrt(air[0] * air[0] + air[1] * air[1] + air[2] * air[2])
    q = 0.5 * rho * airspeed * airspeed if in_air else math.nan
    if veh is None and q > 0.0:      # a tumbling part's drag, against the air-relative velocity
        drag = -drag_factor(y, p, (h0, dh, density, pressure, temperature, sound, wind_east, wind_north), wind,
                            area_mass, length) * q / airspeed
        ax, ay, az = ax + drag * air[0], ay + drag * air[1], az + drag * air[2]
        sx, sy, sz = sx + drag * air[0], sy + drag * air[1], sz + drag * air[2]
    out[SAMPLE_MASS + 1] = math.sqrt(ax * ax + ay * ay + az * az)
    out[SAMPLE_SENSED] = math.sqrt(sx * sx + sy * sy + sz * sz)
    out[SAMPLE_AIRSPEED] = airspeed
    along = (nx * air[0] + ny * air[1] + nz * air[2]) / airspeed if airspeed > 0.0 else math.nan
    out[SAMPLE_ALPHA] = math.acos(min(1.0, max(-1.0, along))) / DEG if airspeed > 0.0 else math.nan
    out[SAMPLE_MACH] = airspeed / a_sound
    out[SAMPLE_DYNAMIC_PRESSURE] = q
    if veh is not None:
        _vehicle_into(out, t, y, p, p_a, veh, group, n_groups, nose_radius, k_heat)
    out[-2] = t
    out[-1] = shield_temperature
    return out
