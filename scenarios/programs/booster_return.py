"""Return of a separated first stage to the mission's landing pad (``fc.target.pad``).

Attached to the lower stage by the scenario's ``programs:`` (it starts at
separation), or flown from the pad by a hop. Reads only the navigation
estimate, so it flies with ``sensors: realistic`` as with the truth. Phases:

1. boost-back: three engines (the centre and two opposite ones of the ring,
   THREE_ENGINES; all those with an ignition left on another vehicle) burn
   with the thrust horizontal, against the miss of the predicted impact point
   (below); the autopilot flips the stage with the gimbals on the way. The burn
   ends when the predicted impact point reaches the pad (throttled back to the
   engines' minimum over the last few kilometres). It aims OVERSHOOT beyond
   the pad: the entry burn, mostly against the velocity, shortens the fall;
2. coast; the grid fins are handed to the autopilot;
3. entry burn: below ENTRY_ALTITUDE, falling faster than ENTRY_SPEED, and
   once the nose is within ENTRY_ALIGNMENT of the airflow's reverse (the
   stage has no thrusters: it keeps the boost-back's attitude through the
   vacuum and the grid fins turn it tail first only as the air thickens), the
   engines burn against the air-relative velocity until the airspeed is down
   to ENTRY_END_SPEED (or only the landing burn's propellant is left), leaned
   (as in the descent, towards the pad) so that the impact point predicted from
   the burn's end is on the pad: how far the burn shortens the fall, which
   OVERSHOOT only estimates, depends on the path the boost-back left (a wind in
   the ascent changes it by kilometres);
4. aerodynamic descent tail first on the grid fins: the nose is held on
   the air-relative velocity's reverse, leaned away from the direction the
   impact point must move (a body falling tail first is pushed away from
   the side its nose leans to), by an angle that keeps q * alpha far from
   the structure's limit;
5. landing burn on the centre engine (LANDING_ENGINES): lit when stopping at a constant deceleration needs
   LANDING_MARGIN of what the engines and the drag (``q / BALLISTIC``) give; the throttle then flies a
   descent-rate reference against the radar clearance of the feet (:func:`land`),
   the thrust leaned by a zero-effort-miss law onto the pad
   (``a = -6 (x + v t_go) / t_go^2 + 2 v / t_go`` horizontally, ``t_go`` the time
   to a gate TERMINAL_HEIGHT above the ground at the mean speed), the last TERMINAL_HEIGHT metres nearly upright,
   killing the drift and what is left of the offset; the engines are cut just above the ground. The legs are deployed at the start of the burn.

Impact prediction: the state (Earth-fixed, from the navigation estimate) is
integrated to the ground under point-mass + J2 gravity, the Coriolis and
centrifugal terms and drag on an exponential air (scale height 7.2 km) at
the stage's ballistic coefficient ``m / (C_D A)``, estimated here (BALLISTIC).
In the descent the prediction includes the landing burn (lit by the same
rule, against the velocity, stopping the stage at the ground), which keeps
the stage near its velocity's line. A guidance model, not the physics: its
errors are what the later phases correct. It is compiled
(:func:`rocketsim.flight.guidance.descent_point`): about 20 us a prediction.

Guidance rate: the boost-back predicts its miss once a second and sleeps
between predictions, waiting on compiled conditions while the stage turns
onto its aim (the nose within AIMED of it, or the next prediction's time).
The descent updates its lean every DESCENT_PERIOD (0.5 s), the entry and
landing burns their direction and throttle every GUIDANCE_STEP (0.1 s); the
autopilot holds the last command every 20 ms step. Each goes to every step
as the limit it acts at nears (:class:`~rocketsim.flight.guidance_rate.Approach`:
the boost-back's miss, the entry burn's end speed and propellant reserve, the
landing burn's altitude and rule, the cut-off's clearance), so it acts in the
step the limit is crossed.
"""

import math

import numpy as np

from rocketsim.constants import EARTH_J2, EARTH_MU, EARTH_OMEGA
from rocketsim.frames.earth_fixed import eci_to_ecef, eci_to_ecef_velocity
from rocketsim.frames.geodetic import enu_basis, geodetic_to_ecef
from rocketsim.flight.guidance import descent_point, warm_up
from rocketsim.flight.guidance_rate import Approach

