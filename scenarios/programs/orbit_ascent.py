"""Ascent of a two-stage launcher to the mission's target orbit (lower stage expended).

Reads the target (altitude, inclination) from the mission file, so the same
program flies any two-stage vehicle from any site:

1. vertical rise on the first stage's engines;
2. a pitch kick towards the launch azimuth that reaches the target
   inclination (computed from the site's latitude, corrected for the ground's
   eastward speed; the branch, north- or south-going, is the one nearest the
   site's pad azimuth);
3. a gravity turn (holding surface prograde) to first-stage burn-out,
   throttling back through max-Q;
4. staging, then direct insertion (dropping the fairing above 110 km): the upper stage pitches so that a
   critically damped loop drives altitude to the target and vertical speed
   to zero while the rest of its thrust builds horizontal speed, with a
   cross-track term that trims the inclination, until the periapsis clears
   the target less 5 %.

The return of the lower stage (boost-back, entry and landing burns) is not
flown here.
"""

import math

EARTH_OMEGA = 7.2921159e-5     # rad/s (WGS84)
EARTH_MU = 3.986004418e14      # m^3/s^2
EARTH_RADIUS = 6378137.0       # m
KICK = math.radians(84.0)      # pitch after the kick
KICK_HEIGHT = 300.0            # m above the pad
KICK_TIME = 10.0               # s held before the gravity turn
Q_LIMIT = 33e3                 # Pa: throttle back above this dynamic pressure
FAIRING_ALTITUDE = 110e3       # m: above this the air is thin enough to drop the fairing


def main(fc):
    target = fc.target.orbit
    azimuth = launch_azimuth(fc.latitude, target.inclination, target.altitude, fc.pad_azimuth)
    hold_altitude = target.altitude + 10e3     # geodetic height reads ~10 km above the
    #                                            periapsis (equatorial radius) at mid latitudes
    first, upper = fc.stages[0], fc.stages[1]
    fc.ignite(first)
    fc.throttle(1.0)
    fc.point(math.pi / 2, azimuth)
    pad = fc.altitude
    fc.wait_until(lambda: fc.altitude > pad + KICK_HEIGHT)
    fc.point(KICK, azimuth)
    fc.sleep(KICK_TIME)
    fc.hold("surface_prograde")
    while fc.thrust > 0.0:                             # to first-stage burn-out
        fc.throttle(max_q_throttle(fc.dynamic_pressure))
        fc.step()
    fc.release()
    fc.sleep(3.0)
    fc.stage()
    fc.sleep(2.0)
    fc.ignite(upper)
    fc.throttle(1.0)
    fairing_on = True
    while fc.periapsis < 0.95 * target.altitude:
        if fairing_on and fc.altitude > FAIRING_ALTITUDE:
            fairing_on = False
            try:
                fc.jettison_fairing()
            except ValueError:          # a vehicle without one
                pass
        steer(fc, insertion_pitch(fc, hold_altitude), target.inclination)
        fc.step()
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


def max_q_throttle(q):
    """Full throttle, backed off linearly above Q_LIMIT (the engines clip it to
    their range): the bending load q * alpha stays inside the structure's limit."""
    return 1.0 - 2.0 * max(0.0, q - Q_LIMIT) / Q_LIMIT


def insertion_pitch(fc, altitude):
    """Pitch above the horizon for the vertical loop (see the module)."""
    wanted = -0.04 * fc.vertical_speed - 4e-4 * (fc.altitude - altitude)
    thrust_acceleration = fc.thrust / fc.mass
    if thrust_acceleration <= 0:
        return 0.0
    s = (wanted + fc.effective_gravity) / thrust_acceleration
    return math.asin(max(-0.5, min(0.9, s)))


def steer(fc, pitch, inclination):
    """Point ``pitch`` above the local horizontal in the direction of motion, with a
    cross-track term along the orbit normal that trims the inclination."""
    v = fc.velocity
    up = fc.radial
    horizontal = v - (v @ up) * up
    horizontal /= math.sqrt(horizontal @ horizontal)
    # thrust along the orbit normal turns the inclination by cos(u) of it (u the
    # argument of latitude: the Gauss equation di/dt = r cos(u) a_n / h)
    error = (fc.inclination - inclination) * math.cos(fc.orbit.arglat)
    cross = -max(-0.3, min(0.3, 8.0 * error)) * fc.normal
    fc.point_at(math.cos(pitch) * horizontal + math.sin(pitch) * up + cross)
