"""Classical fourth-order Runge-Kutta at a fixed step, as the flight model flies.

"The integrator" (physics model): every body is advanced by classical RK4 at
a fixed step (20 ms by default, any headless step up to 0.1 s). Within 2 m of
the ground the step is split into four equal sub-steps so stiff contact stays
stable. The attitude quaternion is normalised after each (sub-)step, not
inside the stages (EQUATIONS.md, "Equations of motion").
"""

import math

import numpy as np

from rocketsim._jit import njit
from rocketsim.constants import GROUND_SUBSTEP_HEIGHT, GROUND_SUBSTEPS
from rocketsim.dynamics.derivative import derivative
from rocketsim.dynamics.state import P_POLAR_RADIUS, P_RADIUS, Q, R


@njit
def rk4_step(y, t, h, p):
    """One classical RK4 step of size ``h`` (s) from ``(t, y)``; returns the new state."""
    n = y.shape[0]
    k1 = np.empty(n)
    k2 = np.empty(n)
    k3 = np.empty(n)
    k4 = np.empty(n)
    tmp = np.empty(n)
    derivative(t, y, p, k1)
    for i in range(n):
        tmp[i] = y[i] + 0.5 * h * k1[i]
    derivative(t + 0.5 * h, tmp, p, k2)
    for i in range(n):
        tmp[i] = y[i] + 0.5 * h * k2[i]
    derivative(t + 0.5 * h, tmp, p, k3)
    for i in range(n):
        tmp[i] = y[i] + h * k3[i]
    derivative(t + h, tmp, p, k4)
    out = np.empty(n)
    for i in range(n):
        out[i] = y[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i])
    norm = math.sqrt(out[Q] ** 2 + out[Q + 1] ** 2 + out[Q + 2] ** 2 + out[Q + 3] ** 2)
    for i in range(4):
        out[Q + i] /= norm
    return out


@njit
def radial_height(y, p):
    """Height (m) above the central body's ellipsoid, measured along the radius.

    ``|r| - a b / sqrt(b^2 cos^2 phi_c + a^2 sin^2 phi_c)`` (phi_c geocentric
    latitude, a and b the equatorial and polar radii). Within a few metres of
    the surface it differs from the geodetic height by less than 0.1 mm, and
    it has the same sign: it serves the ground-proximity and impact tests
    (telemetry and programs read the geodetic height).
    """
    rho2 = y[R] ** 2 + y[R + 1] ** 2
    z2 = y[R + 2] ** 2
    r2 = rho2 + z2
    a = p[P_RADIUS]
    b = p[P_POLAR_RADIUS]
    return math.sqrt(r2) - a * b / math.sqrt((b * b * rho2 + a * a * z2) / r2)


@njit
def near_ground(y, p):
    """True when the body is within 2 m of its central body's reference ellipsoid.

    The bound ``|r| - a`` (a = equatorial radius) rules out almost every step
    before :func:`radial_height` is computed.
    """
    r = math.sqrt(y[R] ** 2 + y[R + 1] ** 2 + y[R + 2] ** 2)
    if r - p[P_RADIUS] > GROUND_SUBSTEP_HEIGHT:
        return False
    return radial_height(y, p) < GROUND_SUBSTEP_HEIGHT


@njit
def step(y, t, h, p):
    """Advance one flight-model step of ``h`` seconds (sub-stepped near the ground)."""
    if near_ground(y, p):
        sub = h / GROUND_SUBSTEPS
        for k in range(GROUND_SUBSTEPS):
            y = rk4_step(y, t + k * sub, sub, p)
        return y
    return rk4_step(y, t, h, p)


@njit
def advance(y, k0, h, n_steps, p):
    """Advance up to ``n_steps`` flight-model steps; returns ``(y, steps_taken)``.

    Step ``k`` starts at mission time ``k h`` (``k`` counted from ``k0``, so
    time never accumulates rounding). Identical, bit for bit, to calling
    :func:`step` once per step: a coast with nothing to decide between steps
    is batched this way. Stops early, after the step that took the body below
    its central body's ellipsoid (an impact).
    """
    for k in range(n_steps):
        y = step(y, (k0 + k) * h, h, p)
        if radial_height(y, p) < 0.0:
            return y, k + 1
    return y, n_steps
