"""Ascent of a two-stage launcher to the mission's target orbit (lower stage expended).

Reads the target (altitude, inclination) from the mission file, so the same
program flies any two-stage vehicle from any site:

1. vertical rise on the first stage's engines;
2. a pitch kick towards the launch azimuth that reaches the target
   inclination (computed from the site's latitude, corrected for the ground's
   eastward speed; the branch, north- or south-going, is the one nearest the
   site's pad azimuth). The kick is KICK_PER_TW per unit of thrust-to-weight
   above 1 at the kick: 6 deg for a Falcon 9 at 1.47, about 10.8 deg for an
   Electron at about 1.85, whose sprightlier climb would otherwise stay too
   steep (an empirical rule tuned on the two);
3. a gravity turn (holding surface prograde) to first-stage burn-out,
   throttling back linearly through max-Q above Q_LIMIT (``fc.limit_q``: the
   bending load q * alpha stays inside the structure's limit; the engines clip
   the throttle to their range); when the mission names a landing pad
   (``target.pad``) the first stage is cut off with RETURN_RESERVE of its
   propellant left for its return (its own program flies it back);
4. staging, then direct insertion (dropping the fairing above 110 km):
   closed-loop guidance (:class:`Insertion`) pitches the upper stage along a
   linear-tangent law re-solved every second so that the burn ends at the
   target radius with no radial speed, with a cross-track term that trims
   the inclination, until the periapsis clears the target less 5 %;
5. DEPLOY_DELAY later the payload is deployed (a body of its own).

Guidance rate: the first stage's climb needs no program at all: the autopilot
holds surface prograde, the engines' throttle law backs off through max-Q at
every step and the program waits on its stage's propellant (compiled
conditions: ``fc.below("propellant", ...)``), so it wakes in the step the
reserve is reached. The upper stage's
program, like a real flight computer's guidance, solves its steering law every
GUIDANCE_PERIOD (1 s) and sleeps in between, while the autopilot follows the
law every 20 ms step (``fc.steer_linear_tangent``); it wakes more often as the
cut-off nears (:class:`~rocketsim.guidance.rate.Approach`: the insertion's
periapsis), every step at the end, so the engine is cut in the step the limit is
crossed. A program that wants the per-step loop calls ``fc.step()`` instead.

The return of the lower stage (boost-back, entry and landing burns) is flown
by its own program (``programs:`` in the scenario, e.g. booster_return.py).
"""

import math

from rocketsim.constants import EARTH_MU, EARTH_OMEGA, EARTH_RADIUS_EQ as EARTH_RADIUS
from rocketsim.flight.guidance import solve_linear_tangent, warm_up
from rocketsim.guidance.rate import Approach

KICK_PER_TW = math.radians(12.66)  # kick per unit of thrust-to-weight above 1
KICK_HEIGHT = 300.0            # m above the pad
KICK_TIME = 10.0               # s held before the gravity turn
Q_LIMIT = 33e3                 # Pa: throttle back above this dynamic pressure (zero at 1.5 times it)
BURN_OUT_WATCH = 0.02          # share of the first stage's load left when burn-out is watched every step
FAIRING_ALTITUDE = 110e3       # m: above this the air is thin enough to drop the fairing
GUIDANCE_PERIOD = 1.0          # s between insertion guidance solutions
GUIDANCE_STEP = 0.1            # s between guidance updates nearing a cut-off
NEWTON_PASSES = 2              # Newton passes per solution (warm-started)
PREDICTION_STEP = 2.0          # s, step of the guidance's burn prediction
DEPLOY_DELAY = 10.0            # s from insertion to payload deploy
SEPARATION_DELAY = 10.0        # s from insertion to a carried spacecraft's separation
RETURN_RESERVE = 0.18          # share of the first stage's propellant kept for its return

warm_up()       # the guidance's compiled kernels, loaded with the program, not inside a step


def main(fc):
    ascend(fc)
    fc.sleep(DEPLOY_DELAY)
    try:
        fc.log("deployed", fc.deploy_payload())
    except ValueError:                  # a vehicle without a payload
        pass


def carry_to_orbit(fc):
    """A launcher carrying a spacecraft stacked on top (``spacecraft:`` in the
    scenario): :func:`ascend`, then SEPARATION_DELAY later its upper stage
    separates and the program flies on with the spacecraft. Returns the spent
    stage's body name."""
    ascend(fc)
    fc.sleep(SEPARATION_DELAY)
    return fc.stage()


