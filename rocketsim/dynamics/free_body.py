"""A rigid body nobody steers: gravity, a tumbling body's drag, torque-free rotation.

A fairing half or a deployed payload has no engines, no control and no
aerodynamic model of its own: it tumbles. Its model is gravity (the awake
field: central body's point mass and J2, the other bodies of an n-body field),
point-mass drag ``-1/2 rho |v_air| v_air C_D A/m`` with ``v_air = v - omega x r - wind``
(``omega`` the central body's rate, ``p[P_SPIN]``; the day's wind held for the step, as
the vehicles hold it, :func:`rocketsim.dynamics.rk4.wind_at`) and the torque-free rotation of its
inertia. The attitude does not enter the drag (the tumbling body's ``C_D`` and
mean area, :mod:`rocketsim.vehicle.tumbling`), so each step is the sum of two
exact pieces, at the flight model's step ``h``:

- attitude and body rates: the awake rigid body's RK4 step
  (:func:`rocketsim.dynamics.rk4.step`, Euler's equations without torque),
  bit for bit the attitude of a drag-free rigid body;
- position and velocity: RK4 of gravity plus drag,
  :func:`rocketsim.dynamics.nbody.translational_rk4`, the one home of the
  point-mass drag (the sleep rails' too), with ``C_D A/m`` held for the step
  from the Mach and Knudsen numbers at its start, and the wind, in the central
  body's air table (the day's about Earth, Mars's about Mars, none about the Moon).

Where there is no air (above 600 km about Earth, the Moon, or no drag area) the
translational part is the awake step's own, bit for bit a drag-free rigid body's.
"""

from __future__ import annotations

import math

import numpy as np

from rocketsim.jit import copy_into, njit
from rocketsim.atmosphere.table import air_in
from rocketsim.dynamics.derivative import radial_height
from rocketsim.dynamics.nbody import translational_rk4
from rocketsim.dynamics.rk4 import step, wind_at
from rocketsim.layout import P_SPIN, R, V
from rocketsim.dynamics.third_bodies import FIELD_DRAG, FIELD_WIND, P_HELD
from rocketsim.vehicle.tumbling import tumbling_cd


@njit(inline="always")
def drag_factor(y, p, air, wind, area_mass, length):
    """``C_D A/m`` (m^2/kg) of a tumbling body of mean area over mass ``area_mass``
    (m^2/kg) and ``length`` (m) in state ``y`` (0 where there is no air), from the
    air table ``air`` (the arguments of ``air_at`` before the height) and the ``wind``
    (m/s, frame axes)."""
    rho, _, _, sound, _, _ = air_in(air, radial_height(y, p))
    if not (rho > 0.0 and area_mass > 0.0):
        return 0.0
    wx = y[V] + p[P_SPIN] * y[R + 1] - wind[0]
    wy = y[V + 1] - p[P_SPIN] * y[R] - wind[1]
    wz = y[V + 2] - wind[2]
    speed = math.sqrt(wx * wx + wy * wy + wz * wz)
    return area_mass * tumbling_cd(speed / sound, rho, length)


@njit
def free_step(y, t, h, p, fp, air, area_mass, length, nbody=None):
    """One step of ``h`` s from mission time ``t`` (a new state). ``fp``: the field
    array (:func:`rocketsim.dynamics.nbody.make_field`) of the body's central body,
    a scratch copy whose drag slot is set here; ``nbody`` as
    :func:`rocketsim.dynamics.rk4.step`'s."""
    out = step(y, t, h, p, None, nbody)     # attitude (and the n-body hold in p) as the awake body
    wind = wind_at(y, t, p, air)
    k = drag_factor(y, p, air, wind, area_mass, length)
    if k == 0.0:
        return out
    fp[FIELD_DRAG] = k
    fp[FIELD_WIND], fp[FIELD_WIND + 1], fp[FIELD_WIND + 2] = wind
    if nbody is not None:
        s = p[P_HELD:P_HELD + 12].reshape((4, 3)).copy()
    else:
        s = np.zeros((4, 3))
    moved = y.copy()
    translational_rk4(moved, h, p, s, fp, air, np.empty(3))
    copy_into(out, 0, moved[:6])
    return out


@njit
def advance_free(y, k0, h, n_steps, p, fp, air, area_mass, length, nbody=None):
    """Advance up to ``n_steps`` steps (step ``k`` from mission time ``(k0 + k) h``);
    returns ``(y, steps_taken)``. Stops early, after the step that took the body
    below its central body's ellipsoid (an impact). Bit-identical to calling
    :func:`free_step` once per step (``nbody`` as its)."""
    fp = fp.copy()
    for k in range(n_steps):
        y = free_step(y, (k0 + k) * h, h, p, fp, air, area_mass, length, nbody)
        if radial_height(y, p) < 0.0:
            return y, k + 1
    return y, n_steps
