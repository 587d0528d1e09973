"""Burns and approach trims for flight programs on interplanetary missions.

Helpers a program imports (``from rocketsim.flight.maneuvers import burn``):
they only use the ``fc`` API, hand back control step by step like any
program, and state units and frames as ``fc`` does (SI, the central body's
frame).

- :func:`burn`: "velocity to be gained" guidance. At the engine's 10 %
  floor the vehicle first turns to the burn's initial direction; then the
  nose follows the velocity still to gain, the throttle drops as it
  shrinks (never below the engine's 10 % floor) and the engine is shut down within a tolerance of the
  target. In the last 2 m/s the direction is held, not chased (the
  velocity left is then small and noisy in direction), and the engine stops
  where the velocity left is smallest: the vehicle stops turning before
  cutoff instead of tumbling on after it. The engine's gimbal turns the
  vehicle, so a burn starting far from its direction wastes some delta-v;
  with ``rcs_turn=True`` a vehicle with RCS thrusters turns on them first
  (engine off, until the nose is within 1 deg of the burn direction and the
  body rates below 0.1 deg/s), keeps them on through the burn (roll and
  help with pitch and yaw) and hands them back off after it.
- :func:`hyperbola_velocity`: the velocity at a position on the escape
  hyperbola whose excess velocity is a given vector (closed form below).
- :func:`trim_periapsis`: turn the velocity in its own plane, speed kept,
  so that the predicted periapsis (``fc.predict``: the full n-body field)
  is at a given radius; a secant search on the turn angle.
"""

from __future__ import annotations

import math

import numpy as np

from rocketsim.constants import G0, SECONDS_PER_DAY
from rocketsim.frames.quaternion import quat_to_matrix

MIN_THROTTLE = 0.1
HOLD_BELOW = 2.0        # m/s left to gain below which a burn stops re-aiming
ALIGNED = math.cos(math.radians(5.0))   # nose within 5 deg of the burn direction
RCS_ALIGNED = math.cos(math.radians(1.0))   # an RCS turn ends within 1 deg of it ...
RCS_SETTLED = math.radians(0.1)             # ... with every body rate below 0.1 deg/s


def unit(v) -> np.ndarray:
    return np.asarray(v, dtype=float) / np.linalg.norm(v)


def burn_time(mass: float, dv: float, thrust: float, isp: float) -> float:
    """Seconds at full ``thrust`` (N, vacuum Isp ``isp`` s) to gain ``dv`` m/s from
    ``mass`` kg (the rocket equation)."""
    exhaust = isp * G0
    return mass * (1.0 - math.exp(-dv / exhaust)) / (thrust / exhaust)


def turn_with_rcs(fc, target_velocity) -> bool:
    """Turn the nose onto the velocity still to gain, ``target_velocity() - fc.velocity``
    (m/s, frame axes), with the RCS thrusters, engines off, until it is within
    ``RCS_ALIGNED`` and every body rate is below ``RCS_SETTLED`` rad/s; the
    thrusters stay on. False (nothing done) for a vehicle without thrusters."""
    try:
        fc.rcs(True)
    except ValueError:
        return False

    def settled() -> bool:
        togo = target_velocity() - fc.velocity
        fc.point_at(togo)
        nose = quat_to_matrix(fc.attitude)[:, 0]
        return (float(nose @ togo) / float(np.linalg.norm(togo)) > RCS_ALIGNED
                and float(np.max(np.abs(fc.body_rates))) < RCS_SETTLED)

    fc.wait_until(settled)
    return True


def burn(fc, target_velocity, label: str, thrust: float, isp: float, tolerance: float = 0.1,
         rcs_turn: bool = False):
    """Burn until ``fc.velocity`` is ``target_velocity()`` (m/s) within ``tolerance``.

    ``thrust`` (N) and ``isp`` (s): the vehicle's engines at full throttle (for
    the throttle-down and the event's delta-v). ``rcs_turn``: turn with the RCS
    thrusters before igniting (:func:`turn_with_rcs`; the event then also has the
    turn's ``turn_s``). Records an event ``label`` with the delta-v spent (rocket
    equation), the velocity left to gain and the duration; returns the delta-v
    spent (m/s).
    """
    t_turn = fc.time
    rcs = rcs_turn and turn_with_rcs(fc, target_velocity)
    m0, t0 = fc.mass, fc.time
    togo = target_velocity() - fc.velocity
    left = best = float(np.linalg.norm(togo))
    first = togo / left
    fc.point_at(first)
    fc.throttle(MIN_THROTTLE)
    fc.ignite()
    turning = True
    lit = False                 # spooled up: before, drift can grow the velocity left
    while True:
        togo = target_velocity() - fc.velocity
        left = float(np.linalg.norm(togo))
        lit = lit or fc.thrust >= MIN_THROTTLE * thrust   # spooled up to the least throttle
        if left < tolerance or lit and ((left < HOLD_BELOW and left > best) or (left > best + 1.0 and left < 5.0)):
            break               # on target, or as close as the held direction gets
        if fc.time > t0 + 5.0 and fc.thrust == 0.0:
            fc.log(f"{label}: no thrust left, {left:.1f} m/s to go")
            break
        best = min(best, left)
        nose = quat_to_matrix(fc.attitude)[:, 0]
        if turning:
            # turn to the first direction (a fixed target: chasing the velocity left,
            # which the low thrust turns as fast as the vehicle does, can orbit it)
            turning = float(nose @ first) < ALIGNED
        elif left > HOLD_BELOW:
            fc.point_at(togo)       # below: hold the direction, so the rates die out by cutoff
        aligned = float(nose @ togo) / left
        wanted = min(1.0, left / (2.0 * thrust / fc.mass))
        fc.throttle(max(wanted if aligned > ALIGNED and not turning else 0.0, MIN_THROTTLE))
        fc.step()
    fc.shutdown()
    fc.release()
    if rcs:
        fc.rcs(False)
    spent = isp * G0 * math.log(m0 / fc.mass)
    figures = {"turn_s": t0 - t_turn} if rcs else {}
    fc.event(label, delta_v_m_s=spent, left_m_s=left, duration_s=fc.time - t0, **figures)
    return spent


