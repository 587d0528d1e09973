"""The n-body field about a central body: its point mass and J2, every other body's pull.

docs/physics.md#n-body-field: with the central body ``c``,
the other bodies ``k`` at ``s_k`` from ``c`` and the vehicle at ``r`` from
``c``::

    a = a_c(r) + sum_k mu_k [ (s_k - r)/|s_k - r|^3  -  s_k/|s_k|^3 ]

``a_c`` is the central body's point mass plus J2 about the frame's ``z``
axis (:func:`rocketsim.bodies.gravity.point_mass_j2`), so the frame's ``z``
must be the central body's pole: Earth's ECI, or the IAU-pole frame a
sphere-of-influence handover sets up (:mod:`rocketsim.dynamics.soi`). The
first term in the brackets is the body's pull on the vehicle (direct), the
second its pull on the central body, with which the frame falls (indirect).
Solar radiation pressure (a flat absorber facing the Sun,
``a = (S/c) (AU/d)^2 C_R A/m`` away from the Sun) is implemented and off
unless the field's SRP coefficient is set.

A field is described by one float64 array ``fp`` (:func:`make_field`): the
central body's index in :data:`rocketsim.ephemeris.solar_system.BODIES`
(sun 0, earth 1, moon 2, mars 3), the TT Julian date of mission time 0, the
SRP coefficient ``C_R A/m`` (m^2/kg, 0 = off), the rotation frame -> J2000
(row-major) and each body's mu (0 = not in the field). The central body's
own mu, radius and J2 come from the state's parameters ``p`` as in
:func:`rocketsim.dynamics.derivative.derivative`.

In the flight model the other bodies' positions are computed once per
:data:`~rocketsim.constants.NBODY_HOLD` (5 s) of mission time and held,
quantised on mission time (:func:`held_bodies`), so a run stays bit-identical
however its steps are batched. Cruise rails evaluate them at every stage.
The slots, the bodies' positions and the perturbation itself live in
:mod:`rocketsim.dynamics.third_bodies` (below the derivative, which adds them
for a body that carries its field).
"""

from __future__ import annotations

import math

import numpy as np

from rocketsim.jit import njit
from rocketsim.bodies.gravity import point_mass_j2
from rocketsim.atmosphere.table import air_in
from rocketsim.dynamics.derivative import derivative, radial_height
from rocketsim.layout import P_J2, P_MU, P_RADIUS, P_SPIN, Q, R, V
from rocketsim.dynamics.third_bodies import (  # noqa: F401  (the field's slots and pull live there)
    FIELD_CENTER, FIELD_DRAG, FIELD_JD0, FIELD_MU, FIELD_ROT, FIELD_SRP, FIELD_WIND, MU, N_FIELD, SRP_1AU, bodies_at,
    held_bodies, hold_time, perturbation)
from rocketsim.ephemeris.solar_system import BODIES



def make_field(center: str, jd0_tt: float, rotation=None, bodies=BODIES,
               srp: float = 0.0, drag: float = 0.0) -> np.ndarray:
    """The field array about ``center`` ("sun", "earth", "moon" or "mars").

    ``jd0_tt``: TT Julian date of mission time 0; ``rotation``: 3x3 matrix
    taking frame components to J2000 equatorial ones (identity by default);
    ``bodies``: names of the bodies whose pull is felt (the centre's own entry
    is ignored: its pull is ``a_c``); ``srp``: ``C_R A/m`` in m^2/kg, 0 = off;
    ``drag``: ``C_D A/m`` in m^2/kg of the rails' point-mass drag (Earth only).
    """
    fp = np.zeros(N_FIELD)
    fp[FIELD_CENTER] = BODIES.index(center)
    fp[FIELD_JD0] = jd0_tt
    fp[FIELD_SRP] = srp
    fp[FIELD_DRAG] = drag
    rotation = np.eye(3) if rotation is None else np.asarray(rotation, dtype=float)
    fp[FIELD_ROT:FIELD_ROT + 9] = rotation.reshape(9)
    for name in bodies:
        fp[FIELD_MU + BODIES.index(name)] = MU[name]
    return fp


@njit(inline="always")
def field_acceleration(x, y, z, s, fp, p):
    """The whole field (m/s^2): central point mass + J2 (``p``) plus :func:`perturbation`."""
    ax, ay, az = point_mass_j2(x, y, z, p[P_MU], p[P_RADIUS], p[P_J2])
    tx, ty, tz = perturbation(x, y, z, s, fp)
    return ax + tx, ay + ty, az + tz


