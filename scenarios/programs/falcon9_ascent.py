"""Falcon 9-class ascent from SLC-40 to a ~200 km x 51.6 deg orbit (booster expended).

Vertical rise, a pitch kick to 84 deg towards the launch azimuth, a gravity
turn (holding surface prograde) to booster burn-out, staging, then direct
insertion: the second stage pitches so that a critically damped loop drives
altitude to ORBIT and vertical speed to zero while the rest of its thrust
builds horizontal speed, with a cross-track term that trims the inclination.
Booster return (boost-back, entry and landing burns) is not flown yet.
"""

import math

TARGET_INCLINATION = math.radians(51.6)
AZIMUTH = math.radians(42.8)      # launch azimuth towards 51.6 deg, rotating-Earth corrected
ORBIT = 212e3      # m above the ellipsoid: the periapsis (above the equatorial radius) is ~10 km less at 50 deg latitude


def main(fc):
    fc.ignite("booster")
    fc.throttle(1.0)
    fc.point(math.radians(90.0), AZIMUTH)
    fc.wait_until(lambda: fc.altitude > 300.0)
    fc.point(math.radians(84.0), AZIMUTH)              # pitch kick
    fc.sleep(10.0)
    fc.hold("surface_prograde")                        # gravity turn
    fc.wait_until(lambda: fc.thrust == 0.0)                 # MECO: the booster runs dry
    fc.shutdown("booster")
    fc.release()
    fc.sleep(3.0)
    fc.stage()
    fc.sleep(2.0)
    fc.ignite()
    fc.throttle(1.0)
    while fc.periapsis < 195e3:
        steer(fc, insertion_pitch(fc))
        fc.step()
    fc.shutdown()
    fc.release()
    fc.log("SECO", fc.apoapsis, fc.periapsis, math.degrees(fc.inclination))


def insertion_pitch(fc):
    """Pitch above the horizon that drives altitude to ORBIT and vertical speed to
    zero (a critically damped vertical loop) while the rest of the thrust
    builds horizontal speed: direct insertion into a circular orbit."""
    wanted = -0.04 * fc.vertical_speed - 4e-4 * (fc.altitude - ORBIT)
    thrust_acceleration = fc.thrust / fc.mass
    if thrust_acceleration <= 0:
        return 0.0
    s = (wanted + fc.effective_gravity) / thrust_acceleration
    return math.asin(max(-0.5, min(0.9, s)))


def steer(fc, pitch):
    """Point ``pitch`` above the local horizontal, in the direction of motion,
    with a cross-track term that steers the orbit plane to the target inclination."""
    v = fc.velocity
    up = fc.radial
    horizontal = v - (v @ up) * up
    horizontal /= math.sqrt(horizontal @ horizontal)
    error = fc.inclination - TARGET_INCLINATION
    # the normal points north-ish for a prograde orbit: thrust along it raises i
    cross = -max(-0.3, min(0.3, 8.0 * error)) * fc.normal
    direction = math.cos(pitch) * horizontal + math.sin(pitch) * up + cross
    fc.point_at(direction)