BALLISTIC = 1800.0          # kg/m^2: the empty stage tail first with its grid fins (estimate)
SEA_LEVEL_DENSITY = 1.225   # kg/m^3, and scale height (m): the predictor's air
SCALE_HEIGHT = 7200.0
ENTRY_ALTITUDE = 60e3       # m
ENTRY_SPEED = 900.0         # m/s
ENTRY_END_SPEED = 650.0     # m/s
ENTRY_ALIGNMENT = math.radians(10.0)  # the entry burn lights with the nose this close to the airflow's reverse
UNUSABLE = 4200.0           # kg: propellant the engines cannot draw (1 % of the booster's load)
OVERSHOOT = 6000.0          # m: boost-back aims this far beyond the pad (the entry burn shortens the fall)
FINE_MISS = 3000.0          # m: boost-back throttled back below this miss
AIMED = math.radians(20.0)  # rad: the boost-back burns with the nose this near its aim
LANDING_ALTITUDE = 8e3     # m: the landing burn starts below this (drag brakes the stage above)
LANDING_MARGIN = 0.5        # share of the available deceleration the landing burn plans on
TOUCH_SPEED = 0.5           # m/s: descent rate the landing burn aims for at contact
CUTOFF_CLEARANCE = 0.15      # m: engines off this high (the tail-off finishes the job)
FINAL_HEIGHT = 60.0         # m of clearance: below this the landing burn slows at
FINAL_DECELERATION = 2.5    # m/s^2 (more than the least thrust gives the empty stage)
MIN_TIME_TO_GO = 8.0        # s: floor of t_go (the attitude loop, ~1 rad/s, lags the law)
SPEED_GAIN = 1.5            # 1/s: throttle feedback on the descent rate's error
TERMINAL_HEIGHT = 40.0      # m: nearly upright from here down, the drift killed and
TERMINAL_TIME = 1.5         # s: the offset closed with this time constant,
TERMINAL_LEAN = math.radians(3.0)     # leaning at most this much (touchdown must be within 5 deg)
MAX_LEAN = math.radians(15.0)
LEAN_SCALE = 300.0         # m of miss for the full lean (entry burn, descent)
THREE_ENGINES = ("centre", "ring/1", "ring/5")    # boost-back and entry burns (Falcon 9's three)
LANDING_ENGINES = ("centre",)                      # the landing burn
LANDING_DV = 450.0          # m/s kept for the landing burn (terminal speed and gravity loss)
EXHAUST_SPEED = 2800.0      # m/s, effective exhaust speed of the engines low in the air (estimate)
# Pa deg: lean commanded in the air at most; the structure's limit is 250 kPa deg, and the
# autopilot's lag through the wind's shears overshoots a command by up to ~100 kPa deg
Q_ALPHA = 100e3
ENTRY_PREDICTION_STEP = 0.2  # s, steps of the entry burn's prediction
DESCENT_PERIOD = 0.5        # s between the descent's lean updates (see the module)
GUIDANCE_STEP = 0.1         # s between the burns' steering and throttle updates

warm_up()       # the predictor's compiled kernels, loaded with the program, not inside a step


def main(fc):
    pad = fc.target.pad
    guide = Guide(fc, pad.latitude, pad.longitude)
    relight = [e["name"] for e in fc.engines if e["ignitions_left"] > 0]
    three = [name for name in relight if name.endswith(THREE_ENGINES)] or relight
    landing = [name for name in relight if name.endswith(LANDING_ENGINES)] or relight
    fc.sleep(2.0)                                       # clear of the upper stage
    boost_back(fc, guide, three)
    fc.deploy_grid_fins()
    fc.hold("surface_retrograde")
    fc.wait_until(fc.below("altitude", ENTRY_ALTITUDE) & fc.below("vertical_speed", -ENTRY_SPEED))
    while fc_nose(fc) @ fc.air_velocity > -math.cos(ENTRY_ALIGNMENT) * fc.airspeed:
        fc.sleep(GUIDANCE_STEP)     # the grid fins are still turning the stage tail first
    share = len(landing) / len(three)
    landing_full = entry_burn(fc, guide, three, share) * share
    descend(fc, guide, landing_full)
    land(fc, guide, landing, landing_full)


