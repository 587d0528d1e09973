"""The autopilot: turns a commanded attitude into gimbal, grid-fin and RCS commands, once per step.

A program commands where the nose should point (a direction in a named frame,
pitch/heading, or a mode that follows the flight: prograde, retrograde,
surface retrograde, normal, radial). Each step the autopilot, reading the
navigation estimate like the program, computes the attitude error ``e`` as a
rotation vector in body axes (no roll component unless a roll is
commanded, below) and asks for the angular
acceleration of a damped second-order response with a rate limit::

    w_cmd = clip(omega_n / (2 zeta) e, |w_cmd| <= RATE_LIMIT)   (pitch and yaw)
    w_cmd_x = 0                          (roll: damped only, unless a roll is commanded)
    alpha = 2 zeta omega_n (w_cmd - w)

with ``omega_n = 1 rad/s``, ``zeta = 0.9`` and ``RATE_LIMIT = 0.15 rad/s``
(8.6 deg/s). Below the limit this is exactly
``alpha = omega_n^2 e - 2 zeta omega_n w``; a large turn (a booster's flip)
is flown at the limited rate instead of winding up an overshoot. The torque
``tau = I alpha`` (I the principal inertias about the centre of mass) goes
to two actuators, shared in proportion to their authority on each axis:

* the gimbals of every firing engine alike: an engine a lever arm ``L`` behind
  the centre of mass with thrust ``T`` gives ``tau_y = L T g_z`` and
  ``tau_z = -L T g_y`` (small angles; the engine model's sign convention), so
  ``g_z = tau_y / (L T)``, ``g_y = -tau_z / (L T)``; authority ``L T sin(g_max)``.
  Clipped by each engine's cone and reached at its slew rate.
* the grid fins, once the program has called ``fc.deploy_grid_fins()`` and
  while the air is there: their moment per radian of the pitch, yaw and roll
  deflections is measured each step from the fin model itself
  (:func:`rocketsim.vehicle.grid_fins.grid_fin_forces` at the estimated air
  velocity, density and Mach, ``B_k = (M_k(FIN_PROBE) - M_k(0)) / FIN_PROBE``),
  so the sign reversal of a tail-first descent and the choking near Mach 1
  are in the gain; ``delta_k = tau_k / B_k``, authority ``|B_k| delta_max``,
  clipped to the fins' range and reached at their slew rate.
* the reaction-control thrusters (:mod:`rocketsim.vehicle.rcs`), once the
  program has called ``fc.rcs(True)``: they supply what the other two leave,
  ``tau_rcs = tau - tau_fins - s tau_gimbal`` on all three axes, where
  ``s = min(1, g_max / |g|)`` is the part of the commanded gimbal angle
  ``g = (g_y, g_z)`` inside the engines' cone (all of it in a coast). Each
  thruster ``i`` gives ``a_i = (r_i - r_cm) x T_i d_i`` (N m) per unit command;
  the commands ``f_i`` in [0, 1] (the thrusters' proportional model: a fraction of
  full thrust held for the step, no minimum impulse, no slew) are the bounded
  least-squares solution of ``sum_i a_i f_i = tau_rcs`` (bounded-variable least
  squares, deterministic); a thruster whose tank is empty is left out. Beyond
  the thrusters' authority the torque saturates (bang-bang at full thrust).

Roll: with no roll commanded (``roll=None``) the roll rate is only damped
(``w_cmd_x = 0``) by whatever can act on it (grid fins, RCS). With a roll
commanded (``fc.point(pitch, heading, roll)``, or a roll with ``point_at`` and
``hold``), the target is a whole attitude: the nose on the target direction and
the body z axis turned ``roll`` about it from the belly-to-the-ground reference
of :attr:`rocketsim.flight.readings.StateView.euler` (so ``fc.roll`` reads it
back). The error is then the rotation vector (body axes) from the body axes onto
the target axes, and the same law acts on all three axes with the rate limit on
the norm of the three commanded rates. Within 0.01 deg of the vertical the
roll reference is undefined and the roll command is ignored (nose only).

In the air, nose first, the torque also cancels the destabilising part of the
modelled aerodynamic moment (:mod:`rocketsim.flight.aero_feedforward`), so an
unfinned launcher through max-Q keeps the same second-order response as in
vacuum. With neither thrust nor deployed fins in the air the autopilot commands
nothing. A booster falling tail first is statically unstable bare and stable
with its grid fins (tests/test_aero.py); the fins' restoring moment at zero
deflection is left to help, not cancelled.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import lsq_linear

from rocketsim.flight.aero_feedforward import destabilising_moment
from rocketsim.vehicle import engines as E
from rocketsim.vehicle import grid_fins as G
from rocketsim.vehicle import rcs as RC
from rocketsim.frames.quaternion import quat_from_matrix
from rocketsim.flight.readings import _VERTICAL

OMEGA_N = 1.0     # rad/s, natural frequency of the attitude response
ZETA = 0.9        # damping ratio
RATE_LIMIT = 0.15  # rad/s, largest commanded turn rate (pitch/yaw)
FIN_PROBE = 0.05  # rad, deflection used to measure the grid fins' moment per radian

MODES = ("prograde", "retrograde", "surface_prograde", "surface_retrograde", "normal",
         "antinormal", "radial", "antiradial")


@dataclass(frozen=True)
class AttitudeCommand:
    """Where the nose should point: a fixed ECI direction, pitch/heading, or a mode."""

    direction: np.ndarray | None = None     # unit vector, ECI
    pitch: float | None = None              # rad above the local horizon
    heading: float | None = None            # rad from north towards east
    mode: str | None = None
    roll: float | None = None               # rad about the nose (StateView.euler's); None: free, damped

    def target(self, view) -> np.ndarray:
        """The commanded nose direction (unit vector, ECI) for the state ``view``."""
        if self.direction is not None:
            return self.direction
        if self.mode is not None:
            sign = -1.0 if self.mode.startswith(("retro", "anti", "surface_retro")) else 1.0
            base = {"prograde": "prograde", "retrograde": "prograde",
                    "surface_prograde": "surface_prograde", "surface_retrograde": "surface_prograde",
                    "normal": "normal", "antinormal": "normal",
                    "radial": "radial", "antiradial": "radial"}[self.mode]
            return sign * getattr(view, base)
        east, north, up = view.enu
        horizontal = math.sin(self.heading) * east + math.cos(self.heading) * north
        return math.cos(self.pitch) * horizontal + math.sin(self.pitch) * up


def attitude_error(axes: np.ndarray, target: np.ndarray) -> np.ndarray:
    """Rotation vector (rad, body axes) that turns the nose (body x) onto ``target`` (ECI).

    ``axes`` is the body -> ECI matrix; the result has no roll component.
    """
    d = axes.T @ target                      # target in body axes
    axis = np.array([0.0, -d[2], d[1]])      # x_b cross d
    s = float(np.linalg.norm(axis))
    angle = math.atan2(s, float(d[0]))
    if s == 0.0:
        return np.array([0.0, 0.0, math.pi]) if d[0] < 0 else np.zeros(3)
    return axis / s * angle


def target_axes(nose: np.ndarray, enu, roll: float) -> np.ndarray | None:
    """Body -> ECI matrix of the attitude with the nose along ``nose`` (unit, ECI) turned
    ``roll`` rad about it from the belly-to-the-ground reference (``enu`` the local east,
    north, up unit vectors, ECI); None within 0.01 deg of the vertical (no reference)."""
    east, north, up = enu
    sin_pitch = float(np.clip(nose @ up, -1.0, 1.0))
    if abs(sin_pitch) >= _VERTICAL:
        return None
    horizontal = nose - sin_pitch * up
    horizontal = horizontal / np.linalg.norm(horizontal)
    z_ref = sin_pitch * horizontal - math.sqrt(1.0 - sin_pitch * sin_pitch) * up
    z_body = math.cos(roll) * z_ref + math.sin(roll) * np.cross(nose, z_ref)
    return np.column_stack((nose, np.cross(z_body, nose), z_body))


def rotation_error(axes: np.ndarray, target: np.ndarray) -> np.ndarray:
    """Rotation vector (rad, body axes) that turns the body axes ``axes`` onto the
    target axes ``target`` (both body -> ECI matrices), all three components."""
    q = quat_from_matrix(axes.T @ target)
    if q[0] < 0.0:
        q = -q
    s = float(np.linalg.norm(q[1:]))
    if s == 0.0:
        return np.zeros(3)
    return q[1:] / s * (2.0 * math.atan2(s, float(q[0])))


def command_error(command: "AttitudeCommand", view) -> np.ndarray:
    """The attitude error (rad, body axes) of ``command`` for the state ``view``: the
    nose's (no roll component) or, with a roll commanded, the whole attitude's."""
    nose = command.target(view)
    if command.roll is not None:
        target = target_axes(nose, view.enu, command.roll)
        if target is not None:
            return rotation_error(view.axes, target)
    return attitude_error(view.axes, nose)


def angular_acceleration(error: np.ndarray, rates: np.ndarray) -> np.ndarray:
    """Commanded angular acceleration (rad/s^2, body axes) for the rate-limited damped
    response of the module docstring; ``error`` (rad) and ``rates`` (rad/s) in body axes.
    A roll component of ``error`` (a commanded roll) is flown like pitch and yaw."""
    wanted = OMEGA_N / (2.0 * ZETA) * np.array([error[0], error[1], error[2]])
    size = math.hypot(wanted[1], wanted[2]) if error[0] == 0.0 else float(np.linalg.norm(wanted))
    if size > RATE_LIMIT:
        wanted *= RATE_LIMIT / size
    return 2.0 * ZETA * OMEGA_N * (wanted - rates)


def rcs_torques(arrays, y: np.ndarray, x_cm: float) -> np.ndarray:
    """Torque (N m, body x y z about the centre of mass) of each thruster at full
    command, a 3 x n matrix; zero for a thruster whose tank is empty."""
    rcs = arrays.aero.rcs
    lever = np.column_stack((rcs[:, RC.R_X] - x_cm, rcs[:, RC.R_Y], rcs[:, RC.R_Z]))
    push = rcs[:, RC.R_THRUST, None] * rcs[:, RC.R_DX:RC.R_DZ + 1]
    torques = np.cross(lever, push)
    torques[y[rcs[:, RC.R_TANK].astype(int)] <= 0.0] = 0.0
    return torques.T


def rcs_command(torques: np.ndarray, wanted: np.ndarray) -> np.ndarray:
    """Thruster commands in [0, 1] whose torques ``torques`` (3 x n, N m) sum closest
    to ``wanted`` (N m, body axes): bounded-variable least squares."""
    if not np.any(wanted) or not np.any(torques):
        return np.zeros(torques.shape[1])
    return np.clip(lsq_linear(torques, wanted, bounds=(0.0, 1.0), method="bvls").x, 0.0, 1.0)


def gimbal_command(torque_y: float, torque_z: float, thrust: float, lever: float) -> tuple[float, float]:
    """``(g_y, g_z)`` (rad) of every firing engine for a torque about body y and z (N m).

    ``thrust`` (N) is the total thrust, ``lever`` (m) the thrust-weighted
    distance of the gimbal points behind the centre of mass.
    """
    if thrust <= 0.0 or lever <= 0.0:
        return 0.0, 0.0
    return -torque_z / (lever * thrust), torque_y / (lever * thrust)


def fin_moments(arrays, air_body: np.ndarray, rho: float, sound: float, x_cm: float,
                deflections) -> np.ndarray:
    """Moment (N m, body x y z about the centre of mass) of the grid fins of ``arrays``
    held at ``deflections`` = (pitch, yaw, roll) rad, in air moving at ``air_body``
    (m/s, body axes, the vehicle relative to the air) of density ``rho`` (kg/m^3)."""
    grid = arrays.aero.grid
    held = np.zeros_like(arrays.aero.grid_cmd)
    G.command(grid, held, 0.0, *deflections)
    u, v, w = air_body
    return np.array(G.grid_fin_forces(1e9, u, v, w, 0.0, 0.0, 0.0, rho, sound, x_cm, grid, held)[3:])


def fin_gains(arrays, air_body: np.ndarray, rho: float, sound: float, x_cm: float) -> np.ndarray:
    """Moment per radian (N m/rad) of the pitch, yaw and roll deflections about body y, z, x."""
    base = fin_moments(arrays, air_body, rho, sound, x_cm, (0.0, 0.0, 0.0))
    gains = np.zeros(3)
    for k, axis in enumerate((1, 2, 0)):
        probe = [0.0, 0.0, 0.0]
        probe[k] = FIN_PROBE
        gains[k] = (fin_moments(arrays, air_body, rho, sound, x_cm, probe)[axis] - base[axis]) / FIN_PROBE
    return gains


def steer(command: AttitudeCommand, view, vehicle, propulsion, y: np.ndarray, t: float,
          ambient_pressure: float, fins: bool = False, rcs: bool = False) -> tuple[float, float]:
    """Command the gimbals of ``vehicle``'s firing engines (and its grid fins when
    ``fins``, its RCS thrusters when ``rcs``) for one step; returns the engines' ``(g_y, g_z)``."""
    error = command_error(command, view) if command.roll is not None else \
        attitude_error(view.axes, command.target(view))
    _, x_cm, ixx, iyy, izz = vehicle.mass_properties(y)
    torque = np.array([ixx, iyy, izz]) * angular_acceleration(error, view.body_rates)
    each = propulsion.thrusts(y, t, ambient_pressure)
    firing = np.flatnonzero(each > 0.0)
    thrust = float(each.sum())
    torque[1:] -= destabilising_moment(view, vehicle, y, thrust, x_cm)     # aero feedforward
    engine_authority = lever = 0.0
    if len(firing) and thrust > 0.0:
        lever = float(each @ (x_cm - vehicle.arrays.eng[:, E.E_X])) / thrust
        cone = float(vehicle.arrays.eng[firing, E.E_GIMBAL_RANGE].min())
        engine_authority = max(lever, 0.0) * thrust * math.sin(cone)
    fin_torque = np.zeros(3)            # body x, y, z
    grid = vehicle.arrays.aero.grid
    if fins and len(grid):
        rho, _, _, sound, _, air = view.air
        if rho > 0.0:
            gains = fin_gains(vehicle.arrays, view.axes.T @ air, rho, sound, x_cm)   # pitch, yaw, roll
            deflect = [0.0, 0.0, 0.0]
            for k, axis in enumerate((1, 2, 0)):
                if gains[k] == 0.0:
                    continue
                authority = abs(gains[k]) * float(grid[:, G.G_MAX].min())
                share = 1.0 if axis == 0 else authority / (authority + engine_authority)
                fin_torque[axis] = share * torque[axis]
                deflect[k] = fin_torque[axis] / gains[k]
            G.command(grid, vehicle.arrays.aero.grid_cmd, t, *deflect)
    if not len(firing) or thrust <= 0.0:
        if rcs:
            vehicle.arrays.aero.rcs_cmd[:] = rcs_command(rcs_torques(vehicle.arrays, y, x_cm),
                                                         torque - fin_torque)
        return 0.0, 0.0
    gy, gz = gimbal_command(torque[1] - fin_torque[1], torque[2] - fin_torque[2], thrust, lever)
    if rcs:
        size = math.hypot(gy, gz)
        inside = 1.0 if size <= cone else cone / size      # the part the gimbals can reach
        rest = torque - fin_torque
        rest[1:] *= 1.0 - inside
        vehicle.arrays.aero.rcs_cmd[:] = rcs_command(rcs_torques(vehicle.arrays, y, x_cm), rest)
    propulsion.gimbal(t, gy, gz, [int(e) for e in firing])
    return gy, gz