def field(r, t: float, fp, p, held: bool = True) -> np.ndarray:
    """Acceleration (3,) m/s^2 at ``r`` (m, frame axes) at mission time ``t`` (s).

    ``held``: the flight model's 5 s hold of the other bodies; False evaluates
    them at ``t`` itself (cruise rails).
    """
    fp = np.asarray(fp, dtype=float)
    s = held_bodies(fp, t) if held else bodies_at(fp, t)[0]
    return np.array(field_acceleration(float(r[0]), float(r[1]), float(r[2]), s, fp,
                                       np.asarray(p, dtype=float)))


@njit
def awake_derivative(t, y, p, s, fp, dy, veh=None):
    """The flight model's derivative in the n-body field: :func:`derivative`
    (central body, engines, Euler) plus the other bodies held at ``s``."""
    derivative(t, y, p, dy, veh)
    tx, ty, tz = perturbation(y[R], y[R + 1], y[R + 2], s, fp)
    dy[V] += tx
    dy[V + 1] += ty
    dy[V + 2] += tz


def no_air():
    """Placeholder air table (the arguments of ``air_at`` before the height) for
    fields without drag."""
    zero = np.zeros(2)
    return (0.0, 1.0, zero, zero, zero, zero, zero, zero)


# inlined by LLVM (forceinline) into translational_rk4, a borrowing kernel (rocketsim.jit):
# typed and lowered once, not once per RK4 stage as numba's own inlining did (a large part of
# a cold Falcon 9's compiling); a call per stage left to LLVM's choice is not inlined and
# slows the rails; in a kernel that counts references its tuple of arrays' counts would cost
# more than the rest of a rails step (tests/benchmarks/test_bench_rails.py measures it)
@njit(borrows=True, forceinline=True)
def translational_acceleration(x, y, z, vx, vy, vz, p, s, fp, air, pos):
    """The field at ``(x, y, z)`` (m) and, with ``fp[FIELD_DRAG]`` set, point-mass drag
    ``-1/2 rho |v_air| v_air C_D A/m`` (``v_air = v - omega x r - wind``, ``omega`` the
    central body's rate ``p[P_SPIN]``, ``wind`` the one held in ``fp[FIELD_WIND:FIELD_WIND + 3]``;
    density from the central body's air table ``air`` at the radial height: the day's
    about Earth, none above 600 km; Mars's about Mars). ``pos``: a scratch array of 3.
    Returns m/s^2, frame axes."""
    ax, ay, az = field_acceleration(x, y, z, s, fp, p)
    if fp[FIELD_DRAG] != 0.0:
        pos[0] = x
        pos[1] = y
        pos[2] = z
        rho = air_in(air, radial_height(pos, p))[0]
        if rho > 0.0:
            wx = vx + p[P_SPIN] * y - fp[FIELD_WIND]
            wy = vy - p[P_SPIN] * x - fp[FIELD_WIND + 1]
            wz = vz - fp[FIELD_WIND + 2]
            k = -0.5 * rho * math.sqrt(wx * wx + wy * wy + wz * wz) * fp[FIELD_DRAG]
            ax += k * wx
            ay += k * wy
            az += k * wz
    return ax, ay, az


@njit
def translational_derivative(y, p, s, fp, air, dy):
    """Position and velocity rates only (``dy[0:6]``): :func:`translational_acceleration`."""
    dy[R] = y[V]
    dy[R + 1] = y[V + 1]
    dy[R + 2] = y[V + 2]
    dy[V], dy[V + 1], dy[V + 2] = translational_acceleration(
        y[R], y[R + 1], y[R + 2], y[V], y[V + 1], y[V + 2], p, s, fp, air, np.empty(3))


