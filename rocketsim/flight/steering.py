"""The autopilot's step, compiled: from the navigation estimate to the actuator commands.

One compiled call per step (:func:`steer_step`) does what
:mod:`rocketsim.flight.autopilot` documents (the control law, its gains, how the
torque is shared between the gimbals, the grid fins and the RCS): it derives
from the estimated state what the readings derive
(:class:`~rocketsim.flight.readings.StateView`: the body axes, the local east,
north and up, the air), the commanded nose direction and the attitude error,
the torque of the damped response less the destabilising aerodynamic moment
(:mod:`rocketsim.flight.aero_feedforward`), the mass properties and the
engines' thrust, the grid fins' gains measured on their model, and writes the
gimbal and grid-fin commands into the vehicle's arrays in place. The torque
left to the RCS thrusters is returned; their bounded least squares stays in
Python (:func:`rocketsim.flight.autopilot.rcs_command`) while they are on.

A commanded attitude is handed over as six numbers
(:func:`rocketsim.dynamics.rails.command_code`, the encoding the sleep rails
read too; its nose direction is :func:`rocketsim.dynamics.rails.nose_target`).
Units: SI, vectors in ECI unless said to be in body axes (x the nose).
"""

from __future__ import annotations

import math

import numpy as np

from rocketsim.jit import njit
from rocketsim.dynamics.rails import nose_target
from rocketsim.layout import P_POLAR_RADIUS, P_RADIUS, P_SPIN, Q, R, V, W
from rocketsim.flight.aero_feedforward import destabilising_moment
from rocketsim.flight.navigation import estimate
from rocketsim.flight.readings import air_here
from rocketsim.frames.local import VERTICAL, where_and_how_fast
from rocketsim.frames.quaternion import quat_from_matrix, quat_to_matrix
from rocketsim.frames.vectors import compiled_cross
from rocketsim.vehicle.engines import E_GIMBAL_RANGE, E_X, command_gimbals, thrusts
from rocketsim.vehicle.grid_fins import G_MAX, command, grid_fin_forces
from rocketsim.vehicle.mass_properties import vehicle_mass_properties

OMEGA_N = 1.0     # rad/s, natural frequency of the attitude response
ZETA = 0.9        # damping ratio
RATE_LIMIT = 0.15  # rad/s, largest commanded turn rate (pitch/yaw)
FIN_PROBE = 0.05  # rad, deflection used to measure the grid fins' moment per radian


@njit
def _in_body(axes, vector):
    """``axes.T @ vector``: an ECI vector in the body axes of ``axes`` (body -> ECI)."""
    out = np.empty(3)
    for k in range(3):
        out[k] = axes[0, k] * vector[0] + axes[1, k] * vector[1] + axes[2, k] * vector[2]
    return out


@njit(inline="always")
def attitude_error(axes, target):
    """Rotation vector (rad, body axes) that turns the nose (body x) onto ``target`` (ECI).

    ``axes`` is the body -> ECI matrix; the result has no roll component.
    """
    d = _in_body(axes, target)                  # target in body axes
    out = np.zeros(3)
    s = math.sqrt(d[2] * d[2] + d[1] * d[1])    # |x_b cross d|, x_b cross d = (0, -d_z, d_y)
    angle = math.atan2(s, d[0])
    if s == 0.0:
        if d[0] < 0:
            out[2] = math.pi
        return out
    out[1] = -d[2] / s * angle
    out[2] = d[1] / s * angle
    return out


@njit(inline="always")
def target_axes(nose, enu, roll):
    """``(found, matrix)``: the body -> ECI matrix of the attitude with the nose along
    ``nose`` (unit, ECI) turned ``roll`` rad about it from the belly-to-the-ground
    reference (``enu`` rows: the local east, north, up unit vectors, ECI); ``found``
    false within 0.01 deg of the vertical (no reference)."""
    up = enu[2]
    out = np.empty((3, 3))
    sin_pitch = min(max(nose[0] * up[0] + nose[1] * up[1] + nose[2] * up[2], -1.0), 1.0)
    if abs(sin_pitch) >= VERTICAL:
        return False, out
    horizontal = np.empty(3)
    for i in range(3):
        horizontal[i] = nose[i] - sin_pitch * up[i]
    size = math.sqrt(horizontal[0] * horizontal[0] + horizontal[1] * horizontal[1]
                     + horizontal[2] * horizontal[2])
    cos_pitch = math.sqrt(1.0 - sin_pitch * sin_pitch)
    z_ref = np.empty(3)
    for i in range(3):
        z_ref[i] = sin_pitch * (horizontal[i] / size) - cos_pitch * up[i]
    side = compiled_cross(nose, z_ref)
    z_body = np.empty(3)
    for i in range(3):
        z_body[i] = math.cos(roll) * z_ref[i] + math.sin(roll) * side[i]
    y_body = compiled_cross(z_body, nose)
    for i in range(3):
        out[i, 0] = nose[i]
        out[i, 1] = y_body[i]
        out[i, 2] = z_body[i]
    return True, out


