"""The time derivative of a body's state: Newton and Euler in an inertial frame.

The equations (docs/physics.md#equations-of-motion)::

    r' = v
    v' = g(r) + F/m
    q' = 1/2 q (x) (0, w)
    w' = I^-1 (tau - w x (I w)),   I = diag(Ixx, Iyy, Izz)

No Coriolis or centrifugal terms: the frame is inertial. Units SI; ``r``,
``v`` in the central body's inertial frame, ``w`` and ``tau`` in body axes.
Gravity is the central body's point mass + J2 (docs/physics.md#j2), plus the
other bodies' pull when ``p`` carries an n-body field
(:mod:`rocketsim.dynamics.third_bodies`, docs/physics.md#n-body-field). A
rigid body (no ``veh``) feels gravity alone; a staged vehicle adds thrust,
aerodynamics, RCS and contact to ``F`` and ``tau``, evaluated at every RK4
stage.

A staged vehicle passes ``veh``, its
:class:`~rocketsim.vehicle.build.VehicleArrays`: then the mass and inertia
come from the propellant left in its tanks (``y[13:]``), not from ``p``, and
its engines add thrust and torque and drain the tanks, all at every stage
(the ambient pressure for the thrust is looked up at the radial height in the
vehicle's atmosphere table). The rate of change of the inertia and the jet
damping it causes are not modelled. Without ``veh`` (``None``, the rigid body)
that branch is compiled away.

A vehicle with an ``aero:`` section (``veh.aero.ref[A_ON]``) also gets, at
every stage, its aerodynamics from the air at the stage's height (axial,
segment crossflow, nose lift, fins: :mod:`rocketsim.vehicle.aero`), its grid
fins (:mod:`~rocketsim.vehicle.grid_fins`), its RCS thrusters
(:mod:`~rocketsim.vehicle.rcs`, draining their tanks) and, within reach of
the ground, its contact forces (:mod:`~rocketsim.vehicle.contact`). The air
moves with the ground plus the wind held for the step in ``veh.aero.wind``; the
ground turns with the central body at ``p[P_SPIN]`` about the frame's z.
A vacuum spacecraft (``aero: {aerodynamics: false}``, ``ref[A_ON] = 0``) gets
its RCS thrusters only.
"""

import math

from rocketsim.jit import njit
from rocketsim.atmosphere.table import air_in
from rocketsim.atmosphere.ussa1976 import Z_86
from rocketsim.bodies.gravity import point_mass_j2
from rocketsim.layout import (P_CLASSIC, P_IXX, P_IYY, P_IZZ, P_J2, P_MU,
                                      P_POLAR_RADIUS, P_RADIUS, P_SPIN, Q, R, V, W)
from rocketsim.dynamics.third_bodies import held_perturbation
from rocketsim.frames.local import air_velocity_inertial, body_air_velocity
from rocketsim.frames.quaternion import hamilton_product, rotate_components
from rocketsim.vehicle.aero import A_GROUND, A_ON, A_REACH, body_aero
from rocketsim.vehicle.contact import contact_forces
from rocketsim.vehicle.engines import engine_forces
from rocketsim.vehicle.grid_fins import grid_fin_forces
from rocketsim.vehicle.rcs import rcs_forces
from rocketsim.vehicle.mass_properties import vehicle_mass_properties
from rocketsim.vehicle.motors import motor_forces
from rocketsim.vehicle.parachutes import CANOPY_RATE_TIME, canopy_drag
from rocketsim.vehicle.rail import RL_ON, constrain_to_rail


@njit(borrows=True)
def radial_height(y, p):
    """Height (m) above the central body's ellipsoid, measured along the radius.

    ``|r| - a b / sqrt(b^2 cos^2 phi_c + a^2 sin^2 phi_c)`` (phi_c geocentric
    latitude, a and b the equatorial and polar radii). Within a few metres of
    the surface it differs from the geodetic height by less than 0.1 mm, and
    it has the same sign: it serves the ground-proximity and impact tests
    (telemetry and programs read the geodetic height) and the ambient
    pressure of the engines (a few metres off at altitude: negligible).
    """
    rho2 = y[R] ** 2 + y[R + 1] ** 2
    z2 = y[R + 2] ** 2
    r2 = rho2 + z2
    a = p[P_RADIUS]
    b = p[P_POLAR_RADIUS]
    return math.sqrt(r2) - a * b / math.sqrt((b * b * rho2 + a * a * z2) / r2)


