"""What the accelerometers read: the sensed (specific-force) acceleration.

An accelerometer at the centre of mass measures every force on the vehicle but
gravity, per unit mass::

    a_s = dv/dt - g          (m/s^2, axes of the central body's inertial frame)

with ``dv/dt`` from the derivative the integrator uses (thrust, air, RCS, the
ground's push through the contact points) and ``g`` the whole field the body
flies in: the central body's point mass and J2 and, in an n-body field, the
other bodies' direct and indirect terms (they pull the vehicle and the proof
mass alike). Standing on the pad it reads the ground's push, about 1 g up;
coasting in vacuum, zero. Solar radiation pressure (off by default) rides in
the n-body field's perturbation and is not read.
"""

from __future__ import annotations

import numpy as np

from rocketsim.jit import njit
from rocketsim.bodies.gravity import point_mass_j2
from rocketsim.dynamics.derivative import derivative
from rocketsim.layout import P_J2, P_MU, P_RADIUS, R, V
from rocketsim.dynamics.third_bodies import held_perturbation


@njit
def sensed_acceleration(t, y, p, veh, nbody=None):
    """``a_s`` (m/s^2, frame axes) of state ``y`` at mission time ``t`` (s); ``veh`` the
    vehicle's arrays, None for a rigid body; ``nbody`` True when ``p`` carries an n-body
    field, None when it does not (as :func:`~rocketsim.dynamics.derivative.derivative`'s)."""
    dy = np.zeros(y.shape[0])
    derivative(t, y, p, dy, veh, nbody)
    gx, gy, gz = point_mass_j2(y[R], y[R + 1], y[R + 2], p[P_MU], p[P_RADIUS], p[P_J2])
    if nbody is not None:
        tx, ty, tz = held_perturbation(y[R], y[R + 1], y[R + 2], p)
        gx, gy, gz = gx + tx, gy + ty, gz + tz
    return np.array([dy[V] - gx, dy[V + 1] - gy, dy[V + 2] - gz])
