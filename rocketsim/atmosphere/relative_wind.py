"""The velocity the air sees: inertial velocity less the turning air and the wind.

Physics model ("The state and its frames"): the air turns with Earth, so the
velocity the aerodynamics see is ``v_air = v - omega_E x r - w``, with ``w``
the wind (EQUATIONS.md, "Equations of motion"). All vectors in the inertial
frame (ECI), m and m/s; Earth's rotation vector is ``(0, 0, EARTH_OMEGA)``.
About the Moon or Mars the frame's z is the body's pole and its rotation
vector ``(0, 0, spin)`` (the parameters' ``P_SPIN``).
"""

import numpy as np

from rocketsim._jit import njit
from rocketsim.constants import EARTH_OMEGA


@njit
def air_velocity(r, v, wind, spin=EARTH_OMEGA):
    """``v - omega x r - wind`` (m/s, frame axes) for position ``r`` (m) and velocity
    ``v`` (m/s), ``omega = (0, 0, spin)`` the central body's rotation (rad/s; Earth's
    by default)."""
    out = np.empty(3)
    out[0] = v[0] + spin * r[1] - wind[0]
    out[1] = v[1] - spin * r[0] - wind[1]
    out[2] = v[2] - wind[2]
    return out