@njit(borrows=True, inline="always")
def flight_dynamic_pressure(y, p, veh):
    """Dynamic pressure (Pa) the aerodynamics of the staged vehicle ``veh`` meet at
    state ``y``: the density of its air at the radial height, as the derivative reads
    it, and the speed of the air past it with the wind held for the step."""
    rho = air_in(veh.air, radial_height(y, p))[0]
    ax, ay, az = air_velocity_inertial(y, veh.aero.wind, p[P_SPIN])
    return 0.5 * rho * (ax * ax + ay * ay + az * az)


@njit(borrows=True, inline="always")
def _aero_and_contact(t, y, p, dy, rho, sound, x_cm, aero, fx, fy, fz, mx, my, mz, contact=True):
    """Add the body's aerodynamics, grid fins, RCS and ground contact (body axes, about
    the centre of mass) to the engines' force and moment ``(fx..mz)``; no contact
    without ``contact`` (on a launch rail, which carries the vehicle)."""
    wx, wy, wz = y[W], y[W + 1], y[W + 2]
    if rho > 0.0:
        u, v, w = body_air_velocity(y, aero.wind, p[P_SPIN])
        a = body_aero(u, v, w, wx, wy, wz, rho, sound, fx, x_cm, aero.ref, aero.seg, aero.fin,
                      aero.ca_nf, aero.ca_tf)
        fx, fy, fz, mx, my, mz = fx + a[0], fy + a[1], fz + a[2], mx + a[3], my + a[4], mz + a[5]
        if aero.grid.shape[0] > 0:
            a = grid_fin_forces(t, u, v, w, wx, wy, wz, rho, sound, x_cm, aero.grid, aero.grid_cmd)
            fx, fy, fz, mx, my, mz = fx + a[0], fy + a[1], fz + a[2], mx + a[3], my + a[4], mz + a[5]
    if aero.rcs.shape[0] > 0:
        a = rcs_forces(y, dy, x_cm, aero.rcs, aero.rcs_cmd)
        fx, fy, fz, mx, my, mz = fx + a[0], fy + a[1], fz + a[2], mx + a[3], my + a[4], mz + a[5]
    # contact only within reach of the ground (a cheap bound first)
    r = math.sqrt(y[R] ** 2 + y[R + 1] ** 2 + y[R + 2] ** 2)
    reach = aero.ref[A_REACH] + aero.ref[A_GROUND]      # the ground: the ellipsoid, or above it
    if contact and r - p[P_RADIUS] < reach and radial_height(y, p) < reach:
        a = contact_forces(y, x_cm, p[P_RADIUS], p[P_POLAR_RADIUS], p[P_SPIN], aero.contact,
                           aero.ref[A_GROUND])
        fx, fy, fz, mx, my, mz = fx + a[0], fy + a[1], fz + a[2], mx + a[3], my + a[4], mz + a[5]
    return fx, fy, fz, mx, my, mz


@njit(inline="always")     # small: typed in its callers, no kernel of its own
def derivative(t, y, p, dy, veh=None, nbody=None):
    """Write ``dy/dt`` of state ``y`` at mission time ``t`` (s) into ``dy``.

    Parameters
    ----------
    t : float
        Mission time, s.
    y : array
        The state (slots of :mod:`rocketsim.layout`): position m and velocity
        m/s in the central body's inertial frame, attitude quaternion body ->
        inertial, body rates rad/s; a staged vehicle's tank masses (kg) and
        engine clocks (s) after slot 13.
    p : array
        The parameters (SI units: kg, kg m^2, m^3/s^2, m, rad/s), with the
        n-body field when the body carries one.
    dy : array
        Written with the rates: m/s, m/s^2, 1/s, rad/s^2, kg/s, and 1 for the
        clocks.
    veh : VehicleArrays or None
        The arrays of a staged vehicle, or None for a rigid body of constant
        mass and inertia ``p``.
    nbody : True or None
        True when ``p`` carries an n-body field (the other bodies' pull, held in
        ``p``, is added), None when it does not
        (:func:`~rocketsim.dynamics.third_bodies.nbody_flag`): a switch on the
        argument's type, like ``veh``; with None the pull is not compiled.

    Nothing is held: this is the model's
    derivative at ``(t, y)`` (:func:`held_derivative` with ``(t, y)`` as the hold).
    """
    held_derivative(t, y, p, dy, veh, t, y, nbody)