class Guide:
    """The pad in the Earth-fixed frame and the impact-point prediction."""

    def __init__(self, fc, latitude, longitude):
        self.fc = fc
        self.pad = geodetic_to_ecef(latitude, longitude, 0.0)
        self.enu = enu_basis(latitude, longitude)           # rows east, north, up (ECEF)
        self._recent = {}                                  # name -> (mission time s, value)

    def state(self):
        """Earth-fixed position and velocity (m, m/s) of the estimate."""
        fc = self.fc
        r, v, t = fc.position, fc.velocity, fc.time
        return eci_to_ecef(r, t), eci_to_ecef_velocity(r, v, t)

    def offset(self):
        """(east, north) of the vehicle from the pad (m) and its ground velocity (m/s)."""
        r, v = self.state()
        return (self.enu @ (r - self.pad))[:2], (self.enu @ v)[:2]

    def usable(self):
        """Propellant (kg) the engines can still burn (the gauges less the unusable part)."""
        return sum(self.fc.propellant.values()) - UNUSABLE

    def recent(self, name, age, compute):
        """``compute()``, recomputed once every ``age`` seconds (kept under ``name``)."""
        when, value = self._recent.get(name, (-math.inf, None))
        if self.fc.time - when >= age:
            when, value = self.fc.time, compute()
            self._recent[name] = (when, value)
        return value

    def recent_miss(self, age=1.0, thrust_accel=0.0):
        """The miss (as :meth:`miss`), recomputed once every ``age`` seconds."""
        return self.recent("miss", age, lambda: self.miss(thrust_accel))

    def recent_burn_end_miss(self, age, full, landing_share):
        """The miss from the entry burn's end (as :meth:`burn_end_miss`), recomputed once
        every ``age`` seconds."""
        return self.recent("burn end miss", age, lambda: self.burn_end_miss(full, landing_share))

    def burn_end_miss(self, full, landing_share):
        """(east, north) of the impact point from the pad (m) predicted from where the
        entry burn, at ``full`` thrust (N) against the velocity, ends (ENTRY_END_SPEED, or
        only the landing burn's propellant left), with the landing burn at
        ``landing_share`` of that thrust. The burn is integrated in the Earth-fixed frame
        (point-mass gravity, the Coriolis and centrifugal terms, no drag: it burns above
        50 km) in ENTRY_PREDICTION_STEP steps, its mass flow ``full / EXHAUST_SPEED``."""
        r, v = self.state()
        mass, usable = self.fc.mass, self.usable()
        w = EARTH_OMEGA
        dt = ENTRY_PREDICTION_STEP
        flow = full / EXHAUST_SPEED * dt
        while True:
            speed = math.sqrt(v @ v)
            if speed <= ENTRY_END_SPEED or usable <= landing_propellant(mass):
                break
            gravity = -EARTH_MU / (r @ r) ** 1.5 * r
            # the Coriolis and centrifugal terms, 2 w x v and w x (w x r), w along +z
            coriolis = np.array((-(w * v[1]), w * v[0], 0.0))
            centrifugal = np.array((-(w * (w * r[0])), -(w * (w * r[1])), 0.0))
            a = -full / mass / speed * v + gravity - 2.0 * coriolis - centrifugal
            v = v + a * dt
            r = r + v * dt
            mass, usable = mass - flow, usable - flow
        return (self.enu @ (impact(r, v, BALLISTIC, landing_share * full / mass) - self.pad))[:2]

    def miss(self, thrust_accel=0.0):
        """(east, north) of the predicted impact point from the pad, m (with the landing
        burn when the engines' full thrust over the mass, m/s^2, is given)."""
        r, v = self.state()
        return (self.enu @ (impact(r, v, BALLISTIC, thrust_accel) - self.pad))[:2]