@njit(inline="always")
def rotation_error(axes, target):
    """Rotation vector (rad, body axes) that turns the body axes ``axes`` onto the
    target axes ``target`` (both body -> ECI matrices), all three components."""
    turn = np.empty((3, 3))                     # axes.T @ target
    for i in range(3):
        for j in range(3):
            turn[i, j] = axes[0, i] * target[0, j] + axes[1, i] * target[1, j] + axes[2, i] * target[2, j]
    q = quat_from_matrix(turn)
    if q[0] < 0.0:
        q = -q
    s = math.sqrt(q[1] * q[1] + q[2] * q[2] + q[3] * q[3])
    out = np.zeros(3)
    if s == 0.0:
        return out
    angle = 2.0 * math.atan2(s, q[0])
    for k in range(3):
        out[k] = q[k + 1] / s * angle
    return out


@njit(inline="always")
def angular_acceleration(error, rates):
    """Commanded angular acceleration (rad/s^2, body axes) for the rate-limited damped
    response of :mod:`rocketsim.flight.autopilot`; ``error`` (rad) and ``rates``
    (rad/s) in body axes. A roll component of ``error`` (a commanded roll) is flown
    like pitch and yaw."""
    wanted = OMEGA_N / (2.0 * ZETA) * error
    if error[0] == 0.0:
        size = math.hypot(wanted[1], wanted[2])
    else:
        size = math.sqrt(wanted[0] * wanted[0] + wanted[1] * wanted[1] + wanted[2] * wanted[2])
    if size > RATE_LIMIT:
        wanted = wanted * (RATE_LIMIT / size)
    return 2.0 * ZETA * OMEGA_N * (wanted - rates)


@njit
def fin_moments(aero, u, v, w, rho, sound, x_cm, pitch, yaw, roll):
    """Moment ``(M_x, M_y, M_z)`` (N m, body axes, about the centre of mass) of the grid
    fins of ``aero`` held at the deflections ``pitch``, ``yaw``, ``roll`` (rad), in air
    moving at ``(u, v, w)`` (m/s, body axes, the vehicle relative to the air) of
    density ``rho`` (kg/m^3) and speed of sound ``sound`` (m/s)."""
    held = np.zeros_like(aero.grid_cmd)
    command(aero.grid, held, 0.0, pitch, yaw, roll)
    forces = grid_fin_forces(1e9, u, v, w, 0.0, 0.0, 0.0, rho, sound, x_cm, aero.grid, held)
    return forces[3], forces[4], forces[5]


@njit(inline="always")
def fin_gains(aero, u, v, w, rho, sound, x_cm):
    """Moment per radian (N m/rad) of the pitch, yaw and roll deflections about body
    y, z, x, measured on the fin model with a ``FIN_PROBE`` deflection (arguments as
    :func:`fin_moments`)."""
    base = fin_moments(aero, u, v, w, rho, sound, x_cm, 0.0, 0.0, 0.0)
    pitch = fin_moments(aero, u, v, w, rho, sound, x_cm, FIN_PROBE, 0.0, 0.0)
    yaw = fin_moments(aero, u, v, w, rho, sound, x_cm, 0.0, FIN_PROBE, 0.0)
    roll = fin_moments(aero, u, v, w, rho, sound, x_cm, 0.0, 0.0, FIN_PROBE)
    gains = np.empty(3)
    gains[0] = (pitch[1] - base[1]) / FIN_PROBE
    gains[1] = (yaw[2] - base[2]) / FIN_PROBE
    gains[2] = (roll[0] - base[0]) / FIN_PROBE
    return gains


