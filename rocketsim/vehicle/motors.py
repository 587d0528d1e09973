"""Solid rocket motors: a thrust curve against time since ignition, compiled.

docs/physics.md#solid-motors. A motor's thrust is its curve, linear between
the file's points (RASP's interpolation, its thrust times the motor's
``thrust_scale``), zero before ignition and after the last point; no correction for the ambient pressure (a curve is measured at
a static test stand at ground level). It acts along body +x on the axis
through the nozzle, so it has no moment about the (on-axis) centre of mass.
Propellant burns in proportion to the impulse delivered,

    m(t) = m0 (1 - I(t) / I_total),   dm/dt = -m0 T(t) / I_total,

``I(t)`` the integral of the curve since ignition, ``I_total`` the whole
curve's (trapezoid of the points). The propellant mass of each motor is an
integrated entry of the state (after the engine clocks), so the same RK4
stages carry it; steps are split at every point of a lit motor's curve
(:func:`next_motor_kink`), where the thrust has a kink, so each part
integrates a straight piece of it: the mass is then the impulse law to
rounding.

Arrays: ``motor`` (motors x :data:`N_MOTOR`) with the columns below, and
``curve`` (points x 2: time s since ignition, thrust N) holding every
motor's points one after another. ``M_IGNITION`` holds the mission time of
ignition, from the vehicle file or set by the program (nan: not lit); the curve's first point is
``(0, 0)``, so the ignition instant is a kink like the others and the whole
burn is decided inside the compiled step.

Mass properties (:func:`rocketsim.vehicle.mass_properties.mass_properties`):
the propellant is a hollow cylinder of outer radius ``R`` and core radius
``r`` centred at ``M_X_CENTRE``, ``r^2 = a - b m``, with
``I_xx = m (R^2 + r^2)/2`` and ``I_yy = m ((R^2 + r^2)/4 + K)``. A BATES grain of
``n`` segments of length ``L`` (gap ``g``) burning on its core only has
``a = R^2``, ``b = (R^2 - r0^2)/m0`` and ``K = L^2/12 + (L + g)^2 (n^2 - 1)/12``
(the segments' own length and their spread about the stack's centre); the
default, a uniform cylinder of the motor's size losing density, has
``a = b = 0`` and ``K = L_motor^2/12``.
"""

from __future__ import annotations

import math

import numpy as np

from rocketsim.jit import njit

# motor columns
M_STAGE = 0         # index of the stage the motor belongs to
M_X_NOZZLE = 1      # m, station of the nozzle exit (the motor's aft end)
M_X_CENTRE = 2      # m, station of the propellant's centre (the motor's centre)
M_IGNITION = 3      # s, mission time of ignition (nan: not lit)
M_PROPELLANT = 4    # kg, propellant loaded
M_IMPULSE = 5       # N s, total impulse of the curve
M_CURVE0 = 6        # first row of the motor's points in ``curve``
M_POINTS = 7        # number of points
M_RADIUS2 = 8       # m^2, R^2: outer radius of the propellant squared
M_CORE_A = 9        # m^2, a of r^2 = a - b m
M_CORE_B = 10       # m^2/kg, b of r^2 = a - b m
M_LATERAL = 11      # m^2, K: the lateral inertia's length term
N_MOTOR = 12


@njit
def curve_thrust(curve, k0, n, c):
    """Thrust (N) of the curve ``curve[k0:k0 + n]`` at ``c`` seconds since ignition: linear
    between points, 0 before the first and after the last."""
    if c < curve[k0, 0] or c > curve[k0 + n - 1, 0]:
        return 0.0
    lo = k0
    hi = k0 + n - 1
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if curve[mid, 0] <= c:
            lo = mid
        else:
            hi = mid
    f = (c - curve[lo, 0]) / (curve[hi, 0] - curve[lo, 0])
    return curve[lo, 1] + f * (curve[hi, 1] - curve[lo, 1])


@njit
def motor_thrust(t, motor, curve, i):
    """Thrust (N) of motor ``i`` at mission time ``t`` (s); 0 while not lit."""
    lit = motor[i, M_IGNITION]
    if math.isnan(lit):
        return 0.0
    return curve_thrust(curve, int(motor[i, M_CURVE0]), int(motor[i, M_POINTS]), t - lit)