def _enu_eci(fc):
    """Local east, north, up at the vehicle, ECI axes (from the estimate): ``up`` the
    radial direction, ``east = z x up`` normalised, ``north = up x east``."""
    up = fc.radial
    ux, uy, uz = up.tolist()
    size = math.sqrt(ux * ux + uy * uy)
    ex, ey = -uy / size, ux / size
    return np.array((ex, ey, 0.0)), np.array((-uz * ey, uz * ex, ux * ey - uy * ex)), up


def impact(r, v, ballistic, thrust_accel=0.0):
    """Earth-fixed point (m) where the state (r, v) (Earth-fixed, m, m/s) comes down on
    the ellipsoid, with drag on the exponential air (see the module) and, when
    ``thrust_accel`` (m/s^2, the engines' full thrust over the mass) is given, the
    landing burn as the program flies it: lit by the same rule, against the
    velocity, at the deceleration that stops the stage at the ground
    (:func:`rocketsim.flight.guidance.descent_point`, compiled)."""
    x, y, z = r.tolist()
    vx, vy, vz = v.tolist()
    return np.array(descent_point(x, y, z, vx, vy, vz, ballistic, thrust_accel, 2.0,
                                  SEA_LEVEL_DENSITY, SCALE_HEIGHT, LANDING_ALTITUDE,
                                  LANDING_MARGIN, TOUCH_SPEED, EARTH_J2))


def horizontal(fc, east, north):
    """A horizontal unit vector (ECI) from local (east, north) components."""
    e, n, _ = _enu_eci(fc)
    d = east * e + north * n
    return d / np.linalg.norm(d)


def boost_back(fc, guide, engines):
    """Burn until the predicted impact point is on the pad: at the engines' minimum
    while the gimbals flip the stage, then at full thrust, and at the minimum again
    over the last FINE_MISS metres. The miss is predicted once a second, then every
    GUIDANCE_STEP and every step as its part along the first miss nears zero; the
    burn ends where the next step would take it past (within half a step's change)."""
    miss = guide.miss()
    first = miss / np.linalg.norm(miss)
    size = float(np.linalg.norm(miss))
    fc.point_at(horizontal(fc, -miss[0], -miss[1]))
    fc.ignite(engines)
    fc.throttle(0.0)
    fc.event("boost-back start", miss_m=float(np.linalg.norm(miss)))
    remaining = Approach(0.0, periods=(1.0, GUIDANCE_STEP))     # the miss along the first one
    along, wait, checked = miss @ first, 1.0, -math.inf
    while True:
        if fc.time - checked >= wait - 1e-9:
            previous = along
            miss, checked = guide.miss() + OVERSHOOT * first, fc.time
            size = float(np.linalg.norm(miss))
            if size > FINE_MISS:                    # hold still over the last part: no spin
                wanted = horizontal(fc, -miss[0], -miss[1])     # is left when the engines stop
            along = miss @ first
            if not remaining.ahead(along, fc.time) or (wait == 0.0 and along <= 0.5 * (previous - along)):
                break                               # on the aim within half a step
            wait = remaining.next_update()
        fc.point_at(wanted)
        aligned = fc_nose(fc) @ wanted > math.cos(AIMED)
        fc.throttle(1.0 if size > FINE_MISS and aligned else 0.0)
        if aligned or wait < 1.0:                   # to the next prediction
            fc.sleep(max(checked + wait - fc.time, 0.0))
        else:                       # turning onto the aim: until it is reached, or the next prediction
            fc.wait_until(fc.below("nose_angle", AIMED, towards=wanted) | fc.above("time", checked + 0.99))
    fc.shutdown(engines)
    fc.event("boost-back end", miss_m=size)
    fc.sleep(1.0)                   # hold the attitude through the tail-off: no spin-up


def fc_nose(fc):
    """The nose direction (unit vector, ECI) from the estimated attitude."""
    w, x, y, z = fc.attitude
    return np.array([1.0 - 2.0 * (y * y + z * z), 2.0 * (x * y + w * z), 2.0 * (x * z - w * y)])


