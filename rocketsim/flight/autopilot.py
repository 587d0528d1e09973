"""The autopilot: turns a commanded attitude into engine gimbal commands, once per step.

A program commands where the nose should point (a direction in a named frame,
pitch/heading, or a mode that follows the flight: prograde, retrograde,
surface retrograde, normal, radial). Each step the autopilot, reading the
navigation estimate like the program, computes the attitude error as a
rotation vector in body axes and asks for the angular acceleration of a
damped second-order response::

    alpha = omega_n^2 e - 2 zeta omega_n w        (pitch and yaw axes)

with ``omega_n = 1 rad/s`` and ``zeta = 0.9``. The torque ``I alpha`` is
produced by gimballing every firing engine alike: an engine a lever arm ``L``
behind the centre of mass with thrust ``T`` gives ``tau_y = L T g_z`` and
``tau_z = -L T g_y`` (small angles; the engine model's sign convention), so
``g_z = tau_y / (L T)``, ``g_y = -tau_z / (L T)``, clipped by each engine's
cone and reached at its slew rate. In the air, nose first, the torque also
cancels the destabilising part of the modelled aerodynamic moment
(:mod:`rocketsim.flight.aero_feedforward`), so that an unfinned launcher
through max-Q keeps the same second-order response as in vacuum. Roll is not controlled yet (it needs
reaction control), and with no thrust the autopilot commands nothing.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from rocketsim.flight.aero_feedforward import destabilising_moment
from rocketsim.vehicle import engines as E

OMEGA_N = 1.0     # rad/s, natural frequency of the attitude response
ZETA = 0.9        # damping ratio

MODES = ("prograde", "retrograde", "surface_prograde", "surface_retrograde", "normal",
         "antinormal", "radial", "antiradial")


@dataclass(frozen=True)
class AttitudeCommand:
    """Where the nose should point: a fixed ECI direction, pitch/heading, or a mode."""

    direction: np.ndarray | None = None     # unit vector, ECI
    pitch: float | None = None              # rad above the local horizon
    heading: float | None = None            # rad from north towards east
    mode: str | None = None

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


def gimbal_command(error: np.ndarray, rates: np.ndarray, inertia_pitch: float, inertia_yaw: float,
                   thrust: float, lever: float, aero: tuple[float, float] = (0.0, 0.0)) -> tuple[float, float]:
    """``(g_y, g_z)`` (rad) of every firing engine for the damped response above.

    ``thrust`` (N) is the total thrust, ``lever`` (m) the thrust-weighted
    distance of the gimbal points behind the centre of mass; ``aero`` (N m,
    body y and z) the aerodynamic moment the gimbals cancel
    (:mod:`rocketsim.flight.aero_feedforward`).
    """
    if thrust <= 0.0 or lever <= 0.0:
        return 0.0, 0.0
    alpha_y = OMEGA_N ** 2 * error[1] - 2.0 * ZETA * OMEGA_N * rates[1]
    alpha_z = OMEGA_N ** 2 * error[2] - 2.0 * ZETA * OMEGA_N * rates[2]
    tau_y, tau_z = inertia_pitch * alpha_y - aero[0], inertia_yaw * alpha_z - aero[1]
    return -tau_z / (lever * thrust), tau_y / (lever * thrust)


def steer(command: AttitudeCommand, view, vehicle, propulsion, y: np.ndarray, t: float,
          ambient_pressure: float) -> tuple[float, float]:
    """Command the gimbals of ``vehicle``'s firing engines for one step; returns ``(g_y, g_z)``."""
    error = attitude_error(view.axes, command.target(view))
    _, x_cm, _, iyy, izz = vehicle.mass_properties(y)
    each = propulsion.thrusts(y, t, ambient_pressure)
    firing = np.flatnonzero(each > 0.0)
    thrust = float(each.sum())
    if not len(firing) or thrust <= 0.0:
        return 0.0, 0.0
    lever = float(each @ (x_cm - vehicle.arrays.eng[:, E.E_X])) / thrust
    aero = destabilising_moment(view, vehicle, y, thrust, x_cm)     # aero feedforward
    gy, gz = gimbal_command(error, view.body_rates, iyy, izz, thrust, lever, aero)
    propulsion.gimbal(t, gy, gz, [int(e) for e in firing])
    return gy, gz