@njit
def steer_step(veh, y, p, t, t_nav, r, v, q, w, ambient_pressure, air_table, code, fins, rcs):
    """One step of the autopilot of the staged vehicle ``veh`` (its arrays) with state
    ``y`` at mission time ``t`` (s): commands the gimbals of its firing engines and,
    when ``fins``, its grid fins (in place, in ``veh.cmd`` and ``veh.aero.grid_cmd``).

    The autopilot reads the navigation estimate ``r``, ``v``, ``q``, ``w`` (position m,
    velocity m/s, attitude quaternion body -> ECI, body rates rad/s) at ``t_nav`` (s)
    in the central body's air (``air_table``: the tuple of
    :meth:`~rocketsim.atmosphere.table.AtmosphereTable.arrays`), its local vertical and
    turning ground those of the central body of the parameters ``p`` (ellipsoid and
    ``P_SPIN``). The engines' thrust
    is the truth's, at ``ambient_pressure`` (Pa; nan: the estimate is the truth, its
    air's pressure). ``code``: the command
    (:func:`~rocketsim.dynamics.rails.command_code`; its last entry the roll, rad, nan
    for none).

    Returns ``(x_cm, tau_x, tau_y, tau_z)``: the centre of mass's station (m) and the
    torque (N m, body axes) left to the RCS thrusters when ``rcs`` (zero otherwise).
    """
    lat, lon, height, enu, surface_velocity = where_and_how_fast(r, v, t_nav, p[P_SPIN], p[P_RADIUS],
                                                                 p[P_POLAR_RADIUS])
    rho, p_a, _, sound, _, air = air_here(*air_table, lat, lon, height, t_nav, r, v, p[P_SPIN])
    if not math.isnan(ambient_pressure):
        p_a = ambient_pressure
    axes = quat_to_matrix(q)
    nose = nose_target(code, r, v, enu, surface_velocity, t_nav)
    roll = code[5]
    found = False
    if not math.isnan(roll):
        found, target = target_axes(nose, enu, roll)
        if found:
            error = rotation_error(axes, target)
    if not found:
        error = attitude_error(axes, nose)
    _, x_cm, ixx, iyy, izz = vehicle_mass_properties(veh, y)
    alpha = angular_acceleration(error, w)
    torque = np.empty(3)
    torque[0] = ixx * alpha[0]
    torque[1] = iyy * alpha[1]
    torque[2] = izz * alpha[2]
    eng = veh.eng
    each = thrusts(t, y, veh.first_clock, eng, veh.cmd, veh.stage, p_a)
    firing = np.flatnonzero(each > 0.0)
    thrust = 0.0
    for e in range(each.shape[0]):
        thrust += each[e]
    air_body = _in_body(axes, air)
    u, v_air, w_air = air_body[0], air_body[1], air_body[2]
    aero = veh.aero
    my, mz = destabilising_moment(aero, u, v_air, w_air, w[0], w[1], w[2], rho, sound, thrust, x_cm)
    torque[1] -= my                     # aero feedforward
    torque[2] -= mz
    engine_authority = lever = cone = 0.0
    if firing.shape[0] and thrust > 0.0:
        for e in range(each.shape[0]):
            lever += each[e] * (x_cm - eng[e, E_X])
        lever /= thrust
        cone = eng[firing[0], E_GIMBAL_RANGE]
        for e in firing:
            cone = min(cone, eng[e, E_GIMBAL_RANGE])
        engine_authority = max(lever, 0.0) * thrust * math.sin(cone)
    fin_torque = np.zeros(3)            # body x, y, z
    grid = aero.grid
    if fins and grid.shape[0] and rho > 0.0:
        gains = fin_gains(aero, u, v_air, w_air, rho, sound, x_cm)     # pitch, yaw, roll
        fin_max = grid[0, G_MAX]
        for i in range(grid.shape[0]):
            fin_max = min(fin_max, grid[i, G_MAX])
        deflect = np.zeros(3)
        for k in range(3):
            axis = (1, 2, 0)[k]
            if gains[k] == 0.0:
                continue
            authority = abs(gains[k]) * fin_max
            share = 1.0 if axis == 0 else authority / (authority + engine_authority)
            fin_torque[axis] = share * torque[axis]
            deflect[k] = fin_torque[axis] / gains[k]
        command(grid, aero.grid_cmd, t, deflect[0], deflect[1], deflect[2])
    rest = torque - fin_torque
    if not firing.shape[0] or thrust <= 0.0:
        if not rcs:
            rest[:] = 0.0
        return x_cm, rest[0], rest[1], rest[2]
    # the gimbals of every firing engine alike: tau_y = L T g_z, tau_z = -L T g_y
    gy = gz = 0.0
    if lever > 0.0:
        gy, gz = -rest[2] / (lever * thrust), rest[1] / (lever * thrust)
    size = math.hypot(gy, gz)
    if rcs:
        inside = 1.0 if size <= cone else cone / size      # the part the gimbals can reach
        rest[1] *= 1.0 - inside
        rest[2] *= 1.0 - inside
    else:
        rest[:] = 0.0
    command_gimbals(eng, veh.cmd, firing, t, gy, gz, size)
    return x_cm, rest[0], rest[1], rest[2]


@njit(inline="always")     # small: typed in its callers, no kernel of its own
def steer_on_estimate(veh, y, p, t, errors, j, code, fins):
    """The autopilot's step (:func:`steer_step`, no RCS) of the staged vehicle ``veh`` with
    state ``y`` at mission time ``t`` (s), as the world's loop runs it before a step
    (:meth:`rocketsim.flight.fc.FlightComputer.autopilot`), reading the navigation
    estimate of row ``j`` of ``errors`` (:meth:`rocketsim.flight.sensors.Sensors.run_errors`;
    none: the truth) in the vehicle's air (the day's): the truth itself, or
    :func:`rocketsim.flight.navigation.estimate` with the engines' thrust at the truth's
    ambient pressure (its air's, at the true height, as the readings' ``air``)."""
    if errors.shape[0] == 0:
        steer_step(veh, y, p, t, t, y[R:R + 3], y[V:V + 3], y[Q:Q + 4], y[W:W + 3], math.nan, veh.air, code, fins,
                   False)
        return
    r, v, q, w = estimate(y, errors, j)
    lat, lon, height, _, _ = where_and_how_fast(y[R:R + 3], y[V:V + 3], t, p[P_SPIN], p[P_RADIUS],
                                                p[P_POLAR_RADIUS])
    ambient = air_here(*veh.air, lat, lon, height, t, y[R:R + 3], y[V:V + 3], p[P_SPIN])[1]
    steer_step(veh, y, p, t, t, r, v, q, w, ambient, veh.air, code, fins, False)
