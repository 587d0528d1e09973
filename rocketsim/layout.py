"""The state and parameter slots of one body: the layout every kernel reads.

State ``y`` (float64, length :data:`N_STATE`), in the inertial frame:

======  =====  ==============================================================
index   name   meaning
======  =====  ==============================================================
0:3     r      position of the centre of mass, m
3:6     v      velocity of the centre of mass, m/s
6:10    q      unit quaternion (w, x, y, z), body axes -> inertial frame
10:13   w      body rates about the body axes, rad/s (x is the roll axis)
======  =====  ==============================================================

A staged vehicle (:mod:`rocketsim.vehicle.build`) carries more integrated
quantities after index 13, so that the same RK4 stages integrate them: the
propellant mass of each of its tanks (kg), then the clock of each of its
engines (s since its last ignition or shutdown command).

Parameters ``p`` (float64, length :data:`N_PARAMS`) are what the derivative
reads but does not integrate: the mass and the diagonal inertia of a rigid
body, the central body's gravity (mu, reference radius, J2) and rotation rate
(:data:`P_SPIN`: the ground and the air turn at it about the frame's z, the
body's pole), which model flies the body (:data:`P_CLASSIC`: 1 on the classic
range, whose original model holds a staged vehicle's thrust, mass and upper-air
density for the step; see :func:`rocketsim.dynamics.derivative.held_derivative`),
and whether the body flies in the n-body field (:data:`P_NBODY`: 1 when the
field and the other bodies' held positions follow the slots,
:func:`rocketsim.dynamics.third_bodies.with_field`). Index constants below
are the only names for these slots.
"""

import numpy as np

from rocketsim.constants import EARTH_OMEGA

# state slots
R = 0
V = 3
Q = 6
W = 10
N_STATE = 13

# parameter slots
P_MASS = 0          # kg
P_IXX = 1           # kg m^2, roll
P_IYY = 2           # kg m^2, pitch
P_IZZ = 3           # kg m^2, yaw
P_MU = 4            # m^3/s^2, central body
P_RADIUS = 5        # m, central body's reference radius
P_J2 = 6            # central body's J2 (0 for a point mass)
P_POLAR_RADIUS = 7  # m, central body's polar radius (ground proximity)
P_CLASSIC = 8       # 1: the classic range's original model (held for the step), 0: realistic
P_SPIN = 9          # rad/s, central body's rotation rate about the frame's z (its pole)
P_NBODY = 10        # 1: the n-body field follows these slots (rocketsim.dynamics.third_bodies), 0: none
N_PARAMS = 11


def make_state(r, v, q=(1.0, 0.0, 0.0, 0.0), w=(0.0, 0.0, 0.0)) -> np.ndarray:
    """Assemble a state vector from position, velocity, attitude and rates."""
    y = np.empty(N_STATE)
    y[R:R + 3] = r
    y[V:V + 3] = v
    y[Q:Q + 4] = q
    y[Q:Q + 4] /= np.linalg.norm(y[Q:Q + 4])
    y[W:W + 3] = w
    return y


def make_params(mass, inertia, mu, radius, j2, polar_radius, classic=False,
                spin=EARTH_OMEGA) -> np.ndarray:
    """Assemble the parameter vector (SI units; ``inertia`` = (Ixx, Iyy, Izz));
    ``classic``: fly the classic range's original model (:data:`P_CLASSIC`);
    ``spin``: the central body's rotation rate, rad/s (:data:`P_SPIN`; Earth's by
    default, :func:`rocketsim.dynamics.soi.central_params` sets another body's)."""
    p = np.empty(N_PARAMS)
    p[P_MASS] = mass
    p[P_IXX:P_IZZ + 1] = inertia
    p[P_MU] = mu
    p[P_RADIUS] = radius
    p[P_J2] = j2
    p[P_POLAR_RADIUS] = polar_radius
    p[P_CLASSIC] = 1.0 if classic else 0.0
    p[P_SPIN] = spin
    p[P_NBODY] = 0.0
    return p
