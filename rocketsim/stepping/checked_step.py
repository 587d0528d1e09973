"""A vehicle's step with the figures its checks read, in one compiled call.

After every step of a vehicle with aerodynamics the world's checks
(:class:`rocketsim.sim.vehicle_checks.VehicleChecks`: breakup, heat shield,
touchdown) read a few figures of its new state: the air, the dynamic pressure,
the angle of attack, the axial load, the height of its lowest contact point
(:func:`step_figures`). :func:`advance_checked` computes them in the step's own
call, after the autopilot's step and the RK4 advance; the accelerations the
figures and the telemetry read are those of the derivative the integrator uses
(:func:`accelerations`).
"""

import math

import numpy as np

from rocketsim.jit import njit
from rocketsim.atmosphere.table import air_in
from rocketsim.bodies.gravity import point_mass_j2
from rocketsim.dynamics.derivative import derivative, radial_height
from rocketsim.dynamics.rk4 import advance, near_ground
from rocketsim.flight.steering import steer_on_estimate
from rocketsim.frames.local import body_air_velocity
from rocketsim.layout import P_J2, P_MU, P_RADIUS, P_SPIN, Q, R, V
from rocketsim.vehicle.aero import A_GROUND, A_REACH
from rocketsim.vehicle.contact import lowest_contact_height
from rocketsim.vehicle.mass_properties import vehicle_mass_properties


@njit(inline="always")     # small: typed in its callers, no kernel of its own
def accelerations(t, y, p, veh, nbody=None):
    """``(ax, ay, az, sx, sy, sz)``: the inertial acceleration ``dv/dt`` and the sensed
    (specific-force) acceleration ``dv/dt - g`` (m/s^2, ECI axes) of state ``y`` at
    mission time ``t`` (s), from the derivative the integrator uses (``veh`` the
    vehicle's arrays, None for a rigid body; ``nbody`` as the derivative's); ``g`` is
    the central body's point mass and J2 of ``p``."""
    return accelerations_into(np.empty(y.shape[0]), t, y, p, veh, nbody)


@njit(inline="always")     # small: typed in its callers, no kernel of its own
def accelerations_into(dy, t, y, p, veh, nbody=None):
    """:func:`accelerations`, the derivative written into ``dy`` (every slot)."""
    derivative(t, y, p, dy, veh, nbody)
    gx, gy, gz = point_mass_j2(y[R], y[R + 1], y[R + 2], p[P_MU], p[P_RADIUS], p[P_J2])
    return dy[V], dy[V + 1], dy[V + 2], dy[V] - gx, dy[V + 1] - gy, dy[V + 2] - gz


@njit
def step_figures(t, y, p, veh, contact, nbody=None):
    """:func:`step_figures_into` with an array of its own."""
    return step_figures_into(np.empty(y.shape[0]), t, y, p, veh, contact, nbody)


@njit(borrows=True)
def step_figures_into(dy, t, y, p, veh, contact, nbody=None):
    """What the checks read after a step, in one compiled call: ``(density kg/m^3, air
    temperature K, airspeed m/s, dynamic pressure Pa, total angle of attack rad, sensed
    acceleration along body x m/s^2 from the flight loads, height of the lowest contact
    point m)``. ``veh`` is the vehicle's arrays without their contact points (the flight
    loads), ``contact`` its contact points (one named tuple to unbox per call, not two);
    ``nbody`` as the derivative's; the derivative at ``y`` is written into ``dy``.

    The air moves with the ground and the wind held for the step (as the derivative
    sees it); the angle of attack is measured from the nose.
    """
    x_cm = vehicle_mass_properties(veh, y)[1]
    rho, _, temperature, _, _, _ = air_in(veh.air, radial_height(y, p))
    u, v, w = body_air_velocity(y, veh.aero.wind, p[P_SPIN])
    speed = math.sqrt(u * u + v * v + w * w)
    alpha = math.acos(max(-1.0, min(1.0, u / speed))) if speed > 0.0 else 0.0
    _, _, _, sx, sy, sz = accelerations_into(dy, t, y, p, veh, nbody)
    # body x in inertial axes: first column of the rotation of q
    qw, qx, qy, qz = y[Q], y[Q + 1], y[Q + 2], y[Q + 3]
    ax = 1.0 - 2.0 * (qy * qy + qz * qz)
    ay = 2.0 * (qx * qy + qw * qz)
    az = 2.0 * (qx * qz - qw * qy)
    lowest = lowest_contact_height(y, p, contact, x_cm, veh.aero.ref[A_GROUND])
    return rho, temperature, speed, 0.5 * rho * speed * speed, alpha, sx * ax + sy * ay + sz * az, lowest


@njit
def advance_checked(y, k0, h, n_steps, p, veh, steer, code, fins, errors, j, nbody=None):
    """:func:`~rocketsim.dynamics.rk4.advance` of a staged vehicle with aerodynamics
    (arrays ``veh``, ``nbody`` as its), then :func:`step_figures` at the new state, in one
    compiled call. Returns ``(y, steps taken, near, figures)``.

    With ``steer``, the autopilot's step comes first, as the world's loop runs it
    before the advance: :func:`~rocketsim.flight.steering.steer_on_estimate` reading the
    navigation estimate of the state ``y`` at the step's start time ``k0 h`` (row ``j`` of
    the sensors' ``errors``; none: the truth) in the vehicle's air (the day's) with the
    command ``code``, the grid fins when ``fins``, no RCS.

    The figures' flight loads are the derivative's without the contact forces. Out of
    the contact points' reach of the ground the derivative adds none, so ``veh`` itself
    serves; within it (``near``, tested with the margin of the ground sub-steps) the
    figures are computed here all the same but the caller must compute them again
    with the contact points removed.
    """
    if steer:
        steer_on_estimate(veh, y, p, k0 * h, errors, j, code, fins)
    y, taken = advance(y, k0, h, n_steps, p, veh, nbody)
    near = near_ground(y, p, veh.aero.ref[A_REACH] + veh.aero.ref[A_GROUND])
    return y, taken, near, step_figures((k0 + taken) * h, y, p, veh, veh.aero.contact, nbody)