def hyperbola_velocity(r, v_inf, mu: float) -> np.ndarray:
    """Velocity (m/s) at ``r`` (m) on the hyperbola about ``mu`` (m^3/s^2) that leaves
    with the excess velocity vector ``v_inf`` (m/s), moving towards it.

    In the plane of ``r`` and ``v_inf``, with ``theta`` the angle from ``r`` to
    the asymptote and ``s = sqrt(e^2 - 1)``, the conic equation
    ``|r| (1 + e cos(nu_inf - theta)) = p`` with ``cos nu_inf = -1/e`` and
    ``p = mu s^2 / v_inf^2`` becomes the quadratic
    ``(mu / v_inf^2) s^2 - |r| sin(theta) s - |r| (1 - cos theta) = 0``;
    then ``h = sqrt(mu p)``, ``nu = nu_inf - theta``, ``v_r = mu e sin(nu) / h``,
    ``v_t = h / |r|`` (Bate, Mueller & White, Fundamentals of Astrodynamics, ch. 1-2).
    """
    r = np.asarray(r, dtype=float)
    rn = float(np.linalg.norm(r))
    speed = float(np.linalg.norm(v_inf))
    u = np.asarray(v_inf, dtype=float) / speed
    normal = unit(np.cross(r, u))
    radial = r / rn
    along = np.cross(normal, radial)
    theta = math.atan2(float(u @ along), float(u @ radial))
    k = mu / speed ** 2
    s = (rn * math.sin(theta) + math.sqrt((rn * math.sin(theta)) ** 2
                                          + 4.0 * k * rn * (1.0 - math.cos(theta)))) / (2.0 * k)
    e = math.sqrt(1.0 + s * s)
    p = k * s * s
    h = math.sqrt(mu * p)
    nu = math.acos(-1.0 / e) - theta
    return (mu * e * math.sin(nu) / h) * radial + (h / rn) * along


def turned(v, normal, angle: float) -> np.ndarray:
    """``v`` turned by ``angle`` (rad) about the unit vector ``normal`` (perpendicular to it)."""
    return v * math.cos(angle) + np.cross(normal, v) * math.sin(angle)


def periapsis_radius(fc, delta_v, horizon: float) -> float:
    """Radius (m) of the next periapsis within ``horizon`` s after ``delta_v`` now."""
    _, r, _ = fc.predict(horizon, delta_v, periapsis=True)
    return float(np.linalg.norm(r))


def trim_periapsis(fc, radius: float, label: str, thrust: float, isp: float,
                   horizon: float = 3 * SECONDS_PER_DAY, smallest: float = 1.0, rcs_turn: bool = False) -> float:
    """Turn the velocity in its plane (speed kept) so that the next periapsis is at
    ``radius`` (m, within 200 m); burns only when the change is at least
    ``smallest`` m/s (turning the vehicle to burn costs more; ``rcs_turn`` as in
    :func:`burn`). Returns the delta-v."""
    v = fc.velocity.copy()
    normal = unit(np.cross(fc.position, v))
    a0, f0 = 0.0, periapsis_radius(fc, None, horizon) - radius
    a1, f1 = 1e-3, f0
    for _ in range(16):
        f1 = periapsis_radius(fc, turned(v, normal, a1) - v, horizon) - radius
        if abs(f1) < 200.0 or f1 == f0:
            break
        a0, f0, a1 = a1, f1, a1 - f1 * (a1 - a0) / (f1 - f0)
    fc.log(f"{label}: turn {math.degrees(a1):.4f} deg for a periapsis {f1 / 1e3:+.2f} km off")
    change = turned(v, normal, a1) - v
    if np.linalg.norm(change) < smallest:
        return 0.0
    start = fc.velocity.copy()
    return burn(fc, lambda: start + change, label, thrust, isp, rcs_turn=rcs_turn)


def time_to_periapsis(fc, horizon: float = 3 * SECONDS_PER_DAY) -> float:
    """Seconds to the next periapsis about the central body (the full field)."""
    return fc.predict(horizon, periapsis=True)[0] - fc.time
