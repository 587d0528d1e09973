"""Liquid rocket engines: thrust, mass flow, timing, throttle and gimbal, compiled.

docs/physics.md#propulsion::

    T = f * (tau * T_vac - p_a * A_e)   (never below 0)
    mdot = f * tau * T_vac / (g0 * Isp_vac)

with ``tau`` the throttle, ``p_a`` the ambient pressure, ``A_e`` the nozzle
exit area and ``f`` the spool fraction (0 before first thrust, 1 at full
thrust). The mass flow is fixed by the throttle, so thrust and specific
impulse rise as the air thins. The spool fraction scales the pressure term too
(the exit pressure follows the chamber pressure), so an engine that is off
pushes nothing and draws nothing.

Timing, from the engine's clock ``c`` (seconds since its last ignition or
shutdown command, an integrated entry of the state vector):

* ignition: ``f = 0`` for the dead time ``t_d`` (0.2-0.5 s), then rises
  linearly to 1 over the spool-up time: ``f = min(1, (c - t_d) / t_spool)``;
* shutdown: ``f`` falls linearly from its level at the command to 0 over the
  tail-off (0.25 s): ``f = level * max(0, 1 - c / t_tail)``;
* a stage whose usable propellant is gone stops at once (no tail-off: there
  is nothing left to burn; see :func:`rocketsim.dynamics.rk4.step`).

Throttle and gimbal follow their commands at a bounded rate, evaluated
exactly at every RK4 stage from the last command's time ``t0`` and the value
then: ``x(t) = x0 + (x_cmd - x0) * min(1, rate (t - t0) / |x_cmd - x0|)``.
The gimbal command is a 2-vector (deflection towards body +y, towards body
+z) clipped to the gimbal cone ``|g| <= range``; it slews along a straight
line, which stays inside the (convex) cone. The thrust direction in body
axes is ``(cos d, sin d g_y / d, sin d g_z / d)``, ``d = |g|``.

Flow separation: an over-expanded nozzle separates when its exit pressure
falls below the Summerfield limit ``p_e < 0.4 p_a``
(:data:`~rocketsim.constants.SUMMERFIELD_SEPARATION_RATIO`). The exit
pressure follows the chamber pressure, ``p_e = tau * p_e,full``, so deep
throttle in thick air separates the flow. The engine controller refuses to
throttle below ``tau_sep = 0.4 p_a / p_e,full``: the throttle actually flown
is ``max(tau(t), tau_sep)`` (at most the top of the range). An engine whose
``tau_sep`` exceeds its maximum throttle (a vacuum nozzle at sea level) runs
separated; :func:`separated` reports it so the world can flag it.

Arrays: ``eng`` (engines x :data:`N_ENG`) holds each engine's fixed figures,
``cmd`` (engines x :data:`N_CMD`) its current commands, both float64 with the
column indices below; ``stage`` (stages x :data:`N_STAGE`) each stage's
unusable reserve, dry flag and tank range.
"""

from __future__ import annotations

import math

import numpy as np

from rocketsim.jit import njit
from rocketsim.constants import SUMMERFIELD_SEPARATION_RATIO

# eng columns
E_STAGE = 0         # index of the stage the engine belongs to
E_X = 1             # m, station of the gimbal point (body x)
E_Y = 2             # m, body y of the gimbal point
E_Z = 3             # m, body z of the gimbal point
E_THRUST = 4        # N, vacuum thrust at full throttle
E_MDOT = 5          # kg/s, mass flow at full throttle
E_AREA = 6          # m^2, nozzle exit area
E_PEXIT = 7         # Pa, exit pressure at full throttle (0: never separates)
E_TAU_MIN = 8       # throttle range
E_TAU_MAX = 9
E_TAU_RATE = 10     # 1/s, throttle slew limit
E_GIMBAL_RANGE = 11  # rad, half-angle of the gimbal cone
E_GIMBAL_RATE = 12  # rad/s, gimbal slew limit
E_DEAD = 13         # s, ignition dead time
E_SPOOL = 14        # s, spool-up time
E_TAIL = 15         # s, tail-off time
E_IGNITIONS = 16    # ignitions allowed (1 + restarts)
N_ENG = 17