def ascend(fc):
    """Steps 1-4 of the module: from the pad to engine cut-off in the target orbit,
    the engines off and the attitude released (the upper stage still attached)."""
    target = fc.target.orbit
    azimuth = launch_azimuth(fc.latitude, target.inclination, target.altitude, fc.pad_azimuth)
    first, upper = fc.stages[0], fc.stages[1]
    fc.ignite(first)
    fc.throttle(1.0)
    fc.point(math.pi / 2, azimuth)
    pad = fc.altitude
    fc.wait_until(fc.above("altitude", pad + KICK_HEIGHT))
    thrust_to_weight = fc.thrust / (fc.mass * fc.gravity)
    fc.point(math.pi / 2 - KICK_PER_TW * (thrust_to_weight - 1.0), azimuth)
    fc.sleep(KICK_TIME)
    fc.hold("surface_prograde")
    fc.limit_q(Q_LIMIT, 1.5 * Q_LIMIT)      # every step, in compiled code: no wake-ups
    load = stage_propellant(fc, first)
    if fc.target.pad is not None:   # main engine cut-off by command, the reserve left
        fc.wait_until(fc.below("propellant", RETURN_RESERVE * load, stage=first))
        fc.limit_q(None)
        fc.shutdown(first)
        fc.event("MECO", stage=first, propellant_left_kg=stage_propellant(fc, first))
    else:                           # to burn-out
        fc.wait_until(fc.below("propellant", BURN_OUT_WATCH * load, stage=first))
        fc.wait_until(lambda: fc.thrust <= 0.0)
        fc.limit_q(None)
    fc.release()
    fc.sleep(3.0)
    fc.stage()
    fc.sleep(2.0)
    fc.ignite(upper)
    fc.throttle(1.0)
    fairing_on = True
    guidance = Insertion(EARTH_RADIUS + target.altitude, target.inclination)
    periapsis = Approach(0.95 * target.altitude, rising=True, periods=(GUIDANCE_PERIOD, GUIDANCE_STEP))
    while periapsis.ahead(fc.periapsis, fc.time):
        if fairing_on and fc.altitude > FAIRING_ALTITUDE:
            fairing_on = False
            try:
                fc.jettison_fairing()
            except ValueError:          # a vehicle without one
                pass
        fc.sleep(min(guidance.steer(fc), periapsis.next_update()))
    fc.shutdown()
    fc.release()
    fc.log(f"insertion: {fc.periapsis / 1e3:.1f} x {fc.apoapsis / 1e3:.1f} km, "
           f"{math.degrees(fc.inclination):.3f} deg")


def launch_azimuth(latitude, inclination, altitude, pad_azimuth):
    """Azimuth (rad from north) that puts a launch from ``latitude`` into an orbit of
    ``inclination``: the inertial azimuth ``sin(b) = cos(i) / cos(lat)``, corrected
    for the ground's eastward speed ``omega R cos(lat)`` against the orbital speed."""
    ratio = max(-1.0, min(1.0, math.cos(inclination) / math.cos(latitude)))
    speed = math.sqrt(EARTH_MU / (EARTH_RADIUS + altitude))
    ground = EARTH_OMEGA * EARTH_RADIUS * math.cos(latitude)
    candidates = []
    for inertial in (math.asin(ratio), math.pi - math.asin(ratio)):
        candidates.append(math.atan2(speed * math.sin(inertial) - ground, speed * math.cos(inertial)))
    return min(candidates, key=lambda a: abs(math.remainder(a - pad_azimuth, 2 * math.pi)))


def stage_propellant(fc, stage):
    """Propellant (kg) left in the tanks of ``stage``."""
    return sum(mass for name, mass in fc.propellant.items() if name.startswith(stage + "/"))


class Insertion:
    """Closed-loop insertion guidance of the upper stage (step 4 of the module).

    The pitch above the local horizontal follows a linear-tangent law
    ``tan(pitch) = A + B tau`` (tau s since the last solution), which the
    autopilot follows at every step (``fc.steer_linear_tangent``). Every
    GUIDANCE_PERIOD seconds ``A, B`` are solved again by Newton's method on a
    planar point-mass prediction of the rest of the burn (inverse-square
    gravity, the thrust and mass flow read now, PREDICTION_STEP midpoint steps;
    compiled: :func:`rocketsim.flight.guidance.solve_linear_tangent`)
    so that the burn ends, at circular speed or when the propellant runs out,
    at the target radius with no radial speed. Recomputed from the state each
    time, it absorbs what the prediction leaves out (J2, the steering's
    cross-track share, the engines' spool). The cross-track share, along the
    orbit normal, trims the inclination: thrust along the normal turns it by
    cos(u) of it (u the argument of latitude: the Gauss equation
    di/dt = r cos(u) a_n / h).
    """

    def __init__(self, radius, inclination):
        self.radius = radius            # m from the Earth's centre
        self.inclination = inclination  # rad
        self.a, self.b = 0.5, 0.0
        self.solved_at = None

    def steer(self, fc):
        """Solve again and hand the law to the autopilot when GUIDANCE_PERIOD has passed
        since the last solution (while none has been found, every GUIDANCE_STEP);
        returns the seconds to the next solution."""
        if self.solved_at is not None and fc.time - self.solved_at < GUIDANCE_PERIOD - 1e-6:
            return self.solved_at + GUIDANCE_PERIOD - fc.time
        self.solve(fc)
        error = (fc.inclination - self.inclination) * math.cos(fc.orbit.arglat)
        fc.steer_linear_tangent(self.a, self.b, -max(-0.3, min(0.3, 8.0 * error)))
        return GUIDANCE_STEP if self.solved_at is None else GUIDANCE_PERIOD

    def solve(self, fc):
        flow = sum(e["mass_flow_kg_s"] for e in fc.engines)
        thrust = fc.thrust
        if flow <= 0.0 or thrust <= 0.0:
            return                      # the engine is still spooling up
        r = math.sqrt(fc.position @ fc.position)
        v = fc.velocity
        vr = float(v @ fc.position) / r
        vh = math.sqrt(max(0.0, v @ v - vr * vr))
        self.a, self.b = solve_linear_tangent(r, vr, vh, fc.mass, thrust, flow,
                                              sum(fc.propellant.values()) / flow, self.radius,
                                              self.a, self.b, EARTH_MU, PREDICTION_STEP, NEWTON_PASSES)
        self.solved_at = fc.time