def entry_burn(fc, guide, engines, landing_share):
    """Slow down against the air, keeping what the landing burn needs, the thrust leaned
    so that the impact point predicted from the burn's end (:meth:`Guide.burn_end_miss`)
    is on the pad; returns the engines' full-throttle thrust (N) measured.
    ``landing_share``: the landing burn's engines' share of that thrust. Updated every
    GUIDANCE_STEP, every step as the airspeed or the propellant nears its end."""
    fc.ignite(engines)
    fc.throttle(1.0)
    gauge = FullThrust(0.0)
    airspeed = Approach(ENTRY_END_SPEED, periods=(GUIDANCE_STEP,))
    reserve = Approach(0.0, periods=(GUIDANCE_STEP,))
    while airspeed.ahead(fc.airspeed, fc.time) & reserve.ahead(guide.usable() - landing_propellant(fc.mass),
                                                                fc.time):
        full = gauge.read(fc)
        if full > 0.0:      # spooled up: the burn's own prediction
            lean_onto(fc, guide.recent_burn_end_miss(0.5, full, landing_share), thrusting=True)
        else:
            fc.point_at(-fc.air_velocity)
        fc.sleep(min(airspeed.next_update(), reserve.next_update()))
    fc.shutdown(engines)
    fc.event("entry burn end", airspeed_m_s=fc.airspeed, altitude_m=fc.altitude,
             usable_propellant_kg=guide.usable())
    return gauge.full


def landing_propellant(mass):
    """Propellant (kg) a landing burn of LANDING_DV needs at ``mass`` (kg)."""
    return mass * (1.0 - math.exp(-LANDING_DV / EXHAUST_SPEED))


def lean_onto(fc, miss, thrusting):
    """Point against the air-relative velocity, leaned so that the impact point moves by
    ``-miss`` (east, north; m) onto the pad: thrust leans towards the pad, a body falling
    tail first leans away."""
    back = -fc.air_velocity / max(fc.airspeed, 1e-3)
    size = float(np.linalg.norm(miss))
    if size > 1.0:
        towards = horizontal(fc, -miss[0], -miss[1])
        side = towards - (towards @ back) * back
        side /= max(np.linalg.norm(side), 1e-9)
        sign = 1.0 if thrusting else -1.0
        angle = min(MAX_LEAN, size / LEAN_SCALE * MAX_LEAN)
        fc.point_at(within_air_limit(fc, math.cos(angle) * back + sign * math.sin(angle) * side))
    else:
        fc.point_at(back)


def within_air_limit(fc, direction):
    """``direction`` (unit, ECI), turned towards the air-relative velocity's reverse as far
    as needed to keep q * alpha (alpha from the tail) within Q_ALPHA."""
    speed = fc.airspeed
    if speed < 1.0:
        return direction
    back = -fc.air_velocity / speed
    limit = math.radians(Q_ALPHA / max(fc.dynamic_pressure, 1.0))
    angle = math.acos(max(-1.0, min(1.0, float(direction @ back))))
    if angle <= limit:
        return direction
    side = direction - (direction @ back) * back
    side /= np.linalg.norm(side)
    return math.cos(limit) * back + math.sin(limit) * side


def descend(fc, guide, full):
    """Fall tail first on the grid fins until the landing burn must start: below
    LANDING_ALTITUDE, once stopping needs LANDING_MARGIN of the deceleration available.
    Updated every DESCENT_PERIOD, every GUIDANCE_STEP and then every step as either nears."""
    floor = Approach(LANDING_ALTITUDE, periods=(DESCENT_PERIOD, GUIDANCE_STEP))
    rule = Approach(0.0, rising=True, periods=(DESCENT_PERIOD, GUIDANCE_STEP))
    while True:
        lean_onto(fc, guide.recent_miss(DESCENT_PERIOD, full / fc.mass), thrusting=False)
        fall = -fc.vertical_speed
        h = fc.clearance
        available = full / fc.mass - fc.gravity + fc.dynamic_pressure / BALLISTIC   # thrust, drag
        need = fall * fall / (2.0 * h) if fall > 0 and h > 0 else 0.0
        high = floor.ahead(fc.altitude, fc.time)
        short = rule.ahead(need - LANDING_MARGIN * available, fc.time)
        if not high and not short:
            return
        # the burn lights at the later of the two crossings: look every step as either nears
        fc.sleep(min(floor.next_update() if high else math.inf, rule.next_update() if short else math.inf))