# cmd columns
C_ON = 0            # 1 after an ignition command, 0 after a shutdown
C_LEVEL = 1         # spool fraction at the last shutdown (start of the tail-off)
C_T_THROTTLE = 2    # s, time of the last throttle command
C_TAU0 = 3          # throttle at that time
C_TAU = 4           # throttle commanded
C_T_GIMBAL = 5      # s, time of the last gimbal command
C_G0 = 6            # gimbal (y, z) at that time, rad (2 columns)
C_G = 8             # gimbal (y, z) commanded, rad (2 columns)
C_IGNITED = 10      # ignitions used
C_Q_START = 11      # Pa: the dynamic pressure where the throttle law starts to back off (nan: no law)
C_Q_END = 12        # Pa: the dynamic pressure where it reaches zero
C_BASE = 13         # the throttle the program last commanded, which the law scales
N_CMD = 14

# stage columns
S_RESERVE = 0       # kg, unusable propellant (1 % of the load)
S_DRY = 1           # 1 once the usable propellant is gone
S_TANK0 = 2         # index of the stage's first tank (its tanks are consecutive)
S_TANKS = 3         # number of tanks
S_DRY_AT = 4        # s, mission time at which the usable propellant ran out (nan before)
N_STAGE = 5


@njit
def spool_fraction(on, level, clock, dead, spool, tail):
    """Spool fraction ``f`` (0..1) from the mode, the clock (s) and the timings (s)."""
    if on > 0.5:
        if clock <= dead:
            return 0.0
        return min(1.0, (clock - dead) / spool)
    if clock >= tail:
        return 0.0
    return level * (1.0 - clock / tail)


@njit
def slew(x0, target, rate, elapsed):
    """Where a value moving from ``x0`` towards ``target`` at ``rate`` per second is after ``elapsed`` s."""
    step = rate * max(elapsed, 0.0)
    if target > x0:
        return min(target, x0 + step)
    return max(target, x0 - step)


@njit
def slew2(a0, b0, a, b, rate, elapsed):
    """A 2-vector slewing along the straight line to ``(a, b)`` at ``rate`` per second."""
    da = a - a0
    db = b - b0
    distance = math.sqrt(da * da + db * db)
    travel = rate * max(elapsed, 0.0)
    if travel >= distance:
        return a, b
    k = travel / distance
    return a0 + k * da, b0 + k * db


@njit
def separation_throttle(p_a, p_exit_full):
    """Smallest throttle whose exit pressure meets the Summerfield limit ``p_e >= 0.4 p_a``."""
    if p_exit_full <= 0.0:
        return 0.0
    return SUMMERFIELD_SEPARATION_RATIO * p_a / p_exit_full


@njit
def engine_state(t, e, clock, eng, cmd, p_a):
    """``(f, tau, g_y, g_z)`` of engine ``e`` at time ``t`` (s): spool fraction, throttle
    actually flown (after the separation floor), and gimbal deflections (rad)."""
    f = spool_fraction(cmd[e, C_ON], cmd[e, C_LEVEL], clock, eng[e, E_DEAD], eng[e, E_SPOOL],
                       eng[e, E_TAIL])
    tau = slew(cmd[e, C_TAU0], cmd[e, C_TAU], eng[e, E_TAU_RATE], t - cmd[e, C_T_THROTTLE])
    floor = min(separation_throttle(p_a, eng[e, E_PEXIT]), eng[e, E_TAU_MAX])
    if tau < floor:
        tau = floor
    gy, gz = slew2(cmd[e, C_G0], cmd[e, C_G0 + 1], cmd[e, C_G], cmd[e, C_G + 1],
                   eng[e, E_GIMBAL_RATE], t - cmd[e, C_T_GIMBAL])
    return f, tau, gy, gz


@njit(inline="always")     # a few operations: typed in its callers, no kernel of its own
def net_thrust(f, tau, thrust_vacuum, exit_area, p_a):
    """Thrust (N) of an engine at spool fraction ``f`` and throttle ``tau`` with vacuum
    thrust ``thrust_vacuum`` (N) and nozzle exit area ``exit_area`` (m^2) at ambient
    pressure ``p_a`` (Pa): ``f (tau T_vac - p_a A_e)``, negative where the air's pressure
    wins (the callers take none then)."""
    return f * (tau * thrust_vacuum - p_a * exit_area)


