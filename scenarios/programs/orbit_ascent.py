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
3. a gravity turn (:func:`gravity_turn`: the nose between the velocity over
   the ground and through the air, so that a wind does not bend the climb) to
   first-stage burn-out, throttling back linearly through max-Q above Q_LIMIT
   (``fc.limit_q``: the bending load q * alpha stays inside the structure's
   limit; the engines clip the throttle to their range); when the mission names a landing pad
   (``target.pad``) the first stage is cut off with RETURN_RESERVE of its
   propellant left for its return (its own program flies it back);
4. staging, then direct insertion (dropping the fairing above 110 km):
   Powered Explicit Guidance (:class:`rocketsim.guidance.ascent.Insertion`)
   steers the upper stage along a linear-tangent law solved again every
   second from the navigation state, and cuts the engine off in the step that
   puts it on the target orbit (in the plane of the target inclination through
   the vehicle at ignition); once the engine's tail-off is over the orbit
   reached is logged in the target's own elements (``Orbit.reached``: mean
   elements for a mission's default target, whose osculating apsides J2 splits
   by kilometres);
5. DEPLOY_DELAY later the payload is deployed (a body of its own).

Guidance rate: the first stage's climb needs little of the program: it aims
the nose every half second in the air (then the autopilot holds surface
prograde), the engines' throttle law backs off through max-Q at every step and
the program waits on its stage's propellant (compiled conditions:
``fc.below("propellant", ...)``), so it wakes in the step the reserve is
reached. The upper stage's guidance, like a real flight
computer's, solves its law every second and sleeps in between, waking more
often as the cut-off nears, every step at the end.

The return of the lower stage (boost-back, entry and landing burns) is flown
by its own program (``programs:`` in the scenario, e.g. booster_return.py).
"""

import math

from rocketsim.guidance.ascent import Insertion, launch_azimuth, mission_orbit

KICK_PER_TW = math.radians(12.66)  # kick per unit of thrust-to-weight above 1
KICK_HEIGHT = 300.0            # m above the pad
KICK_TIME = 10.0               # s held before the gravity turn
Q_LIMIT = 33e3                 # Pa: throttle back above this dynamic pressure (zero at 1.5 times it)
BURN_OUT_WATCH = 0.02          # share of the first stage's load left when burn-out is watched every step
FAIRING_ALTITUDE = 110e3       # m: above this the air is thin enough to drop the fairing
DEPLOY_DELAY = 10.0            # s from insertion to payload deploy
SEPARATION_DELAY = 10.0        # s from insertion to a carried spacecraft's separation
RETURN_RESERVE = 0.18          # share of the first stage's propellant kept for its return
TURN_CYCLE = 0.5               # s between the gravity turn's aims
WIND_SHARE = 0.5               # the turn's nose this share of the way from the ground's velocity to the air's
AIR_TOP = 40e3                 # m: the turn follows the air below this, the ground above


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
    the engines off, their tail-off over and the attitude released (the upper stage
    still attached)."""
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
    fc.limit_q(Q_LIMIT, 1.5 * Q_LIMIT)      # every step, in compiled code: no wake-ups
    load = stage_propellant(fc, first)
    if fc.target.pad is not None:   # main engine cut-off by command, the reserve left
        gravity_turn(fc, fc.below("propellant", RETURN_RESERVE * load, stage=first))
        fc.limit_q(None)
        fc.shutdown(first)
        fc.event("MECO", stage=first, propellant_left_kg=stage_propellant(fc, first))
    else:                           # to burn-out
        gravity_turn(fc, fc.below("propellant", BURN_OUT_WATCH * load, stage=first))
        fc.wait_until(lambda: fc.thrust <= 0.0)
        fc.limit_q(None)
    fc.release()
    fc.sleep(3.0)
    fc.stage()
    fc.sleep(2.0)
    fc.ignite(upper)
    fc.throttle(1.0)
    orbit = mission_orbit(target)
    guidance = Insertion(orbit)
    fairing_on = True
    while not guidance.finished:
        if fairing_on and fc.altitude > FAIRING_ALTITUDE:
            fairing_on = False
            try:
                fc.jettison_fairing()
            except ValueError:          # a vehicle without one
                pass
        fc.sleep(guidance.update(fc))
    fc.sleep(guidance.tail_off)         # the engine's thrust has died out
    periapsis, apoapsis, inclination = orbit.reached(fc.position, fc.velocity)
    fc.log(f"insertion ({guidance.outcome}): {(periapsis - orbit.radius) / 1e3:.1f} x "
           f"{(apoapsis - orbit.radius) / 1e3:.1f} km, {math.degrees(inclination):.3f} deg "
           f"({'mean' if orbit.mean else 'osculating'} elements)")


def gravity_turn(fc, until):
    """The gravity turn until the condition ``until`` holds: the nose WIND_SHARE of the way
    from the velocity over the ground towards the velocity through the air, re-aimed every
    TURN_CYCLE; above AIR_TOP, where the air no longer pushes, on the velocity over the
    ground (``fc.hold("surface_prograde")``, in compiled code). The two differ in a wind:
    a nose held on the velocity over the ground flies at an angle of attack, and the air's
    push across the climb (the lift, the drag along the airflow) bends it, flatter in a
    wind blowing along it; a nose on the velocity through the air tilts the thrust instead,
    which bends it the other way, more. On the shipped Falcon 9's windy days (jets of
    10-60 m/s) the first made the booster's boost-back cost up to 500 m/s more than in
    still air and the second up to 350 m/s less: WIND_SHARE sits between them."""
    while fc.altitude < AIR_TOP:
        ground, air = fc.surface_prograde, fc.air_velocity
        if fc.airspeed > 0.0:
            ground = ground + WIND_SHARE * (air / fc.airspeed - ground)
        fc.point_at(ground)
        fc.wait_until(until | fc.above("time", fc.time + TURN_CYCLE))
        if until():
            return
    fc.hold("surface_prograde")
    fc.wait_until(until)


def stage_propellant(fc, stage):
    """Propellant (kg) left in the tanks of ``stage``."""
    return sum(mass for name, mass in fc.propellant.items() if name.startswith(stage + "/"))
