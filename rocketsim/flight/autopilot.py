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
with its grid fins (tests/unit/vehicle/test_aero.py); the fins' restoring moment at zero
deflection is left to help, not cancelled.

The step is computed in one compiled call
(:func:`rocketsim.flight.steering.steer_step`, where the gains live) from the
estimated state; only the RCS's bounded least squares runs here, in Python,
while the program has the thrusters on.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from rocketsim.dynamics.rails import command_code
from rocketsim.flight.steering import steer_step
from rocketsim.vehicle.rcs import R_DX, R_DZ, R_TANK, R_THRUST, R_X, R_Y, R_Z

MODES = ("prograde", "retrograde", "surface_prograde", "surface_retrograde", "normal",
         "antinormal", "radial", "antiradial")


@dataclass(frozen=True)
class AttitudeCommand:
    """Where the nose should point: a fixed ECI direction, pitch/heading, a mode, or a
    linear-tangent law."""

    direction: np.ndarray | None = None     # unit vector, ECI
    pitch: float | None = None              # rad above the local horizon
    heading: float | None = None            # rad from north towards east
    mode: str | None = None
    law: tuple | None = None                # linear-tangent steering: (t0 s, a, b 1/s, cross), see rails.nose_target
    roll: float | None = None               # rad about the nose (StateView.euler's); None: free, damped
    code: np.ndarray = field(init=False, repr=False, compare=False)   # the numbers steer_step reads

    def __post_init__(self):
        object.__setattr__(self, "code", command_code(self))


def rcs_torques(arrays, y: np.ndarray, x_cm: float) -> np.ndarray:
    """Torque (N m, body x y z about the centre of mass) of each thruster at full
    command, a 3 x n matrix; zero for a thruster whose tank is empty."""
    rcs = arrays.aero.rcs
    lever = np.column_stack((rcs[:, R_X] - x_cm, rcs[:, R_Y], rcs[:, R_Z]))
    push = rcs[:, R_THRUST, None] * rcs[:, R_DX:R_DZ + 1]
    torques = np.cross(lever, push)
    torques[y[rcs[:, R_TANK].astype(int)] <= 0.0] = 0.0
    return torques.T


def rcs_command(torques: np.ndarray, wanted: np.ndarray) -> np.ndarray:
    """Thruster commands in [0, 1] whose torques ``torques`` (3 x n, N m) sum closest
    to ``wanted`` (N m, body axes): bounded-variable least squares."""
    if not np.any(wanted) or not np.any(torques):
        return np.zeros(torques.shape[1])
    from scipy.optimize import lsq_linear   # here: scipy.optimize is slow to import
    return np.clip(lsq_linear(torques, wanted, bounds=(0.0, 1.0), method="bvls").x, 0.0, 1.0)


def steer(command: AttitudeCommand, view, vehicle, propulsion, y: np.ndarray, t: float,
          ambient_pressure: float, fins: bool = False, rcs: bool = False) -> None:
    """Command the gimbals of ``vehicle``'s firing engines (and its grid fins when
    ``fins``, its RCS thrusters when ``rcs``) for one step at mission time ``t`` (s).

    ``view``: the navigation estimate the autopilot reads (a
    :class:`~rocketsim.flight.readings.StateView` at the state ``y``'s time);
    ``propulsion``: the vehicle's :class:`~rocketsim.vehicle.control.Propulsion`
    (its compiled entries); ``ambient_pressure``: the truth's (Pa) for the engines'
    thrust, or nan when ``view`` is the truth itself (the kernel reads it off the air).
    """
    arrays = vehicle.arrays
    x_cm, *left = propulsion.kernels.call(steer_step, arrays, arrays, y, view._p, t, view.t, view.position,
                                          view.velocity, view.attitude, view.body_rates,
                                          ambient_pressure, view._atmosphere().arrays(), command.code,
                                          fins, rcs)
    if rcs:
        arrays.aero.rcs_cmd[:] = rcs_command(rcs_torques(arrays, y, x_cm), np.array(left))