@njit(borrows=True)
def engine_forces(t, y, dy, first_tank, first_clock, eng, cmd, stage, tank_share, p_a, x_cm):
    """Thrust force and torque of every engine at time ``t`` (s), and the mass flows.

    Writes ``dy`` for the propellant masses (``y[first_tank:]``, kg/s, each
    stage's flow shared among its tanks by ``tank_share``) and the engine
    clocks (``y[first_clock:]``, 1 s/s). Returns the force (N) and the torque
    about the centre of mass at station ``x_cm`` (N m), both in body axes.
    ``p_a`` is the ambient pressure (Pa).
    """
    fx = fy = fz = 0.0
    mx = my = mz = 0.0
    # the direction's (cos d, sin d / d) of the last deflection seen: engines of a group
    # share their gimbal command, so most engines reuse the one before's
    last_gy = last_gz = 0.0
    tilted, cd, sd = False, 1.0, 0.0
    for e in range(eng.shape[0]):
        dy[first_clock + e] = 1.0
        s = int(eng[e, E_STAGE])
        if stage[s, S_DRY] > 0.5:
            continue
        f, tau, gy, gz = engine_state(t, e, y[first_clock + e], eng, cmd, p_a)
        if f <= 0.0:
            continue
        mdot = f * tau * eng[e, E_MDOT]
        k0 = first_tank + int(stage[s, S_TANK0])
        for k in range(int(stage[s, S_TANKS])):
            dy[k0 + k] -= mdot * tank_share[k0 - first_tank + k]
        thrust = net_thrust(f, tau, eng[e, E_THRUST], eng[e, E_AREA], p_a)
        if thrust <= 0.0:
            continue
        if gy != last_gy or gz != last_gz:
            last_gy, last_gz = gy, gz
            d = math.sqrt(gy * gy + gz * gz)
            tilted = d > 0.0
            if tilted:
                cd, sd = math.cos(d), math.sin(d) / d
        if tilted:
            ex, ey, ez = thrust * cd, thrust * sd * gy, thrust * sd * gz
        else:
            ex, ey, ez = thrust, 0.0, 0.0
        rx, ry, rz = eng[e, E_X] - x_cm, eng[e, E_Y], eng[e, E_Z]
        fx += ex
        fy += ey
        fz += ez
        mx += ry * ez - rz * ey
        my += rz * ex - rx * ez
        mz += rx * ey - ry * ex
    return fx, fy, fz, mx, my, mz


@njit
def thrusts(t, y, first_clock, eng, cmd, stage, p_a):
    """Thrust (N) of every engine at time ``t`` and ambient pressure ``p_a``:
    ``f (tau T_vac - p_a A_e)``, zero when negative or the engine's stage is dry
    (the same figure :func:`engine_forces` applies), for readings and the autopilot."""
    out = np.zeros(eng.shape[0])
    for e in range(eng.shape[0]):
        if stage[int(eng[e, E_STAGE]), S_DRY] > 0.5:
            continue
        f, tau, gy, gz = engine_state(t, e, y[first_clock + e], eng, cmd, p_a)
        out[e] = max(0.0, net_thrust(f, tau, eng[e, E_THRUST], eng[e, E_AREA], p_a))
    return out


@njit
def engine_states(t, y, first_clock, eng, cmd, stage, p_a):
    """Every engine at time ``t`` (s) and ambient pressure ``p_a`` (Pa), one row each:
    spool fraction (0 while its stage is dry), throttle flown, gimbal deflections
    (rad) as :func:`engine_state` gives them, 1.0 where its nozzle flow is separated
    (:func:`separated`), else 0.0, and its thrust (N) as :func:`thrusts` gives it: what
    the readings show of the engines, in one call."""
    out = np.empty((eng.shape[0], 6))
    flow_separated = separated(eng, cmd, t, p_a)
    for e in range(eng.shape[0]):
        f, tau, gy, gz = engine_state(t, e, y[first_clock + e], eng, cmd, p_a)
        out[e, 5] = max(0.0, net_thrust(f, tau, eng[e, E_THRUST], eng[e, E_AREA], p_a))
        if stage[int(eng[e, E_STAGE]), S_DRY] > 0.5:
            f = 0.0
            out[e, 5] = 0.0
        out[e, 0], out[e, 1], out[e, 2], out[e, 3] = f, tau, gy, gz
        out[e, 4] = 1.0 if flow_separated[e] else 0.0
    return out


