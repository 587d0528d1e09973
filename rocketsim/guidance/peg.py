"""Powered Explicit Guidance: one cycle of an upper stage's insertion guidance.

The problem: a vehicle burning in vacuum (an upper stage after staging) steers
its thrust so that at engine cut-off it is on a target orbit: at a given radius,
speed and flight-path angle, in a given plane. Minimum-propellant steering for a
burn in a uniform gravity field is the **linear-tangent law** (Bryson & Ho,
*Applied Optimal Control*, 1975, sec. 2.7: the tangent of the thrust angle is
linear in time); **Powered Explicit Guidance** (PEG) flies it in vector form,

    u(t) = unit(lambda + lambda_dot (t - t_lambda)),   lambda_dot . lambda = 0,

(the tangent of the angle between ``u`` and ``lambda`` is ``|lambda_dot| (t -
t_lambda)``: linear in time), and corrects the round Earth's gravity with a
predictor-corrector, the whole solved again every guidance cycle from the
navigation state so that it absorbs whatever the engines, the masses or the
model did (Jaggers, "An explicit solution to the exoatmospheric powered flight
guidance and trajectory optimization problem for rocket propelled vehicles",
AIAA 77-1051, 1977; Brand, Brown & Higgins, *Space Shuttle GN&C Equation
Document No. 24: Unified Powered Flight Guidance*, NASA CR-128991, 1973, its
"standard ascent" blocks; McHenry, Brand, Long, Cockrell & Thibodeau, "Space
Shuttle ascent guidance, navigation, and control", *J. Astronaut. Sci.* 27,
1979). One cycle (:func:`cycle`), the blocks of the UPFG document:

* **velocity to be gained** ``vgo``: last cycle's, less what the thrust gained
  since (the velocity change less gravity's, by the trapezoidal rule);
* **time to go** from the rocket equation, constant thrust and exhaust velocity
  ``ve``: ``tgo = tau (1 - exp(-|vgo| / ve))``, ``tau = ve / a_T`` (the time the
  engine would take to burn the whole vehicle, ``a_T`` the thrust acceleration);
* **thrust integrals** (:func:`thrust_integrals`): the moments of the thrust
  acceleration ``a(t) = ve / (tau - t)`` over ``0..tgo``,
  ``L = int a``, ``J = int t a``, ``H = int t^2 a`` and the double integrals
  ``S = int int a``, ``Q = int int t a``, ``P = int int t^2 a``;
* **turning rate**: ``lambda = unit(vgo)`` (with ``t_lambda = J / L`` the thrust
  gains ``L lambda`` to first order); the position the thrust must gain,
  ``rgo = rd - (r + v tgo + rgrav) + rbias``, has its downrange part (along
  ``iz = n x rd``) left free and set so that ``lambda . rgo = S``; then
  ``lambda_dot = (rgo - S lambda) / (Q - S J / L)``. The velocity and position
  the law gains, to second order in the angle ``phi`` between ``u(0)`` and
  ``lambda`` (``vthrust``, ``rthrust``), and what they miss (``vbias = vgo -
  vthrust``, ``rbias = rgo - rthrust``, carried to the next cycle);
* **gravity**: the coast arc that starts from ``rc = r - rthrust / 10 - vthrust
  tgo / 30``, ``vc = v + 1.2 rthrust / tgo - vthrust / 10`` (the UPFG document's
  offsets: a conic whose gravity matches the powered arc's) propagated ``tgo`` on
  the Kepler conic (:func:`rocketsim.orbits.propagate`) gives ``vgrav = vc2 - vc``
  and ``rgrav = rc2 - rc - vc tgo``;
* **cut-off state**: the predicted cut-off point ``rp = r + v tgo + rgrav +
  rthrust`` brought into the target plane at the target radius is ``rd``; the
  target's velocity there ``vd`` (speed and flight-path angle in the plane); and
  ``vgo = vd - v - vgrav + vbias``.

The first cycle starts from a guess (the cut-off point ahead along the target
plane by the arc the burn covers) and is repeated on the same state until the
time to go settles (:func:`start`, :func:`settle`); so is a cycle whose thrust
has stepped. Two refinements for the end of the burn: the burn may be planned
as two constant-thrust phases, its last ``final_speed`` at a lower throttle
(:func:`burn_phases`, :func:`thrust_integrals`: the UPFG document sums the
integrals of its stages the same way), so that the step down does not turn the
law; and in the last seconds the position is released (``released``: the
turning rate ``lambda_dot`` is the last one's, no longer re-derived from the
position to go, while ``lambda = unit(vgo)`` is): ``lambda_dot`` answers a
position error with a gain growing as ``1 / tgo^3``, and there a metre of
navigation noise would swing the law by degrees while a metre of radius is
worth a metre of apsis. Kept, not zeroed, the turning rate leaves the law
continuous: zeroed, the law would step by its turn ``|lambda_dot| J / L``
(about a degree) at the release, and the nose's settling onto it would be left
as climb at the cut-off (0.2 m/s in the shipped ascent; docs/guidance-ascent.md
says what remains). In the last seconds (:class:`~rocketsim.guidance.ascent.Insertion`'s
``freeze``) the law is flown as it is.

The target (:class:`~rocketsim.guidance.target_orbit.Orbit`) gives the cut-off state
wanted at the predicted cut-off point; :class:`~rocketsim.guidance.ascent.Insertion`
flies the cycles through ``fc``.

Units SI (m, s, kg, m/s, rad), vectors in the inertial frame of the flight
(ECI about Earth), numpy arrays.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from rocketsim.frames.vectors import cross
from rocketsim.guidance.target_orbit import Orbit, Target
from rocketsim.orbits import propagate

START_PASSES = 40           # cycles at most on the state at ignition, to settle the first solution
START_TOLERANCE = 1e-3      # s: the first solution has settled when tgo changes by less
GRAVITY_OFFSETS = (0.1, 1.0 / 30.0, 1.2, 0.1)   # UPFG block 7: rc = r - a rthrust - b vthrust tgo,
                                                # vc = v + c rthrust / tgo - d vthrust


def unit(x) -> np.ndarray:
    """``x`` over its length."""
    return x / math.sqrt(float(x @ x))


def gravity(r, mu: float) -> np.ndarray:
    """Point-mass gravity (m/s^2) at ``r`` (m)."""
    d = math.sqrt(float(r @ r))
    return -mu / (d * d * d) * r


def thrust_integrals(phases) -> tuple[float, float, float, float, float, float]:
    """``(L, J, S, Q, P, H)`` of a burn of constant-thrust ``phases``, each
    ``(duration s, tau s, exhaust m/s)`` flown one after the other from now: the moments
    over the burn (``0..T``, ``T`` the phases' total) of the thrust acceleration, in a
    phase ``a = exhaust / (tau - s)`` (``s`` the time into it, ``tau`` the time its thrust
    would take to burn the whole vehicle): ``L = int a``, ``J = int t a``,
    ``H = int t^2 a`` (m/s, m, m s) and the double integrals ``S = int_0^T int_0^t a``,
    ``Q = int int t a``, ``P = int int t^2 a`` (m, m s, m s^2), which are
    ``T L - J``, ``T J - H`` and ``T H - int t^3 a``. A phase's own moments
    ``k_n = int_0^b s^n a ds`` follow from ``k_0 = -exhaust ln(1 - b / tau)`` by
    ``k_n = tau k_(n-1) - exhaust b^n / n``; the burn's are theirs shifted to the
    phase's start. (One phase gives the closed forms of the UPFG document's block 4.)"""
    moments = [0.0, 0.0, 0.0, 0.0]          # int t^n a over the burn, n = 0..3
    begin = 0.0
    for duration, tau, exhaust in phases:
        k = [-exhaust * math.log1p(-duration / tau)]
        for n in (1, 2, 3):
            k.append(tau * k[-1] - exhaust * duration ** n / n)
        moments[0] += k[0]
        moments[1] += k[1] + begin * k[0]
        moments[2] += k[2] + 2.0 * begin * k[1] + begin ** 2 * k[0]
        moments[3] += k[3] + 3.0 * begin * k[2] + 3.0 * begin ** 2 * k[1] + begin ** 3 * k[0]
        begin += duration
    L, J, H, K = moments
    return L, J, begin * L - J, begin * J - H, begin * H - K, H


def burn_phases(speed: float, tau: float, exhaust: float, final_speed: float = 0.0,
                ratio: float = 1.0) -> list[tuple[float, float, float]]:
    """The constant-thrust phases ``(duration s, tau s, exhaust m/s)`` of a burn that gains
    ``speed`` (m/s) at the thrust now (``tau``: the time it would take to burn the whole
    vehicle), its last ``final_speed`` at ``ratio`` of that thrust (a planned throttle-down:
    the same exhaust velocity, ``tau / ratio`` from the mass then); the durations from
    the rocket equation, ``b = tau (1 - exp(-dv / exhaust))``."""
    if ratio < 1.0 and speed > final_speed > 0.0:
        first = tau * -math.expm1(-(speed - final_speed) / exhaust)
        low = (tau - first) / ratio
        return [(first, tau, exhaust), (low * -math.expm1(-final_speed / exhaust), low, exhaust)]
    return [(tau * -math.expm1(-speed / exhaust), tau, exhaust)]


class Solution(NamedTuple):
    """One guidance cycle's solution, carried to the next: at mission time ``t`` (s) the
    state ``r``, ``v``; the velocity to be gained ``vgo``, time to go ``tgo``, cut-off
    point ``rd``, gravity's position effect ``rgrav``, the law's position miss ``rbias``;
    the law ``lam``, ``lam_dot`` (1/s) and its reference time ``t_lambda`` (mission s);
    the ``target`` at the predicted cut-off; the thrust it assumed now, ``tau`` (s) and
    ``exhaust`` (m/s), and the mission time of its planned throttle-down ``switch`` (s;
    None: none planned)."""

    t: float
    r: np.ndarray
    v: np.ndarray
    vgo: np.ndarray
    tgo: float
    rd: np.ndarray
    rgrav: np.ndarray
    rbias: np.ndarray
    lam: np.ndarray
    lam_dot: np.ndarray
    t_lambda: float
    target: Target
    tau: float
    exhaust: float
    switch: float | None

    def direction(self, t: float) -> np.ndarray:
        """The thrust direction of the law at mission time ``t`` (s)."""
        return unit(self.lam + self.lam_dot * (t - self.t_lambda))


def thrust_gain(t0: float, r0, v0, t: float, r, v, mu: float) -> np.ndarray:
    """The velocity (m/s) the thrust gained from ``t0`` to ``t`` (s) between the states
    ``r0``, ``v0`` and ``r``, ``v`` (m, m/s): the velocity change less point-mass gravity's
    (``mu``, m^3/s^2), by the trapezoidal rule."""
    return v - v0 - 0.5 * (t - t0) * (gravity(r0, mu) + gravity(r, mu))


def cycle(previous: Solution, t: float, r, v, acceleration: float, exhaust: float, orbit: Orbit,
          released: bool = False, final: tuple[float, float] = (0.0, 1.0)) -> Solution:
    """One PEG cycle (see the module) at mission time ``t`` from the state ``r`` (m),
    ``v`` (m/s), the thrust acceleration now (m/s^2) and the exhaust velocity (m/s),
    aiming at ``orbit``. ``final``: the last ``final[0]`` m/s flown at ``final[1]`` of the
    thrust now (:func:`burn_phases`). ``released``: the cut-off position is no longer
    aimed at, only the velocity (``lambda_dot`` is the last solution's, not re-derived
    from the position to go; with ``t_lambda = t + J / L`` the law still gains ``vgo``
    to first order in the turn)."""
    mu = orbit.mu
    vgo = previous.vgo - thrust_gain(previous.t, previous.r, previous.v, t, r, v, mu)
    tau = exhaust / acceleration
    speed = math.sqrt(float(vgo @ vgo))
    phases = burn_phases(speed, tau, exhaust, *final)
    tgo = sum(phase[0] for phase in phases)
    L, J, S, Q, P, H = thrust_integrals(phases)

    lam = vgo / speed
    rgrav = (tgo / previous.tgo) ** 2 * previous.rgrav
    if released:        # the last turning rate kept (square to the new lambda), no longer re-aimed
        lam_dot = previous.lam_dot - float(previous.lam_dot @ lam) * lam
        vthrust, rthrust = L * lam, S * lam
        vbias, rbias = np.zeros(3), np.zeros(3)
    else:
        rgo = previous.rd - (r + v * tgo + rgrav) + previous.rbias
        downrange = unit(cross(previous.target.normal, previous.rd))
        rgo = rgo + (S - float(lam @ rgo)) / float(lam @ downrange) * downrange
        lam_dot = (rgo - S * lam) / (Q - S * J / L)
        now = unit(lam - lam_dot * (J / L))
        phi = math.acos(max(-1.0, min(1.0, float(now @ lam))))
        phi_dot = -phi * L / J
        turn = math.sqrt(float(lam_dot @ lam_dot))
        across = lam_dot / turn if turn > 0.0 else np.zeros(3)
        vthrust = (L - 0.5 * L * phi ** 2 - J * phi * phi_dot - 0.5 * H * phi_dot ** 2) * lam \
            - (L * phi + J * phi_dot) * across
        rthrust = (S - 0.5 * S * phi ** 2 - Q * phi * phi_dot - 0.5 * P * phi_dot ** 2) * lam \
            - (S * phi + Q * phi_dot) * across
        vbias, rbias = vgo - vthrust, rgo - rthrust

    a, b, c, d = GRAVITY_OFFSETS
    rc = r - a * rthrust - b * vthrust * tgo
    vc = v + c * rthrust / tgo - d * vthrust
    rc2, vc2 = propagate(mu, rc, vc, tgo)
    vgrav, rgrav = vc2 - vc, rc2 - rc - vc * tgo

    rp = r + v * tgo + rgrav + rthrust
    target = orbit.at(rp, v)
    n = target.normal
    rd = target.radius * unit(rp - float(rp @ n) * n)
    up = rd / target.radius
    vd = target.speed * (math.sin(target.flight_path) * up + math.cos(target.flight_path) * cross(n, up))
    vgo = vd - v - vgrav + vbias
    return Solution(t, r, v, vgo, tgo, rd, rgrav, rbias, lam, lam_dot, t + J / L, target, tau, exhaust,
                    t + phases[0][0] if len(phases) > 1 else None)


def start(t: float, r, v, acceleration: float, exhaust: float, orbit: Orbit,
          final: tuple[float, float] = (0.0, 1.0)) -> Solution:
    """The first solution from the state at ignition (arguments as :func:`cycle`): a guess
    of the cut-off point (ahead in the target plane by the arc flown at the mean of the
    horizontal speed now and the target's, for the time the rocket equation gives to gain
    the target's velocity there), then :func:`settle`."""
    r, v = np.asarray(r, dtype=float), np.asarray(v, dtype=float)
    target = orbit.at(r, v)
    n = target.normal
    up = unit(r - float(r @ n) * n)
    ahead = cross(n, up)
    vd = target.speed * (math.sin(target.flight_path) * up + math.cos(target.flight_path) * ahead)
    tau = exhaust / acceleration
    tgo = tau * -math.expm1(-math.sqrt(float((vd - v) @ (vd - v))) / exhaust)
    arc = 0.5 * (float(v @ ahead) + target.speed) * tgo / target.radius
    rd = target.radius * (math.cos(arc) * up + math.sin(arc) * ahead)
    target = orbit.at(rd, v)
    rgrav = 0.5 * tgo * tgo * gravity(r, orbit.mu)
    solution = Solution(t, r, v, vd - v - 2.0 * rgrav / tgo, tgo, rd, rgrav, np.zeros(3), unit(vd - v),
                        np.zeros(3), t, target, tau, exhaust, None)
    return settle(solution, t, r, v, acceleration, exhaust, orbit, False, final)


def settle(previous: Solution, t: float, r, v, acceleration: float, exhaust: float, orbit: Orbit,
           released: bool = False, final: tuple[float, float] = (0.0, 1.0)) -> Solution:
    """:func:`cycle` repeated on the same state until the time to go changes by less than
    START_TOLERANCE (START_PASSES at most): a solution for a new thrust (ignition, a
    throttle change) that the next cycles need not converge to in flight."""
    solution = previous
    for _ in range(START_PASSES):
        previous = solution
        solution = cycle(previous, t, r, v, acceleration, exhaust, orbit, released, final)
        if abs(solution.tgo - previous.tgo) < START_TOLERANCE:
            break
    return solution