@njit(borrows=True)
def translational_rk4(y, h, p, s, fp, air, pos):
    """One RK4 step of ``h`` s of position and velocity, in place on ``y[0:6]``.

    The arithmetic of :func:`field_rk4_step` on scalars (no allocation): each
    component comes out bit-identical to it, and to the awake step without drag.
    """
    x, yy, z, vx, vy, vz = y[R], y[R + 1], y[R + 2], y[V], y[V + 1], y[V + 2]
    a1x, a1y, a1z = translational_acceleration(x, yy, z, vx, vy, vz, p, s, fp, air, pos)
    x2, y2, z2 = x + 0.5 * h * vx, yy + 0.5 * h * vy, z + 0.5 * h * vz
    u2, v2, w2 = vx + 0.5 * h * a1x, vy + 0.5 * h * a1y, vz + 0.5 * h * a1z
    a2x, a2y, a2z = translational_acceleration(x2, y2, z2, u2, v2, w2, p, s, fp, air, pos)
    x3, y3, z3 = x + 0.5 * h * u2, yy + 0.5 * h * v2, z + 0.5 * h * w2
    u3, v3, w3 = vx + 0.5 * h * a2x, vy + 0.5 * h * a2y, vz + 0.5 * h * a2z
    a3x, a3y, a3z = translational_acceleration(x3, y3, z3, u3, v3, w3, p, s, fp, air, pos)
    x4, y4, z4 = x + h * u3, yy + h * v3, z + h * w3
    u4, v4, w4 = vx + h * a3x, vy + h * a3y, vz + h * a3z
    a4x, a4y, a4z = translational_acceleration(x4, y4, z4, u4, v4, w4, p, s, fp, air, pos)
    y[R] = x + h / 6.0 * (vx + 2.0 * u2 + 2.0 * u3 + u4)
    y[R + 1] = yy + h / 6.0 * (vy + 2.0 * v2 + 2.0 * v3 + v4)
    y[R + 2] = z + h / 6.0 * (vz + 2.0 * w2 + 2.0 * w3 + w4)
    y[V] = vx + h / 6.0 * (a1x + 2.0 * a2x + 2.0 * a3x + a4x)
    y[V + 1] = vy + h / 6.0 * (a1y + 2.0 * a2y + 2.0 * a3y + a4y)
    y[V + 2] = vz + h / 6.0 * (a1z + 2.0 * a2z + 2.0 * a3z + a4z)


@njit
def _rates(t, y, p, s, fp, air, dy, veh, full, live):
    if live:
        s = bodies_at(fp, t)[0]
    if full:
        awake_derivative(t, y, p, s, fp, dy, veh)
    else:
        translational_derivative(y, p, s, fp, air, dy)


@njit
def field_rk4_step(y, t, h, p, s, fp, air, full=True, live=False, veh=None):
    """One classical RK4 step of ``h`` s in the field.

    ``s``: the other bodies' held positions (:func:`held_bodies`); with
    ``live`` they are evaluated at every stage instead (cruise rails).
    ``full``: the whole state by :func:`awake_derivative` (quaternion
    normalised after the step); otherwise only ``y[0:6]`` by
    :func:`translational_derivative` (``air``: its drag table) and the rest
    copied. Each position and velocity component goes through the same
    operations either way, so a body on rails and an awake coasting one stay
    bit-identical (without drag).
    """
    n = y.shape[0]
    m = n if full else 6
    k1 = np.zeros(n)
    k2 = np.zeros(n)
    k3 = np.zeros(n)
    k4 = np.zeros(n)
    tmp = y.copy()
    _rates(t, y, p, s, fp, air, k1, veh, full, live)
    for i in range(m):
        tmp[i] = y[i] + 0.5 * h * k1[i]
    _rates(t + 0.5 * h, tmp, p, s, fp, air, k2, veh, full, live)
    for i in range(m):
        tmp[i] = y[i] + 0.5 * h * k2[i]
    _rates(t + 0.5 * h, tmp, p, s, fp, air, k3, veh, full, live)
    for i in range(m):
        tmp[i] = y[i] + h * k3[i]
    _rates(t + h, tmp, p, s, fp, air, k4, veh, full, live)
    out = y.copy()
    for i in range(m):
        out[i] = y[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i])
    if full:
        norm = math.sqrt(out[Q] ** 2 + out[Q + 1] ** 2 + out[Q + 2] ** 2 + out[Q + 3] ** 2)
        for i in range(4):
            out[Q + i] /= norm
    return out


@njit
def advance_awake(y, k0, h, n_steps, p, fp, air):
    """Advance a coasting rigid body ``n_steps`` flight-model steps in the field.

    Step ``k`` starts at mission time ``(k0 + k) h``; the other bodies are held
    per 5 s bucket of that time (:func:`held_bodies`). Returns the new state.
    """
    bucket = -1.0
    s = np.zeros((4, 3))
    for k in range(n_steps):
        t = (k0 + k) * h
        if hold_time(t) != bucket:
            bucket = hold_time(t)
            s = bodies_at(fp, bucket)[0]
        y = field_rk4_step(y, t, h, p, s, fp, air, True)
    return y