@njit
def separated(eng, cmd, t, p_a):
    """Which engines run with separated nozzle flow at ambient pressure ``p_a`` (Pa):
    the exit pressure at the throttle flown is below the Summerfield limit."""
    out = np.zeros(eng.shape[0], dtype=np.bool_)
    for e in range(eng.shape[0]):
        if eng[e, E_PEXIT] <= 0.0:
            continue
        tau = slew(cmd[e, C_TAU0], cmd[e, C_TAU], eng[e, E_TAU_RATE], t - cmd[e, C_T_THROTTLE])
        tau = max(tau, min(separation_throttle(p_a, eng[e, E_PEXIT]), eng[e, E_TAU_MAX]))
        out[e] = tau * eng[e, E_PEXIT] < SUMMERFIELD_SEPARATION_RATIO * p_a
    return out


@njit(borrows=True, inline="always")
def next_kink(t, h, y, first_clock, eng, cmd, stage):
    """Time (s) from ``t`` to the first instant inside the step ``(t, t + h)`` at which an
    engine's thrust or flow has a kink (end of the dead time, of the spool-up, of
    the tail-off, a throttle or gimbal slew reaching its command), or ``h``.

    The integrator splits the step there, so each part is smooth and a burn
    keeps the method's fourth order through every engine transition.
    """
    first = h
    floor = 1e-9 * h
    for e in range(eng.shape[0]):
        if stage[int(eng[e, E_STAGE]), S_DRY] > 0.5:
            continue
        clock = y[first_clock + e]
        if cmd[e, C_ON] > 0.5:
            a = eng[e, E_DEAD] - clock
            b = a + eng[e, E_SPOOL]
        elif cmd[e, C_LEVEL] > 0.0:
            a = eng[e, E_TAIL] - clock
            b = a
        else:
            continue
        if floor < a < first:
            first = a
        if floor < b < first:
            first = b
        rate = eng[e, E_TAU_RATE]
        a = cmd[e, C_T_THROTTLE] + abs(cmd[e, C_TAU] - cmd[e, C_TAU0]) / rate - t
        if floor < a < first:
            first = a
        rate = eng[e, E_GIMBAL_RATE]
        if rate > 0.0:
            distance = math.hypot(cmd[e, C_G] - cmd[e, C_G0], cmd[e, C_G + 1] - cmd[e, C_G0 + 1])
            a = cmd[e, C_T_GIMBAL] + distance / rate - t
            if floor < a < first:
                first = a
    if first > h - floor:
        return h
    return first


# --- commands (between steps; held for the step) ------------------------------

def throttle_at(eng, cmd, e: int, t: float) -> float:
    """Commanded-path throttle of engine ``e`` at ``t`` (s), before the separation floor."""
    return float(slew(cmd[e, C_TAU0], cmd[e, C_TAU], eng[e, E_TAU_RATE], t - cmd[e, C_T_THROTTLE]))


@njit
def command_throttles(eng, cmd, engines, t, tau):
    """Command each engine of ``engines`` (an int64 array of indices) to throttle ``tau``
    at time ``t`` (s), clipped to its range: its throttle slews on from where it is now.
    One compiled call for a whole stage (a program throttles every step). ``tau`` is
    also the base its dynamic-pressure law scales (:func:`hold_q_law`)."""
    for e in engines:
        cmd[e, C_BASE] = tau
        _command_throttle(eng, cmd, e, t, tau)


@njit(inline="always")     # small: typed in its callers, no kernel of its own
def _command_throttle(eng, cmd, e, t, tau):
    """Command engine ``e`` to throttle ``tau`` at ``t`` (s), clipped to its range."""
    now = slew(cmd[e, C_TAU0], cmd[e, C_TAU], eng[e, E_TAU_RATE], t - cmd[e, C_T_THROTTLE])
    cmd[e, C_TAU0] = now
    cmd[e, C_T_THROTTLE] = t
    cmd[e, C_TAU] = min(max(tau, eng[e, E_TAU_MIN]), eng[e, E_TAU_MAX])


@njit(inline="always")
def q_law_on(cmd) -> bool:
    """Whether any engine of ``cmd`` has a dynamic-pressure throttle law."""
    for e in range(cmd.shape[0]):
        if not math.isnan(cmd[e, C_Q_START]):
            return True
    return False


