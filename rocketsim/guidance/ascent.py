"""Ascent insertion guidance: an upper stage flown to its target orbit by Powered Explicit Guidance.

A vehicle burning in vacuum (an upper stage after staging) steers its thrust so
that at engine cut-off it is on a target orbit. The law and one guidance cycle
are :mod:`rocketsim.guidance.peg` (Powered Explicit Guidance: the linear-tangent
law re-solved every cycle, its gravity by a predictor-corrector); the target,
osculating or Kozai mean elements, node fixed or free, is
:mod:`rocketsim.guidance.target_orbit`. Here: the target of a mission, the launch
azimuth, and the burn flown through ``fc``.

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

from rocketsim.constants import (EARTH_J2, EARTH_MU, EARTH_OMEGA, EARTH_RADIUS_EQ, ENGINE_TAIL_OFF,
                                 G0)
from rocketsim.flight.steering import OMEGA_N, ZETA
from rocketsim.guidance.peg import Solution, cycle, settle, start
from rocketsim.guidance.rate import Approach
from rocketsim.guidance.target_orbit import Orbit

SETTLE_CHANGE = 0.05        # a thrust this far (share) from the last solution's is settled again on
LEAD = 2.0 * ZETA / OMEGA_N  # s: the autopilot's lag behind a steadily turning command (its second-order
                             # response to a ramp): the nose is pointed where the law will be this much later


def mission_orbit(target, mu: float = EARTH_MU, radius: float = EARTH_RADIUS_EQ, j2: float = EARTH_J2) -> Orbit:
    """The :class:`~rocketsim.guidance.target_orbit.Orbit` of a mission's ``target.orbit``
    (``fc.target.orbit``: circular ``altitude`` above ``radius``, ``inclination``,
    ``elements`` mean or osculating), its node free."""
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


# --- flying it ---------------------------------------------------------------------------


class Insertion:
    """Flies an upper stage's burn to ``orbit`` with PEG, from its ignition to its cut-off.

    The program ignites the stage, then calls :meth:`update` and sleeps the seconds it
    returns until :attr:`finished`: while the engines spool up the nose follows the
    velocity; then PEG is solved every ``period`` s (:func:`~rocketsim.guidance.peg.start`,
    :func:`~rocketsim.guidance.peg.cycle`) and the nose pointed (``fc.point_at``) where the
    law will be ``LEAD`` s after the middle of each sleep. The burn is planned with its
    last ``final_speed`` m/s at the engines' lowest throttle (``fc.engines``'
    ``throttle_range``; :func:`~rocketsim.guidance.peg.burn_phases`) and the throttle drops
    there, so that a step's velocity gain, which sets how well the cut-off can be timed,
    is small; the next solution is settled on the new thrust
    (:func:`~rocketsim.guidance.peg.settle`). Below ``release`` s to go only the cut-off
    velocity is aimed at (a position error of metres, or the navigation's noise, no
    longer turns the law), below ``freeze`` s the last law is flown as it is. The engines
    are shut down in the step that brings the orbital energy, with the tail-off's impulse
    (``tail_off`` s of linear decay), nearest the target's (the module's "cut-off"). A
    stage that runs dry first ends the burn where it is (:attr:`outcome` says which). The
    wake-ups quicken as the energy nears the cut-off's
    (:class:`~rocketsim.guidance.rate.Approach`):
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