def land(fc, guide, engines, full):
    """The landing burn, down to the engines' cut-off just above the ground, updated every
    GUIDANCE_STEP and every step as the cut-off's clearance nears.

    The descent rate follows a reference: the constant deceleration planned at
    ignition down to FINAL_HEIGHT, then a gentler FINAL_DECELERATION (more than the
    engine's least thrust gives, so the stage never stops above the ground) to
    ``v_touch`` at the ground; the throttle gives the reference's deceleration plus
    SPEED_GAIN times the speed error."""
    fc.deploy_legs()
    fc.ignite(engines)
    fc.event("landing burn start", altitude_m=fc.altitude, airspeed_m_s=fc.airspeed)
    h, fall = fc.clearance, -fc.vertical_speed
    final_speed = math.sqrt(TOUCH_SPEED ** 2 + 2.0 * FINAL_DECELERATION * FINAL_HEIGHT)
    plan = max((fall * fall - final_speed ** 2) / (2.0 * max(h - FINAL_HEIGHT, 1.0)), 1.0)
    gate_speed = math.sqrt(TOUCH_SPEED ** 2 + 2.0 * FINAL_DECELERATION * TERMINAL_HEIGHT)
    gauge = FullThrust(full)
    cutoff = Approach(CUTOFF_CLEARANCE, periods=(GUIDANCE_STEP,))
    while True:
        h = fc.clearance
        fall = -fc.vertical_speed
        if not cutoff.ahead(h, fc.time) or (fall < 0.0 and h < 3.0):
            break
        if h > FINAL_HEIGHT:
            reference = math.sqrt(final_speed ** 2 + 2.0 * plan * (h - FINAL_HEIGHT))
            slowing = plan
        else:
            reference = math.sqrt(TOUCH_SPEED ** 2 + 2.0 * FINAL_DECELERATION * max(h, 0.0))
            slowing = FINAL_DECELERATION
        up_acc = max(fc.effective_gravity + slowing + SPEED_GAIN * (fall - reference), 0.5)
        offset, ground = guide.offset()
        if h > TERMINAL_HEIGHT:     # zero-effort miss onto the gate TERMINAL_HEIGHT above the pad
            t_go = max(2.0 * (h - TERMINAL_HEIGHT) / (fall + gate_speed), MIN_TIME_TO_GO)
            side = -6.0 * (offset + ground * t_go) / t_go ** 2 + 2.0 * ground / t_go
            lean = MAX_LEAN
        else:                       # nearly upright: the drift, and what is left of the offset
            side = -2.0 * ground / TERMINAL_TIME - offset / TERMINAL_TIME ** 2     # critically damped
            lean = TERMINAL_LEAN
        side_size = float(np.linalg.norm(side))
        cap = up_acc * math.tan(lean)
        if side_size > cap:
            side *= cap / side_size
        e, n, u = _enu_eci(fc)
        wanted = side[0] * e + side[1] * n + up_acc * u
        total = float(np.linalg.norm(wanted))
        fc.point_at(within_air_limit(fc, wanted / total))
        fc.throttle(fc.mass * total / gauge.full)
        gauge.read(fc)
        fc.sleep(cutoff.next_update())
    fc.shutdown(engines)
    fc.release()
    fc.event("landing burn end", clearance_m=fc.clearance, vertical_speed_m_s=fc.vertical_speed)


class FullThrust:
    """Full-throttle thrust (N) of the firing engines: ``full`` until they have spooled
    up, then measured (thrust over throttle), again every GUIDANCE_STEP (it changes
    only with the air's pressure: reading every engine's state every step costs more)."""

    def __init__(self, full):
        self.full = full
        self.measured_at = -math.inf

    def read(self, fc):
        """Measure now if due; returns :attr:`full`."""
        if fc.time - self.measured_at < GUIDANCE_STEP - 1e-9:
            return self.full
        firing = [e for e in fc.engines if e["thrust_N"] > 0.0]
        if firing and all(e["spool"] >= 1.0 for e in firing):
            self.full = sum(e["thrust_N"] / e["throttle"] for e in firing)
            self.measured_at = fc.time
        return self.full
