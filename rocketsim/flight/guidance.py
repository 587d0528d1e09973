"""A compiled guidance predictor a flight program can call at every guidance update.

A program's guidance predicts where its vehicle is going many times a
second; in Python a prediction of a few hundred integration steps costs
milliseconds, compiled it costs tens of microseconds. The predictor is a
guidance model (simple on purpose: the closed loop re-solves from the
navigation state at every update and absorbs what the model leaves out):

* **Falling stage** (:func:`descent_point`): an Earth-fixed state integrated
  to the WGS84 ellipsoid under point-mass + J2 gravity, the Coriolis and
  centrifugal terms of the Earth's rotation, drag on an exponential air at a
  ballistic coefficient ``m / (C_D A)``, and optionally a landing burn flown
  by a stated rule (the booster's return in
  ``scenarios/programs/booster_return.py``).

(The upper stage's insertion guidance is :mod:`rocketsim.guidance.ascent`.)

Units SI (m, s, kg, N, rad); frames as each function states. The kernels are
plain numba functions: call them with floats.
"""

from __future__ import annotations

import math

from rocketsim.jit import njit
from rocketsim.bodies.gravity import point_mass_j2
from rocketsim.constants import (EARTH_J2, EARTH_MU, EARTH_OMEGA, EARTH_RADIUS_EQ,
                                 EARTH_RADIUS_POLAR)
from rocketsim.vehicle.contact import point_height

# the falling stage: the steps of its prediction
DESCENT_STEPS = 4000        # at most this many steps (the point reached is returned)
FINE_HEIGHT = 5000.0        # m: below this height the step is FINE_STEP
FINE_STEP = 0.25            # s


@njit
def _falling(x, y, z, vx, vy, vz, h, ballistic, brake, density0, scale_height, j2):
    """Earth-fixed acceleration (m/s^2) of the falling stage: gravity (point mass and
    ``j2``), the Coriolis and centrifugal terms, drag at ``ballistic`` (kg/m^2) in the
    exponential air, and ``brake`` (1/s) times the velocity against it."""
    w = EARTH_OMEGA
    gx, gy, gz = point_mass_j2(x, y, z, EARTH_MU, EARTH_RADIUS_EQ, j2)
    speed = math.sqrt(vx * vx + vy * vy + vz * vz)
    k = density0 * math.exp(-max(h, 0.0) / scale_height) * speed / (2.0 * ballistic) + brake
    # rotating frame: -2 w x v - w x (w x r), w along +z
    return (gx + 2.0 * w * vy + w * w * x - k * vx,
            gy - 2.0 * w * vx + w * w * y - k * vy,
            gz - k * vz)


@njit
def descent_point(x, y, z, vx, vy, vz, ballistic, thrust_accel=0.0, step=2.0, density0=1.225,
                  scale_height=7200.0, burn_below=8e3, margin=0.5, touch_speed=0.5, j2=EARTH_J2):
    """Earth-fixed point ``(x, y, z)`` (m, ECEF) where a falling stage comes down on the
    WGS84 ellipsoid, from its Earth-fixed position ``(x, y, z)`` (m) and velocity
    ``(vx, vy, vz)`` (m/s, relative to the rotating Earth).

    The model: gravity (point mass and ``j2``, Earth's ``EARTH_J2`` by default), the
    Coriolis and centrifugal terms, drag ``rho v^2 / (2 ballistic)`` with ``ballistic``
    = ``m / (C_D A)`` (kg/m^2) in an exponential air ``density0 exp(-h / scale_height)``
    (kg/m^3, m), ``h`` the height above the ellipsoid along the radius. With
    ``thrust_accel`` > 0 (m/s^2, the engines' full thrust over the mass) the landing
    burn is included as a program flies it: lit below ``burn_below`` (m) once stopping
    the fall at a constant deceleration needs more than ``margin`` of what the thrust
    less gravity plus the drag give, then braking against the velocity at the
    deceleration that stops the fall at the ground (at most ``thrust_accel``); the
    point is where the fall has slowed to ``touch_speed`` (m/s). Midpoint (RK2) steps
    of ``step`` s, FINE_STEP below FINE_HEIGHT; the crossing is interpolated
    linearly within the last step; after DESCENT_STEPS steps the point reached is
    returned."""
    h = point_height(x, y, z, EARTH_RADIUS_EQ, EARTH_RADIUS_POLAR)
    burning = False
    for _ in range(DESCENT_STEPS):
        dt = step if h > FINE_HEIGHT else FINE_STEP
        px, py, pz = x, y, z
        brake = 0.0
        if thrust_accel > 0.0:
            radius = math.sqrt(x * x + y * y + z * z)
            fall = -(vx * x + vy * y + vz * z) / radius
            speed = math.sqrt(vx * vx + vy * vy + vz * vz)
            rho = density0 * math.exp(-max(h, 0.0) / scale_height)
            g = EARTH_MU / (radius * radius)
            if not burning and h < burn_below and fall > 0.0 and fall * fall / (2.0 * h) > \
                    margin * (thrust_accel - g + 0.5 * rho * speed * speed / ballistic):
                burning = True
            if burning:
                if fall <= touch_speed or speed < 1.0:
                    return x, y, z
                brake = min(thrust_accel, fall * fall / (2.0 * max(h, 0.1)) + g) / speed
        ax, ay, az = _falling(x, y, z, vx, vy, vz, h, ballistic, brake, density0, scale_height, j2)
        mx, my, mz = x + 0.5 * dt * vx, y + 0.5 * dt * vy, z + 0.5 * dt * vz
        mvx, mvy, mvz = vx + 0.5 * dt * ax, vy + 0.5 * dt * ay, vz + 0.5 * dt * az
        mh = point_height(mx, my, mz, EARTH_RADIUS_EQ, EARTH_RADIUS_POLAR)
        ax, ay, az = _falling(mx, my, mz, mvx, mvy, mvz, mh, ballistic, brake, density0, scale_height, j2)
        x, y, z = x + dt * mvx, y + dt * mvy, z + dt * mvz
        vx, vy, vz = vx + dt * ax, vy + dt * ay, vz + dt * az
        h_new = point_height(x, y, z, EARTH_RADIUS_EQ, EARTH_RADIUS_POLAR)
        if h_new <= 0.0:
            f = h / (h - h_new)
            return px + f * (x - px), py + f * (y - py), pz + f * (z - pz)
        h = h_new
    return x, y, z


def warm_up() -> None:
    """Load (or compile) the kernel now: a program calls this at load time, so the
    first guidance update inside a step does not wait for it."""
    descent_point(EARTH_RADIUS_EQ + 1e4, 0.0, 0.0, -100.0, 0.0, 0.0, 1800.0, 10.0, 2.0,
                  1.225, 7200.0, 8e3, 0.5, 0.5, EARTH_J2)

