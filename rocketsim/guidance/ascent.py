"""Ascent insertion guidance: Powered Explicit Guidance of an upper stage to a target orbit.

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
says what remains). In the last ``freeze`` seconds the law is flown as it is.

**The target** (:class:`Orbit`): a periapsis and an apoapsis radius and an
inclination, read as osculating two-body elements or as Kozai mean elements
(circular only; a mission's default, :mod:`rocketsim.frames.mean_elements`).
The insertion is at periapsis (flight-path angle zero); for mean elements the
cut-off state is the osculating state of the mean orbit at the argument of
latitude of the predicted cut-off point (J2's short-period terms: up to 6 km of
radius at 200 km, 0.04 deg of inclination). The node is fixed when given, else
free: the target plane is then, at every cycle, the plane of the inclination
through the predicted cut-off point (:func:`plane_through`), so that the
guidance never spends propellant on a node nobody asked for.

**Flying it** (:class:`Insertion`): the nose is pointed (``fc.point_at``) where
the law will be ``LEAD`` later, the lag of the autopilot's second-order response
behind a steadily turning command (``2 zeta / omega_n``,
:mod:`rocketsim.flight.steering`). The burn's last 150 m/s are planned and flown
at the engines' lowest throttle (``fc.engines``' ``throttle_range``): a step's
velocity gain, which sets how well the cut-off is timed, is then small (0.4 m/s
at the Falcon 9-class second stage's lowest throttle, 1 m/s at full). The
engine is shut down in the step that brings the orbital energy
``v^2 / 2 - mu / r``, with the tail-off's impulse (``a_T t_tail / 2`` along the
thrust, the linear tail-off of :mod:`rocketsim.vehicle.engines`), nearest the
target's: the semi-major axis is then right to half a step's velocity gain.

**What it reads**: only the navigation estimate (``fc.position``,
``fc.velocity``), the accelerometers (``fc.acceleration``: the thrust
acceleration in vacuum) and the engines' reports (``fc.engines``: thrust over
mass flow is the exhaust velocity); never the truth.

Units SI (m, s, kg, m/s, rad), vectors in the inertial frame of the flight
(ECI about Earth), numpy arrays.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from rocketsim.constants import (EARTH_J2, EARTH_MU, EARTH_OMEGA, EARTH_RADIUS_EQ, ENGINE_TAIL_OFF,
                                 G0)
from rocketsim.guidance.rate import Approach
from rocketsim.flight.steering import OMEGA_N, ZETA
from rocketsim.frames.elements import Elements, state_to_elements
from rocketsim.frames.mean_elements import mean_elements_of_state, state_of_mean_elements
from rocketsim.orbits import propagate

START_PASSES = 40           # cycles at most on the state at ignition, to settle the first solution
START_TOLERANCE = 1e-3      # s: the first solution has settled when tgo changes by less
SETTLE_CHANGE = 0.05        # a thrust this far (share) from the last solution's is settled again on
LEAD = 2.0 * ZETA / OMEGA_N  # s: the autopilot's lag behind a steadily turning command (its second-order
                             # response to a ramp): the nose is pointed where the law will be this much later
GRAVITY_OFFSETS = (0.1, 1.0 / 30.0, 1.2, 0.1)   # UPFG block 7: rc = r - a rthrust - b vthrust tgo,
                                                # vc = v + c rthrust / tgo - d vthrust


def unit(x) -> np.ndarray:
    """``x`` over its length."""
    return x / math.sqrt(float(x @ x))


def gravity(r, mu: float) -> np.ndarray:
    """Point-mass gravity (m/s^2) at ``r`` (m)."""
    d = math.sqrt(float(r @ r))
    return -mu / (d * d * d) * r


# --- the target --------------------------------------------------------------------------


class Target(NamedTuple):
    """What the cut-off must reach: ``radius`` (m from the centre), ``speed`` (m/s) and
    ``flight_path`` (rad above the local horizontal) in the plane of unit ``normal``
    (the direction of ``r x v``)."""

    radius: float
    speed: float
    flight_path: float
    normal: np.ndarray


def plane_normal(inclination: float, raan: float) -> np.ndarray:
    """Unit normal (``r x v`` direction) of the plane of ``inclination`` and ascending node
    ``raan`` (rad), in the frame whose equator they are measured in."""
    s = math.sin(inclination)
    return np.array([s * math.sin(raan), -s * math.cos(raan), math.cos(inclination)])


def plane_through(position, velocity, inclination: float) -> float:
    """The ascending node (rad) of the plane of ``inclination`` through ``position`` whose
    direction of motion there is nearer the ``velocity``'s (of the two planes of that
    inclination through a point; the nearest one when the point's latitude exceeds the
    inclination). With the node ``W``: ``n . r = 0`` is ``rho sin(W - phi) = -z cot(i)``,
    ``rho``, ``phi`` the position's distance from the axis and its right ascension. An
    equatorial plane has no node: 0."""
    x, y, z = (float(c) for c in position)
    rho, phi = math.hypot(x, y), math.atan2(y, x)
    if abs(math.sin(inclination)) * rho == 0.0:
        return 0.0
    s = max(-1.0, min(1.0, -z * math.cos(inclination) / (rho * math.sin(inclination))))
    best = None
    for node in (phi + math.asin(s), phi + math.pi - math.asin(s)):
        along = np.cross(plane_normal(inclination, node), position)
        score = float(along @ velocity)
        if best is None or score > best[0]:
            best = (score, node % (2.0 * math.pi))
    return best[1]


@dataclass(frozen=True)
class Orbit:
    """A target orbit: ``periapsis`` and ``apoapsis`` radii (m) and ``inclination`` (rad)
    about a body of ``mu`` (m^3/s^2), in the plane of node ``raan`` (rad) or, with ``raan``
    None, in whichever plane of that inclination passes through the cut-off point
    (:func:`plane_through`). ``mean``: Kozai mean elements with that body's J2
    (``radius`` its reference radius, m), circular only; else osculating two-body
    elements. The insertion is at periapsis."""

    periapsis: float
    apoapsis: float
    inclination: float
    raan: float | None = None
    mean: bool = False
    mu: float = EARTH_MU
    radius: float = EARTH_RADIUS_EQ
    j2: float = EARTH_J2

    def __post_init__(self):
        if not 0.0 < self.periapsis <= self.apoapsis:
            raise ValueError(f"a target orbit needs 0 < periapsis <= apoapsis, got {self.periapsis:g} m, "
                             f"{self.apoapsis:g} m")
        if self.mean and self.apoapsis != self.periapsis:
            raise ValueError("a target in mean elements is circular (periapsis = apoapsis)")

    @property
    def energy(self) -> float:
        """The orbit's two-body energy, J/kg (mean elements: the mean orbit's)."""
        return -self.mu / (self.periapsis + self.apoapsis)

    def at(self, point, velocity) -> Target:
        """The cut-off state wanted at ``point`` (m) for a vehicle moving along ``velocity``
        (m/s: which of the two planes of the inclination through the point, when the node
        is free). Osculating elements: the periapsis of the orbit. Mean elements: the
        osculating state of the mean circle at the argument of latitude of ``point``, in
        the osculating plane through ``point`` (free node) or of the osculating node
        (fixed node). J2 is symmetric about the pole, so the osculating state at node
        ``W`` is the one at node 0 turned by ``W`` about the pole: the osculating
        inclination, radius, speed and flight-path angle depend on the argument of
        latitude alone (taken at node 0, the mean argument corrected once so that the
        osculating state's matches the point's)."""
        point = np.asarray(point, dtype=float)
        if not self.mean:
            node = plane_through(point, velocity, self.inclination) if self.raan is None else self.raan
            a = 0.5 * (self.periapsis + self.apoapsis)
            return Target(self.periapsis, math.sqrt(self.mu * (2.0 / self.periapsis - 1.0 / a)), 0.0,
                          plane_normal(self.inclination, node))
        node = plane_through(point, velocity, self.inclination) if self.raan is None else self.raan
        u = _latitude_argument(point, self.inclination, node)
        r, v = self._osculating(u)
        r, v = self._osculating(u - math.remainder(_latitude_argument(r, self.inclination, 0.0) - u, 2.0 * math.pi))
        h = np.cross(r, v)
        inclination = math.atan2(math.hypot(h[0], h[1]), h[2])
        offset = math.atan2(h[0], -h[1])                  # the osculating node at mean node 0
        node = plane_through(point, velocity, inclination) if self.raan is None else self.raan + offset
        radius, speed = math.sqrt(float(r @ r)), math.sqrt(float(v @ v))
        return Target(radius, speed, math.asin(float(r @ v) / (radius * speed)), plane_normal(inclination, node))

    def reached(self, position, velocity) -> tuple[float, float, float]:
        """The periapsis and apoapsis radii (m) and the inclination (rad) of the orbit of the
        state ``position``, ``velocity`` (m, m/s), in this target's elements (Kozai mean or
        osculating): the figures to compare with the target's. (A mean target read in
        osculating elements is kilometres off: J2's short-period terms.)"""
        elements = (mean_elements_of_state(position, velocity, self.mu, self.radius, self.j2) if self.mean
                    else state_to_elements(np.asarray(position, dtype=float), np.asarray(velocity, dtype=float),
                                           self.mu))
        return elements.periapsis, elements.apoapsis, elements.i

    def _osculating(self, u: float):
        """The osculating state of the mean circle at node 0 and argument of latitude ``u``."""
        return state_of_mean_elements(Elements(self.periapsis, 0.0, self.inclination, 0.0, 0.0,
                                               u % (2.0 * math.pi), self.mu), self.radius, self.j2)


