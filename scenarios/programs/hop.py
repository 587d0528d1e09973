"""A first-stage hop: liftoff, climb, hover, and land back on the spot it left.

Flown by ``scenarios/falcon9-hop.yaml`` (the Falcon 9 booster alone, light:
25 t of propellant). One engine (the centre one when there is one) burns
throughout; each step the program asks for an acceleration and turns it into
a thrust direction (the autopilot's command) and a throttle (mass times the
acceleration's size over the full thrust measured once the engine has
spooled up)::

    up:          g + SPEED_GAIN (v_ref - v_z)
    horizontal:  -POSITION_GAIN x - DRIFT_GAIN v_h   (leaning at most MAX_LEAN)

``x`` and ``v_h`` the offset (m) from the liftoff point and the ground
velocity (m/s), local east-north; ``v_ref`` the descent-rate reference of the
phase: CLIMB_SPEED up to HOP_HEIGHT of radar clearance, HEIGHT_GAIN times the
height error for HOVER_TIME, then down at ``TOUCH_SPEED + h / EASE_TIME`` (at
most DESCENT_SPEED); the engine is cut CUTOFF_CLEARANCE above the ground.
Reads only the navigation estimate.
"""

import math

import numpy as np

from rocketsim.frames.earth_fixed import eci_to_ecef, eci_to_ecef_velocity
from rocketsim.frames.geodetic import enu_basis

HOP_HEIGHT = 100.0          # m of clearance (feet above the ground)
CLIMB_SPEED = 10.0          # m/s
HOVER_TIME = 10.0           # s
DESCENT_SPEED = 8.0         # m/s
EASE_TIME = 3.0             # s: descent rate TOUCH_SPEED + h / EASE_TIME near the ground
TOUCH_SPEED = 0.6           # m/s at contact
CUTOFF_CLEARANCE = 0.15     # m
HEIGHT_GAIN = 0.4           # 1/s
SPEED_GAIN = 1.2            # 1/s
POSITION_GAIN = 0.05        # 1/s^2
DRIFT_GAIN = 0.5            # 1/s
MAX_LEAN = math.radians(5.0)
SPOOL_THROTTLE = 0.5        # while spooling up: less than the weight, the stage stays put


def main(fc):
    home, axes = liftoff_point(fc)
    engine = [e["name"] for e in fc.engines if e["name"].endswith("centre")] or None
    fc.ignite(engine)
    fc.throttle(SPOOL_THROTTLE)
    fc.point(math.pi / 2, 0.0)
    fc.wait_until(lambda: spooled(fc))
    full = sum(e["thrust_N"] / e["throttle"] for e in fc.engines if e["thrust_N"] > 0.0)
    fc.event("hop start", full_thrust_n=full)
    climb = lambda h, t: CLIMB_SPEED                                      # noqa: E731
    fly(fc, home, axes, full, climb, until=lambda h, t: h >= HOP_HEIGHT)
    start = fc.time
    fc.event("hover", clearance_m=fc.clearance)
    hover = lambda h, t: HEIGHT_GAIN * (HOP_HEIGHT - h)                  # noqa: E731
    fly(fc, home, axes, full, hover, until=lambda h, t: t - start >= HOVER_TIME)
    fc.deploy_legs()
    down = lambda h, t: -min(DESCENT_SPEED, TOUCH_SPEED + max(h, 0.0) / EASE_TIME)   # noqa: E731
    fly(fc, home, axes, full, down, until=lambda h, t: h < CUTOFF_CLEARANCE)
    fc.shutdown(engine)
    fc.release()
    fc.event("hop end", clearance_m=fc.clearance, vertical_speed_m_s=fc.vertical_speed)


def liftoff_point(fc):
    """The centre of mass's Earth-fixed position (m) before liftoff, and the local
    east-north-up rows (Earth-fixed) there."""
    return eci_to_ecef(fc.position, fc.time), enu_basis(fc.latitude, fc.longitude)


def spooled(fc):
    firing = [e for e in fc.engines if e["thrust_N"] > 0.0]
    return bool(firing) and all(e["spool"] >= 1.0 for e in firing)


def fly(fc, home, axes, full, reference, until):
    """Steer and throttle each step until ``until(clearance, time)``; ``reference(clearance,
    time)`` is the wanted vertical speed (m/s, up)."""
    while True:
        h, t = fc.clearance, fc.time
        if until(h, t):
            return
        r, v = fc.position, fc.velocity
        local_offset = axes @ (eci_to_ecef(r, t) - home)
        local_velocity = axes @ eci_to_ecef_velocity(r, v, t)
        up_acc = max(fc.effective_gravity + SPEED_GAIN * (reference(h, t) - local_velocity[2]), 0.5)
        side = -POSITION_GAIN * local_offset[:2] - DRIFT_GAIN * local_velocity[:2]
        size = float(np.linalg.norm(side))
        cap = up_acc * math.tan(MAX_LEAN)
        if size > cap:
            side *= cap / size
        wanted = np.array([side[0], side[1], up_acc])
        fc.point_at(wanted, frame="local")
        fc.throttle(fc.mass * float(np.linalg.norm(wanted)) / full)
        fc.step()