@njit(borrows=True)
def held_derivative(t, y, p, dy, veh, t_held, y_held, nbody=None):
    """:func:`derivative` inside an RK4 step that started at ``(t_held, y_held)``
    (``nbody`` as its).

    The realistic model (``p[P_CLASSIC] == 0``) ignores the hold: everything
    is evaluated at ``(t, y)``. On the classic range (``p[P_CLASSIC] == 1``,
    the original model, docs/physics.md#classic-range) a staged vehicle's
    engines (thrust, torque, mass flow, and the ambient pressure they see),
    its mass properties and, when the step starts above 86 km, the air
    density are those at the step's start, held for the four stages; powered
    flight is then first order in the step. Gravity, the rest of the air and
    the aerodynamics, RCS and contact are evaluated at every stage either way.
    """
    ax, ay, az = point_mass_j2(y[R], y[R + 1], y[R + 2], p[P_MU], p[P_RADIUS], p[P_J2])
    if nbody is not None:
        # the n-body field the body carries: the other bodies held for the step
        tx, ty, tz = held_perturbation(y[R], y[R + 1], y[R + 2], p)
        ax, ay, az = ax + tx, ay + ty, az + tz
    dy[R] = y[V]
    dy[R + 1] = y[V + 1]
    dy[R + 2] = y[V + 2]
    dy[V] = ax
    dy[V + 1] = ay
    dy[V + 2] = az

    wx, wy, wz = y[W], y[W + 1], y[W + 2]
    dq = hamilton_product(y[Q], y[Q + 1], y[Q + 2], y[Q + 3], 0.0, wx, wy, wz)
    dy[Q], dy[Q + 1], dy[Q + 2], dy[Q + 3] = 0.5 * dq[0], 0.5 * dq[1], 0.5 * dq[2], 0.5 * dq[3]

    for k in range(13, y.shape[0]):
        dy[k] = 0.0
    ixx, iyy, izz = p[P_IXX], p[P_IYY], p[P_IZZ]
    mx = my = mz = 0.0
    canopy = 0.0
    if veh is not None:
        classic = p[P_CLASSIC] > 0.5
        t_e, y_e = (t_held, y_held) if classic else (t, y)     # engines and mass read these
        mass, x_cm, ixx, iyy, izz = vehicle_mass_properties(veh, y_e)
        rho, p_a, _, sound, _, _ = air_in(veh.air, radial_height(y, p))
        if classic:
            h_held = radial_height(y_held, p)
            rho_held, p_a = air_in(veh.air, h_held)[:2]
            if h_held > Z_86:
                rho = rho_held
        fx, fy, fz, mx, my, mz = engine_forces(t_e, y_e, dy, veh.first_tank, veh.first_clock, veh.eng,
                                               veh.cmd, veh.stage, veh.tank_share, p_a, x_cm)
        if veh.motor.shape[0] > 0:      # solid motors: along body x, on the axis (no moment)
            fx += motor_forces(t_e, dy, veh.first_motor, veh.motor, veh.curve)
        aero = veh.aero
        on_rail = veh.rail[RL_ON] > 0.5
        if aero.ref[A_ON] > 0.5:
            fx, fy, fz, mx, my, mz = _aero_and_contact(t, y, p, dy, rho, sound, x_cm, aero,
                                                       fx, fy, fz, mx, my, mz, not on_rail)
        elif aero.rcs.shape[0] > 0:     # a vacuum spacecraft (aero: {aerodynamics: false}): RCS only
            a = rcs_forces(y, dy, x_cm, aero.rcs, aero.rcs_cmd)
            fx, fy, fz, mx, my, mz = fx + a[0], fy + a[1], fz + a[2], mx + a[3], my + a[4], mz + a[5]
        # body force -> inertial
        gx, gy, gz = rotate_components(y[Q], y[Q + 1], y[Q + 2], y[Q + 3], fx, fy, fz)
        dy[V] += gx / mass
        dy[V + 1] += gy / mass
        dy[V + 2] += gz / mass
        if veh.chute.shape[0] > 0 and rho > 0.0:    # parachutes, at their cords' attachments
            cx, cy, cz, cmy, cmz, canopy = canopy_drag(t, y, rho, aero.wind, p[P_SPIN], veh.chute, x_cm)
            dy[V] += cx / mass
            dy[V + 1] += cy / mass
            dy[V + 2] += cz / mass
            my += cmy
            mz += cmz
        if on_rail:     # along the rail only, turning with the ground (rocketsim.vehicle.rail)
            constrain_to_rail(t, y, dy, p[P_SPIN], veh.rail)
            dy[W] = dy[W + 1] = dy[W + 2] = 0.0
            return
    # Euler: I w' = tau - w x (I w)
    hx, hy, hz = ixx * wx, iyy * wy, izz * wz
    dy[W] = (mx - (wy * hz - wz * hy)) / ixx
    dy[W + 1] = (my - (wz * hx - wx * hz)) / iyy
    dy[W + 2] = (mz - (wx * hy - wy * hx)) / izz
    if veh is not None and canopy > 0.0:
        # under a canopy the suspension lines damp the body's rotation
        for k in range(3):
            dy[W + k] -= canopy * y[W + k] / CANOPY_RATE_TIME
