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
   throttling back through max-Q; when the mission names a landing pad
   (``target.pad``) the first stage is cut off with RETURN_RESERVE of its
   propellant left for its return (its own program flies it back);
4. staging, then direct insertion (dropping the fairing above 110 km):
   closed-loop guidance (:class:`Insertion`) pitches the upper stage along a
   linear-tangent law re-solved every second so that the burn ends at the
   target radius with no radial speed, with a cross-track term that trims
   the inclination, until the periapsis clears the target less 5 %;
5. DEPLOY_DELAY later the payload is deployed (a body of its own).

The return of the lower stage (boost-back, entry and landing burns) is flown
by its own program (``programs:`` in the scenario, e.g. booster_return.py).
"""

import math

EARTH_OMEGA = 7.2921159e-5     # rad/s (WGS84)
EARTH_MU = 3.986004418e14      # m^3/s^2
EARTH_RADIUS = 6378137.0       # m
KICK_PER_TW = math.radians(12.66)  # kick per unit of thrust-to-weight above 1
KICK_HEIGHT = 300.0            # m above the pad
KICK_TIME = 10.0               # s held before the gravity turn
Q_LIMIT = 33e3                 # Pa: throttle back above this dynamic pressure
FAIRING_ALTITUDE = 110e3       # m: above this the air is thin enough to drop the fairing
GUIDANCE_PERIOD = 1.0          # s between insertion guidance solutions
NEWTON_PASSES = 2              # Newton passes per solution (warm-started)
PREDICTION_STEP = 2.0          # s, step of the guidance's burn prediction
DEPLOY_DELAY = 10.0            # s from insertion to payload deploy
SEPARATION_DELAY = 10.0        # s from insertion to a carried spacecraft's separation
RETURN_RESERVE = 0.18          # share of the first stage's propellant kept for its return


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
    fc.wait_until(lambda: fc.altitude > pad + KICK_HEIGHT)
    thrust_to_weight = fc.thrust / (fc.mass * fc.gravity)
    fc.point(math.pi / 2 - KICK_PER_TW * (thrust_to_weight - 1.0), azimuth)
    fc.sleep(KICK_TIME)
    fc.hold("surface_prograde")
    reserve = RETURN_RESERVE * stage_propellant(fc, first) if fc.target.pad is not None else 0.0
    while fc.thrust > 0.0 and stage_propellant(fc, first) > reserve:    # to burn-out or the reserve
        fc.throttle(max_q_throttle(fc.dynamic_pressure))
        fc.step()
    if reserve > 0.0:           # main engine cut-off by command, the reserve left
        fc.shutdown(first)
        fc.event("MECO", stage=first, propellant_left_kg=stage_propellant(fc, first))
    fc.release()
    fc.sleep(3.0)
    fc.stage()
    fc.sleep(2.0)
    fc.ignite(upper)
    fc.throttle(1.0)
    fairing_on = True
    guidance = Insertion(EARTH_RADIUS + target.altitude)
    while fc.periapsis < 0.95 * target.altitude:
        if fairing_on and fc.altitude > FAIRING_ALTITUDE:
            fairing_on = False
            try:
                fc.jettison_fairing()
            except ValueError:          # a vehicle without one
                pass
        steer(fc, guidance.pitch(fc), target.inclination)
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


def stage_propellant(fc, stage):
    """Propellant (kg) left in the tanks of ``stage``."""
    return sum(mass for name, mass in fc.propellant.items() if name.startswith(stage + "/"))


def max_q_throttle(q):
    """Full throttle, backed off linearly above Q_LIMIT (the engines clip it to
    their range): the bending load q * alpha stays inside the structure's limit."""
    return 1.0 - 2.0 * max(0.0, q - Q_LIMIT) / Q_LIMIT


class Insertion:
    """Closed-loop insertion guidance of the upper stage (step 4 of the module).

    The pitch above the local horizontal follows a linear-tangent law
    ``tan(pitch) = A + B tau`` (tau s since the last solution). Every
    GUIDANCE_PERIOD seconds ``A, B`` are solved again by Newton's method on a
    planar point-mass prediction of the rest of the burn (inverse-square
    gravity, the thrust and mass flow read now, PREDICTION_STEP midpoint steps)
    so that the burn ends, at circular speed or when the propellant runs out,
    at the target radius with no radial speed. Recomputed from the state each
    time, it absorbs what the prediction leaves out (J2, the steering's
    cross-track share, the engines' spool).
    """

    def __init__(self, radius):
        self.radius = radius            # m from the Earth's centre
        self.a, self.b = 0.5, 0.0
        self.solved_at = None

    def pitch(self, fc):
        """Pitch (rad) above the local horizontal now."""
        if self.solved_at is None or fc.time - self.solved_at >= GUIDANCE_PERIOD:
            self.solve(fc)
        tau = 0.0 if self.solved_at is None else fc.time - self.solved_at
        return math.atan(self.a + self.b * tau)

    def solve(self, fc):
        flow = sum(e["mass_flow_kg_s"] for e in fc.engines)
        if flow <= 0.0 or fc.thrust <= 0.0:
            return                      # the engine is still spooling up
        r = math.sqrt(fc.position @ fc.position)
        v = fc.velocity
        vr = float(v @ fc.position) / r
        vh = math.sqrt(max(0.0, v @ v - vr * vr))
        state = (r, vr, vh, fc.mass, fc.thrust, flow, sum(fc.propellant.values()) / flow)
        a, b = self.a, self.b
        for _ in range(NEWTON_PASSES):
            f0 = self.miss(state, a, b)
            fa = self.miss(state, a + 1e-3, b)
            fb = self.miss(state, a, b + 1e-5)
            j11, j21 = (fa[0] - f0[0]) / 1e-3, (fa[1] - f0[1]) / 1e-3
            j12, j22 = (fb[0] - f0[0]) / 1e-5, (fb[1] - f0[1]) / 1e-5
            det = j11 * j22 - j12 * j21
            if det == 0.0:
                break
            a += max(-0.5, min(0.5, (-f0[0] * j22 + f0[1] * j12) / det))
            b += max(-0.01, min(0.01, (-j11 * f0[1] + j21 * f0[0]) / det))
        self.a, self.b = max(-1.0, min(2.0, a)), b
        self.solved_at = fc.time

    def miss(self, state, a, b):
        """(radius miss in km, radial speed in units of 10 m/s) at the end of the
        predicted burn with the law ``a, b``."""
        r, vr, vh, m, thrust, flow, left = state
        t = 0.0
        while t < left and vh * vh * r < EARTH_MU:
            h = min(PREDICTION_STEP, left - t)
            k1 = _planar_rates(r, vr, vh, thrust / m, a + b * t)
            k2 = _planar_rates(r + 0.5 * h * k1[0], vr + 0.5 * h * k1[1], vh + 0.5 * h * k1[2],
                               thrust / (m - 0.5 * h * flow), a + b * (t + 0.5 * h))
            r, vr, vh, m = r + h * k2[0], vr + h * k2[1], vh + h * k2[2], m - h * flow
            t += h
        return (r - self.radius) / 1e3, vr / 10.0


def _planar_rates(r, vr, vh, acceleration, tangent):
    """(dr/dt, dvr/dt, dvh/dt) in the orbit plane (m/s, m/s^2) under thrust
    ``acceleration`` (m/s^2) at pitch ``atan(tangent)`` above the horizontal."""
    c = 1.0 / math.sqrt(1.0 + tangent * tangent)
    return (vr, acceleration * tangent * c - EARTH_MU / (r * r) + vh * vh / r,
            acceleration * c - vr * vh / r)


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