def _latitude_argument(point, inclination: float, node: float) -> float:
    """The angle (rad) of ``point`` from the ascending node ``node`` in the plane of
    ``inclination`` (of the point's projection into it)."""
    line = np.array([math.cos(node), math.sin(node), 0.0])
    return math.atan2(float(np.cross(plane_normal(inclination, node), line) @ point), float(line @ point))


def mission_orbit(target, mu: float = EARTH_MU, radius: float = EARTH_RADIUS_EQ, j2: float = EARTH_J2) -> Orbit:
    """The :class:`Orbit` of a mission's ``target.orbit`` (``fc.target.orbit``: circular
    ``altitude`` above ``radius``, ``inclination``, ``elements`` mean or osculating), its
    node free."""
    r = radius + target.altitude
    return Orbit(r, r, target.inclination, None, target.elements == "mean", mu, radius, j2)


def launch_azimuth(latitude: float, inclination: float, altitude: float, pad_azimuth: float,
                   mu: float = EARTH_MU, radius: float = EARTH_RADIUS_EQ, spin: float = EARTH_OMEGA) -> float:
    """Azimuth (rad from north) over the ground that puts a launch from ``latitude`` into an
    orbit of ``inclination`` (rad) at ``altitude`` (m): the inertial azimuth
    ``sin(b) = cos(i) / cos(lat)`` (of the plane through the pad), less the ground's
    eastward speed ``spin R cos(lat)`` against the orbital speed ``sqrt(mu / (R + h))``;
    of the two branches (north- or south-going) the one nearer ``pad_azimuth``."""
    ratio = max(-1.0, min(1.0, math.cos(inclination) / math.cos(latitude)))
    speed = math.sqrt(mu / (radius + altitude))
    ground = spin * radius * math.cos(latitude)
    candidates = [math.atan2(speed * math.sin(b) - ground, speed * math.cos(b))
                  for b in (math.asin(ratio), math.pi - math.asin(ratio))]
    return min(candidates, key=lambda a: abs(math.remainder(a - pad_azimuth, 2.0 * math.pi)))