@njit(borrows=True, inline="always")
def motor_forces(t, dy, first_motor, motor, curve):
    """Thrust (N, along body +x) of every motor at mission time ``t`` (s); writes the
    propellant rates ``dy[first_motor + i] = -m0 T / I_total`` (kg/s)."""
    fx = 0.0
    for i in range(motor.shape[0]):
        thrust = motor_thrust(t, motor, curve, i)
        if thrust > 0.0:
            dy[first_motor + i] = -motor[i, M_PROPELLANT] * thrust / motor[i, M_IMPULSE]
            fx += thrust
    return fx


@njit
def sooner(a, first, floor):
    """``a`` (s) if it is a kink inside the step before ``first`` (and past ``floor``), else ``first``."""
    if floor < a < first:
        return a
    return first


@njit
def within_step(first, h, floor):
    """The part of the step to fly (s): the first kink ``first``, or the whole step ``h``
    when that kink is within ``floor`` of its end (the engines' rule, :func:`next_kink`)."""
    if first > h - floor:
        return h
    return first


@njit(borrows=True, inline="always")
def next_motor_kink(t, h, motor, curve):
    """Time (s) from ``t`` to the first point of a lit motor's curve inside the step
    ``(t, t + h)`` (the thrust's kinks), or ``h``; the same floor as the engines' kinks
    (:func:`rocketsim.vehicle.engines.next_kink`)."""
    first = h
    floor = 1e-9 * h
    for i in range(motor.shape[0]):
        lit = motor[i, M_IGNITION]
        if math.isnan(lit):
            continue
        k0 = int(motor[i, M_CURVE0])
        for k in range(k0, k0 + int(motor[i, M_POINTS])):
            first = sooner(lit + curve[k, 0] - t, first, floor)
    return within_step(first, h, floor)


def build_motors(chosen, stage_base):
    """``(motor, curve, cases)`` of the stages ``chosen`` (specs, bottom to top) based at
    ``stage_base`` (m): the arrays above, each motor lit at its file's ignition time (not
    lit: ``ignition: program``, for the program to light), and
    each motor's case as ``(mass kg, centre station m, radius m, length m)`` for the
    fixed masses."""
    rows, points, cases = [], [], []
    for s, (st, base) in enumerate(zip(chosen, stage_base)):
        for m in st.motors:
            pts = np.array(m.thrust, dtype=float) * (1.0, m.thrust_scale)
            impulse = float(np.sum(0.5 * (pts[1:, 1] + pts[:-1, 1]) * np.diff(pts[:, 0])))
            centre = base + m.position + 0.5 * m.length
            row = np.zeros(N_MOTOR)
            row[M_STAGE], row[M_X_NOZZLE], row[M_X_CENTRE] = s, base + m.position, centre
            row[M_IGNITION] = math.nan if m.ignition == "program" else m.ignition
            row[M_PROPELLANT], row[M_IMPULSE] = m.propellant_mass, impulse
            row[M_CURVE0], row[M_POINTS] = len(points), len(pts)
            if m.grain is None:
                row[M_RADIUS2] = (0.5 * m.diameter) ** 2
                row[M_LATERAL] = m.length ** 2 / 12.0
            else:
                g = m.grain
                outer2, core2 = (0.5 * g.outer_diameter) ** 2, (0.5 * g.core_diameter) ** 2
                row[M_RADIUS2] = row[M_CORE_A] = outer2
                row[M_CORE_B] = (outer2 - core2) / m.propellant_mass
                row[M_LATERAL] = (g.length ** 2 + (g.length + g.separation) ** 2 * (g.count ** 2 - 1)) / 12.0
            rows.append(row)
            points.extend(pts.tolist())
            cases.append((m.case_mass, centre, 0.5 * m.diameter, m.length))
    motor = np.array(rows, dtype=float).reshape(len(rows), N_MOTOR)
    curve = np.ascontiguousarray(np.array(points, dtype=float).reshape(len(points), 2))
    return motor, curve, cases
