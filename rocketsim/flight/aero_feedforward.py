"""The aerodynamic moment the autopilot cancels: the destabilising part, nose first.

An unfinned launcher (Electron, Falcon 9) has its centre of pressure ahead of
its centre of mass: in the air the moment of the body's crossflow and nose
lift turns the nose further away from the air-relative velocity, with a
stiffness ``M_alpha / I`` that at 30 kPa is several times the autopilot's
``omega_n^2`` (1 s^-2). The damped response then diverges (the Electron broke
up at 25 s that way). Rather than raising the gains (which tumbles a
vacuum upper stage), the autopilot asks the gimbals for the torque of its
damped response *less* this moment (feedforward), so that the attitude obeys
the same second-order response in the air as in vacuum:

    tau = I (omega_n^2 e - 2 zeta omega_n w) - M_destabilising

``M_destabilising`` is the component of the modelled body moment
(:func:`rocketsim.vehicle.aero.body_aero`: axial, segment crossflow with the
rotation-induced flow, nose lift and fins) about the axis ``n = d x x_b``
that turns the nose away from the air-relative direction ``d``, when it has
that sense and the vehicle flies nose first (angle of attack below 90 deg).
A stabilising moment (fins, a tail-first booster) is left alone to help; grid
fins are not counted (they are commanded separately). The moment is
evaluated on what the autopilot reads (the navigation estimate: air data
errors flow in), in the air of the step, inside the autopilot's compiled step
(:func:`rocketsim.flight.steering.steer_step`).
"""

from __future__ import annotations

import math

from rocketsim.jit import njit
from rocketsim.vehicle.aero import A_ON, body_aero


@njit(inline="always")
def destabilising_moment(aero, u, v, w, wx, wy, wz, rho, sound, thrust, x_cm):
    """``(M_y, M_z)`` (N m, body axes, about the centre of mass) of the aerodynamic
    moment's part that turns the nose away from the air-relative velocity.

    ``aero``: the vehicle's aerodynamic arrays (:class:`~rocketsim.vehicle.aero_build.AeroArrays`);
    ``(u, v, w)``: the air-relative velocity (m/s, body axes) and ``(wx, wy, wz)``
    the body rates (rad/s) the autopilot reads; ``rho`` (kg/m^3) and ``sound``
    (m/s): the air it reads; ``thrust``: the engines' total force along body +x
    (N, for the plume shielding of a tail-first base); ``x_cm``: station of the
    centre of mass (m). Zero without aerodynamics, out of the air, or flying
    more than 90 deg off the air-relative velocity.
    """
    if aero.ref[A_ON] < 0.5 or rho <= 0.0:
        return 0.0, 0.0
    cross = math.hypot(v, w)
    if u <= 0.0 or cross == 0.0:                  # tail first, or no angle of attack
        return 0.0, 0.0
    moment = body_aero(u, v, w, wx, wy, wz, rho, sound, thrust, x_cm, aero.ref, aero.seg,
                       aero.fin, aero.ca_nf, aero.ca_tf)
    # n = d x x_b with d = (u, v, w)/speed: (0, w, -v)/speed, normalised by the
    # crossflow: the axis about which the nose turns away from d
    ny, nz = w / cross, -v / cross
    away = moment[4] * ny + moment[5] * nz
    if away <= 0.0:
        return 0.0, 0.0
    return away * ny, away * nz