# --- one guidance cycle ------------------------------------------------------------------


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
        downrange = unit(np.cross(previous.target.normal, previous.rd))
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
    vd = target.speed * (math.sin(target.flight_path) * up + math.cos(target.flight_path) * np.cross(n, up))
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
    ahead = np.cross(n, up)
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


# --- flying it ---------------------------------------------------------------------------


class Insertion:
    """Flies an upper stage's burn to ``orbit`` with PEG, from its ignition to its cut-off.

    The program ignites the stage, then calls :meth:`update` and sleeps the seconds it
    returns until :attr:`finished`: while the engines spool up the nose follows the
    velocity; then PEG is solved every ``period`` s (:func:`start`, :func:`cycle`) and the
    nose pointed (``fc.point_at``) where the law will be ``LEAD`` s after the middle of
    each sleep. The burn is planned with its last ``final_speed`` m/s at the engines'
    lowest throttle (``fc.engines``' ``throttle_range``; :func:`burn_phases`) and the
    throttle drops there, so that a step's velocity gain, which sets how well the cut-off
    can be timed, is small; the next solution is settled on the new thrust
    (:func:`settle`). Below ``release`` s to go only the cut-off velocity is aimed at
    (a position error of metres, or the navigation's noise, no longer turns the law),
    below ``freeze`` s the last law is flown as it is. The engines are shut down in the
    step that brings the orbital energy, with the tail-off's impulse (``tail_off`` s of
    linear decay), nearest the target's (the module's "cut-off"). A stage that runs dry
    first ends the burn where it is (:attr:`outcome` says which). The wake-ups quicken
    as the energy nears the cut-off's (:class:`~rocketsim.guidance.rate.Approach`):
    the last ones come every step.
    """

    def __init__(self, orbit: Orbit, period: float = 1.0, final_speed: float = 150.0, release: float = 5.0,
                 freeze: float = 2.0, tail_off: float = ENGINE_TAIL_OFF):
        self.orbit = orbit
        self.period = period
        self.final_speed = final_speed
        self.release = release
        self.freeze = freeze
        self.tail_off = tail_off
        self.solution: Solution | None = None
        self.approach = Approach(orbit.energy, rising=True, periods=(period, 0.1))
        self.last_wake: float | None = None
        self.throttled = False
        self.outcome: str | None = None         # "cut-off" or "ran dry" once finished

    @property
    def finished(self) -> bool:
        return self.outcome is not None

    def update(self, fc) -> float:
        """One wake-up of the guidance: steer, throttle or cut off; returns the seconds to
        sleep until the next one (0: the next step)."""
        t = fc.time
        step = None if self.last_wake is None else t - self.last_wake
        self.last_wake = t
        on = [e for e in fc.engines if e["on"]]
        thrust = sum(e["thrust_N"] for e in on)
        if self.solution is not None and thrust <= 0.0:
            self.outcome = "ran dry"
            fc.release()
            return 0.0
        if thrust <= 0.0 or any(e["spool"] < 1.0 for e in on):
            fc.point_at(fc.velocity)
            return 0.0
        r, v = fc.position, fc.velocity
        sensed = fc.acceleration * G0               # the thrust's, in vacuum
        exhaust = thrust / sum(e["mass_flow_kg_s"] for e in on)
        solution = self.solution
        if not self.throttled and solution is not None and solution.switch is not None and t >= solution.switch:
            fc.throttle(0.0)            # clipped to each engine's lowest
            self.throttled = True
        # the thrust at the engines' lowest throttle over the thrust now: the last phase's
        # share, planned; once throttled, 1 when the throttle has slewed down, and until
        # then the plan flies on as it was made (it holds the step down)
        lowest = sum(e["thrust_N"] * e["throttle_range"][0] / e["throttle"] for e in on) / thrust
        slewing = self.throttled and lowest < 1.0 - 1e-9
        final = (0.0, 1.0) if self.throttled else (self.final_speed, lowest)
        if solution is None:
            solution = start(t, r, v, sensed, exhaust, self.orbit, final)
        elif not slewing and solution.tgo - (t - solution.t) > self.freeze:
            expected = solution.exhaust / (solution.tau - (t - solution.t))     # the last solution's thrust
            solve = settle if abs(sensed / expected - 1.0) > SETTLE_CHANGE else \
                cycle if t - solution.t >= self.period - 1e-9 else None
            if solve is not None:
                released = solution.tgo - (t - solution.t) < self.release
                new = solve(solution, t, r, v, sensed, exhaust, self.orbit, released, final)
                if not released and new.tgo < self.release:     # arrived sooner than the last plan said
                    new = solve(solution, t, r, v, sensed, exhaust, self.orbit, True, final)
                solution = new
        self.solution = solution
        mu = self.orbit.mu
        nose = solution.direction(t)
        energy = 0.5 * float(v @ v) - mu / math.sqrt(float(r @ r))
        gain_rate = float(v @ nose) * sensed                   # J/kg per s of thrust
        tail = 0.5 * self.tail_off * gain_rate
        wanted = 0.5 * solution.target.speed ** 2 - mu / solution.target.radius
        half_step = 0.5 * gain_rate * (step if step is not None and step < 0.1 else 0.0)
        if energy + tail + half_step >= wanted:
            fc.shutdown()
            fc.release()
            self.outcome = "cut-off"
            return 0.0
        self.approach.limit = wanted - tail
        self.approach.ahead(energy, t)
        wait = self.approach.next_update()
        if not self.throttled and solution.switch is not None:
            wait = min(wait, max(0.0, solution.switch - t))
        fc.point_at(solution.direction(t + 0.5 * wait + LEAD))
        return wait