@njit(inline="always")
def hold_q_law(eng, cmd, t, q):
    """The dynamic-pressure throttle law of each burning engine that has one, at time
    ``t`` (s) and dynamic pressure ``q`` (Pa): the engine is commanded the throttle its
    program last commanded (``C_BASE``) times ``(q_end - q) / (q_end - q_start)``
    clipped to 0..1 (full below ``q_start``, zero at ``q_end``), then clipped to its
    range and slewed to as every command is (docs/physics.md#propulsion)."""
    for e in range(cmd.shape[0]):
        start = cmd[e, C_Q_START]
        if math.isnan(start) or cmd[e, C_ON] < 0.5:
            continue
        end = cmd[e, C_Q_END]
        share = min(1.0, max(0.0, (end - q) / (end - start)))
        _command_throttle(eng, cmd, e, t, cmd[e, C_BASE] * share)


def set_q_law(eng, cmd, engines, t: float, start: float, end: float) -> None:
    """Give each engine of ``engines`` (indices) the throttle law of :func:`hold_q_law`
    from ``start`` to ``end`` (Pa); ``start`` nan removes it, and the engine is
    commanded its base throttle again at time ``t`` (s)."""
    for e in engines:
        had = not math.isnan(cmd[e, C_Q_START])
        cmd[e, C_Q_START], cmd[e, C_Q_END] = start, end
        if had and math.isnan(start):
            command_throttle(eng, cmd, e, t, cmd[e, C_BASE])


def command_throttle(eng, cmd, e: int, t: float, tau: float) -> None:
    """Command engine ``e`` to throttle ``tau`` at time ``t`` (clipped to its range)."""
    command_throttles(eng, cmd, np.array([e], dtype=np.int64), float(t), float(tau))


@njit(inline="always")
def command_gimbals(eng, cmd, engines, t, gy, gz, size):
    """Command the gimbal of each engine of ``engines`` (an int64 array of indices) to
    ``(gy, gz)`` rad at ``t`` (s), clipped to its cone; ``size`` is ``math.hypot(gy, gz)``
    computed by the (Python) caller, so the clipping has the bits it always had. One
    compiled call for every firing engine (the autopilot steers every step)."""
    for e in engines:
        a, b = slew2(cmd[e, C_G0], cmd[e, C_G0 + 1], cmd[e, C_G], cmd[e, C_G + 1],
                     eng[e, E_GIMBAL_RATE], t - cmd[e, C_T_GIMBAL])
        cmd[e, C_G0] = a
        cmd[e, C_G0 + 1] = b
        cmd[e, C_T_GIMBAL] = t
        cone = eng[e, E_GIMBAL_RANGE]
        cy, cz = gy, gz
        if size > cone:
            if size > 0:
                cy, cz = gy * cone / size, gz * cone / size
            else:
                cy, cz = 0.0, 0.0
        cmd[e, C_G] = cy
        cmd[e, C_G + 1] = cz


def command_gimbal(eng, cmd, e: int, t: float, gy: float, gz: float) -> None:
    """Command engine ``e``'s gimbal to ``(gy, gz)`` rad at ``t``, clipped to its cone."""
    gy, gz = float(gy), float(gz)
    command_gimbals(eng, cmd, np.array([e], dtype=np.int64), float(t), gy, gz, math.hypot(gy, gz))


def ignite(y, eng, cmd, stage, e: int, first_clock: int) -> bool:
    """Command engine ``e`` on (its clock restarts); False, and nothing changes, if it is
    already on, its stage is dry, or it has used every ignition it has."""
    if cmd[e, C_ON] > 0.5 or stage[int(eng[e, E_STAGE]), S_DRY] > 0.5:
        return False
    if cmd[e, C_IGNITED] >= eng[e, E_IGNITIONS]:
        return False
    cmd[e, C_ON] = 1.0
    cmd[e, C_IGNITED] += 1.0
    y[first_clock + e] = 0.0
    return True


def shutdown(y, eng, cmd, e: int, first_clock: int) -> bool:
    """Command engine ``e`` off: the tail-off starts from its present spool fraction."""
    if cmd[e, C_ON] < 0.5:
        return False
    clock = y[first_clock + e]
    cmd[e, C_LEVEL] = spool_fraction(1.0, 0.0, clock, eng[e, E_DEAD], eng[e, E_SPOOL], eng[e, E_TAIL])
    cmd[e, C_ON] = 0.0
    y[first_clock + e] = 0.0
    return True
