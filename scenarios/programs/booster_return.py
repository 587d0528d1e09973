"""Return of a separated first stage to the mission's landing pad (``fc.target.pad``), on rocketsim.guidance.

Attached to the lower stage by the scenario's ``programs:`` (it starts at
separation). It reads only the navigation estimate and the day's forecast
(``fc.forecast``), so it flies with ``sensors: realistic`` as with the truth.
docs/guidance.md explains each algorithm; the phases:

1. **boost-back** (three engines): burn along the velocity to gain that puts
   the predicted landing point (through the day's air and wind, with the entry
   and landing burns as planned) AIM_OFF short of the pad
   (:func:`rocketsim.guidance.boostback.velocity_to_gain`);
2. **coast**, the grid fins handed to the autopilot, tail first into the air;
3. **entry burn** (three engines) below ENTRY_ALTITUDE down to an airspeed of
   ENTRY_SPEED, or higher when the propellant predicted at touchdown would be short
   of LANDING_MARGIN (:func:`rocketsim.guidance.descent.entry_end_speed`: one end
   condition, which the predictions share), leaned so that the predicted landing
   point is on the pad (:func:`rocketsim.guidance.descent.solve_lean`);
4. **aerodynamic descent** on the grid fins: the lean of a body falling tail
   first that flies the predicted point onto the pad, within the bending load
   Q_ALPHA; the body's drag learnt on the way (:class:`~rocketsim.guidance.drag.DragArea`);
5. **landing burn** (the centre engine), lit from the throttle margin
   (LANDING.plan), guided to the pad (:mod:`rocketsim.guidance.powered_descent`),
   cut just above the ground.

Each phase records an event with its figures; a return that cannot succeed
(too little propellant left) says so in its events and flies on.
"""

import math

import numpy as np

from rocketsim.constants import EARTH_MU, G0
from rocketsim.guidance import boostback, descent, powered_descent
from rocketsim.guidance.drag import DragArea
from rocketsim.guidance.landing_point import LandingPoint, entry_burn, landing_burn
from rocketsim.guidance.pad import Pad
from rocketsim.guidance.rate import Approach

# the booster (vehicles/falcon9-block5.yaml) falling tail first with its grid fins out,
# measured in a flight of the shipped vehicle (docs/guidance.md): Mach, the drag area C_D A
# (m^2), the lift-to-drag ratio per radian of angle of attack
AERO = ((0.0, 15.0, 1.5), (0.6, 15.0, 1.5), (0.8, 16.7, 1.5), (0.9, 20.0, 1.0), (1.0, 23.2, 0.8),
        (1.1, 23.9, 0.7), (1.3, 22.4, 0.75), (2.0, 21.6, 0.85), (3.0, 20.7, 1.2), (5.0, 20.7, 1.2))
EXIT_AREA = 0.680           # m^2: a Merlin 1D's nozzle exit (its thrust falls by p_a A_e in the air)
UNUSABLE = 4109.0           # kg: what the engines cannot draw (1 % of the load)
THREE_ENGINES = ("centre", "ring/1", "ring/5")   # boost-back and entry burns
LANDING_ENGINE = "centre"

# the plan
AIM_OFF = 0.0               # m: the boost-back aims this far short of the pad (sea side)
DIPS = tuple(math.radians(d) for d in (0.0, 3.0, 6.0, 9.0, 12.0))   # the boost-back's dips tried
ENTRY_ALTITUDE = 60e3       # m: the entry burn starts here, falling (as planned and predicted),
ENTRY_WINDOW = 3e3          # m: or up to this much higher, as the air swings the nose through
ENTRY_SPEED = 650.0         # m/s of airspeed at the entry burn's end, at least
FASTEST_ENTRY = 2000.0      # m/s: the boost-back's bracket of the entry burn's end speed
ENTRY_ALIGNMENT = math.radians(10.0)   # the nose this near the airflow's reverse before lighting it,
ENTRY_LOWEST = 40e3         # m: or lit anyway this low
CAPTURED = math.radians(3.0)   # rad/s: the entry burn goes to full thrust and leans once the engines
                                # have stopped the swing within ENTRY_ALIGNMENT,
CAPTURE_TIME = 4.0          # s: or this long after their ignition
LANDING_MARGIN = 800.0      # kg of usable propellant predicted at touchdown, at least
MAX_ENTRY_LEAN = 0.35       # horizontal share of the entry burn's thrust at most (19 deg),
HOLD = 0.5                  # s: held, not solved again, over the burn's last this long
Q_ALPHA = math.radians(60e3)           # Pa rad: the bending load commanded at most (the limit is 250 kPa deg)
MAX_ALPHA = math.radians(5.0)    # and the angle of attack commanded at most,
TRIM_TIME = 2.0             # s: the lean's integral trim (the autopilot holds only part of a lean)
TRIM_LIMIT = math.radians(8.0)
LANDING = powered_descent.Plan(plan=0.8, touch_speed=1.0, ceiling=8e3)
LEAD = 0.3 + 0.75           # s: the engine's dead time and half its spool-up
TAIL_OFF = 0.25             # s: an engine's thrust falls to nothing this long after its shutdown
AIMED = math.radians(20.0)  # the boost-back burns at full thrust with the nose this near its aim
FINE_GAIN = 30.0            # m/s: the boost-back ends at its engines' least throttle below this,
STEADY = 1.5                # s: and holds its attitude over its last this long
CYCLE = 0.5                 # s between guidance updates in the air
BURN_CYCLE = 0.1            # s between the burns' updates
FLIP_CYCLE = 1.0            # s between the boost-back's plans while the stage flips to it (its
                            # ignition still checked every BURN_CYCLE)


def main(fc):
    pad = Pad.target_of(fc)
    names = [e["name"] for e in fc.engines if e["ignitions_left"] > 0]
    three = [n for n in names if n.endswith(THREE_ENGINES)] or names
    centre = [n for n in names if n.endswith(LANDING_ENGINE)] or names[:1]
    dry = fc.mass - sum(fc.propellant.values())
    return_ = Return(fc, pad, dry)
    fc.sleep(2.0)                                           # clear of the upper stage
    return_.boost_back(centre, three)
    fc.deploy_grid_fins()
    fc.hold("surface_retrograde")
    fc.wait_until(fc.below("altitude", ENTRY_ALTITUDE + ENTRY_WINDOW) & fc.below("vertical_speed", 0.0))
    return_.await_entry()
    return_.entry(three)
    return_.descend()
    return_.land(centre)


class Return:
    """The return's guidance state: the pad, the predictor, the engines' measured figures."""

    def __init__(self, fc, pad, dry):
        self.fc, self.pad, self.dry = fc, pad, dry
        mach, area, slope = np.array(AERO).T
        self.predict = LandingPoint(fc.forecast, mach, area, slope, Q_ALPHA, MAX_ALPHA)
        self.drag = DragArea(mach, area)
        self.ground_pressure = float(fc.forecast.at(0.0)[1][0])
        self.engine_thrust, self.engine_flow = 914e3, 300.0      # N, kg/s: until measured
        self.entry_speed = ENTRY_SPEED              # m/s: the entry burn's end, until solved

    # --- the readings --------------------------------------------------------
    def nose(self):
        w, x, y, z = self.fc.attitude
        return np.array((1.0 - 2.0 * (y * y + z * z), 2.0 * (x * y + w * z), 2.0 * (x * z - w * y)))

    def after_boost_back(self, r, v, mass, dv, entry, landing):
        """The prediction after a boost-back that changes the velocity ``v`` at ``r`` by ``dv``
        (Earth-fixed), the mass left by the rocket equation at the engines' exhaust speed."""
        left = mass * math.exp(-float(np.linalg.norm(dv)) * self.engine_flow / self.engine_thrust)
        rb, vb, _ = boostback.after_burn(r, v, dv, 6.0 * self.engine_thrust / (mass + left), EARTH_MU)
        return self.predict(rb, vb, left, entry=entry, landing=landing)

    def best_dip(self, back, aim):
        """``(dip, v_go)``: of the boost-back's dips DIPS (rad), the one whose burn, entry
        burn (to ENTRY_SPEED whatever it costs) and landing burn leave the most mass at
        touchdown, and its velocity to gain (Earth-fixed, m/s)."""
        fc, pad = self.fc, self.pad
        r, v = pad.state(fc)
        mass = fc.mass
        entry, landing = self.burns(unbounded=True)
        best = None
        for dip in DIPS:
            def miss(trial):
                return pad.offset(self.after_boost_back(r, v, mass, trial - v, entry, landing).point) - aim

            to_gain = boostback.velocity_to_gain(miss, v, boostback.burn_plane(r, back, dip), passes=6)
            kept = self.after_boost_back(r, v, mass, to_gain, entry, landing).mass
            if best is None or kept > best[0]:
                best = (kept, dip, to_gain)
        return best[1], best[2]

    def usable(self):
        """Propellant (kg) the engines can still draw."""
        return sum(self.fc.propellant.values()) - UNUSABLE

    def measure_engines(self):
        """One lit engine's vacuum thrust (N) and mass flow (kg/s) at full throttle, from the
        engines running at full thrust."""
        full = [e for e in self.fc.engines if e["thrust_N"] > 0.0 and e["spool"] >= 1.0 and e["throttle"] > 0.99]
        if full:
            pressure = self.fc.air_pressure
            self.engine_thrust = float(np.mean([e["thrust_N"] for e in full])) + pressure * EXIT_AREA
            self.engine_flow = float(np.mean([e["mass_flow_kg_s"] for e in full]))

    def solve_entry_speed(self, predict, highest, lit_entry=False, lean=(0.0, 0.0)):
        """Solve the entry burn's end airspeed (m/s, kept in ``entry_speed``) for the
        prediction ``predict(entry, landing)`` of the burns (lit now when ``lit_entry``,
        leaned by ``lean``), at most ``highest``; the usable propellant (kg) predicted at
        touchdown with it (less than LANDING_MARGIN: the return is short)."""
        def kept(speed):
            entry, landing = self.burns(lit_entry, lean, speed=speed)
            return predict(entry, landing).mass - self.dry - UNUSABLE - LANDING_MARGIN

        self.entry_speed = descent.entry_end_speed(kept, ENTRY_SPEED, max(highest, ENTRY_SPEED),
                                                   guess=self.entry_speed)
        return kept(self.entry_speed) + LANDING_MARGIN

    def burns(self, lit_entry=False, lean=(0.0, 0.0), unbounded=False, speed=None):
        """The entry burn (three engines, lit now when ``lit_entry``, ended at ``speed`` or
        the solved ``entry_speed``) and the landing burn (one engine, its thrust less the
        air's push on its nozzle) as the predictor models them; ``unbounded``, as if the
        tanks held whatever they need, the entry burn flown to ENTRY_SPEED (to compare
        plans by what they leave)."""
        speed = ENTRY_SPEED if unbounded else self.entry_speed if speed is None else speed
        entry = entry_burn(math.inf if lit_entry else ENTRY_ALTITUDE, speed, 3.0 * self.engine_thrust,
                           3.0 * self.engine_flow, 0.0 if unbounded else self.dry + UNUSABLE, lean)
        landing = landing_burn(self.engine_thrust, self.engine_flow, LANDING.plan, LANDING.touch_speed,
                               0.0 if unbounded else self.dry + UNUSABLE, LANDING.ceiling, EXIT_AREA)
        return entry, landing

    # --- 1. boost-back ----------------------------------------------------------
    def boost_back(self, centre, three):
        """Flip on the centre engine at its least throttle, then burn on three along the
        velocity to gain; the landing point is predicted from the burn's end
        (:func:`~rocketsim.guidance.boostback.after_burn`), with the mass the burn leaves
        (the rocket equation at the engines' exhaust speed)."""
        fc, pad = self.fc, self.pad
        now = [*pad.state(fc), fc.mass]             # the state the misses are predicted from
        entry, landing = self.burns()

        def miss(trial):
            return pad.offset(self.after_boost_back(*now, trial - now[1], entry, landing).point) - aim

        aim = np.zeros(2)
        first = miss(now[1])
        aim = AIM_OFF * first / np.linalg.norm(first)
        back = -pad.horizontal(*first)                      # over the ground, back towards the pad
        dip, to_gain = self.best_dip(back, aim)
        fc.point_at(pad.to_eci(to_gain, fc.time))
        fc.ignite(centre)
        fc.throttle(0.0)
        fc.event("boost-back start", miss_m=float(np.linalg.norm(first)), to_gain_m_s=float(np.linalg.norm(to_gain)),
                 dip_deg=math.degrees(dip))
        lit = False
        checked = planned = fc.time
        while True:
            if lit or fc.time - planned >= FLIP_CYCLE - 1e-9:   # the plan moves slowly through the flip
                now = [*pad.state(fc), fc.mass]
                plane = boostback.burn_plane(now[0], to_gain, dip)
                to_gain = boostback.velocity_to_gain(miss, now[1], plane, guess=to_gain, passes=2)
                self.solve_entry_speed(lambda e, la: self.after_boost_back(*now, to_gain, e, la), FASTEST_ENTRY)
                entry, landing = self.burns()
                planned = fc.time
            size = float(np.linalg.norm(to_gain))
            acceleration = fc.thrust / fc.mass
            step, checked = fc.time - checked, fc.time       # the update period now
            if lit and boostback.cutoff_due(to_gain, pad.from_eci(self.nose(), fc.time), acceleration,
                                            step, TAIL_OFF):
                break
            if size > STEADY * max(acceleration, 1.0) or not lit:   # then hold still: no spin at cut-off
                aim_eci = pad.to_eci(to_gain / size, fc.time)
                fc.point_at(aim_eci)
            if not lit and self.nose() @ aim_eci > math.cos(AIMED):
                fc.ignite(three)
                lit = True
            fc.throttle(1.0 if lit and size > FINE_GAIN else 0.0)
            if lit and size > FINE_GAIN:
                self.measure_engines()
                entry, landing = self.burns()
            # the time to the cut-off at full thrust: a second's sleep far from it, a cycle's, a step's
            left = (size - acceleration * 0.5 * (step + TAIL_OFF)) / max(acceleration, 1.0)
            fc.sleep(1.0 if lit and left > 3.0 else BURN_CYCLE if left > 2.0 * BURN_CYCLE else 0.0)
        fc.shutdown(three)
        fc.event("boost-back end", to_gain_m_s=size, usable_propellant_kg=self.usable(),
                 entry_end_airspeed_m_s=self.entry_speed)
        fc.sleep(1.0)                       # hold the attitude through the tail-off

    # --- 3. entry burn ----------------------------------------------------------
    def tail_angle(self):
        """The angle (rad) between the nose and the airflow's reverse."""
        fc = self.fc
        return math.acos(max(-1.0, min(1.0, -float(self.nose() @ fc.air_velocity) / fc.airspeed)))

    def await_entry(self):
        """Until the entry burn must be lit: the air swings the stage tail first (it has no
        thrusters), and the engines are lit below ENTRY_ALTITUDE + ENTRY_WINDOW as the nose
        will pass within ENTRY_ALIGNMENT of the airflow's reverse once they have come up
        (LEAD on at the angle's present rate), so that their gimbals catch the swing; or at
        ENTRY_LOWEST."""
        fc = self.fc
        before = None
        while fc.altitude > ENTRY_LOWEST:
            fc.point_at(-fc.air_velocity)                  # the grid fins turn it tail first
            angle = self.tail_angle()
            rate = 0.0 if before is None else (angle - before[0]) / max(fc.time - before[1], 1e-9)
            before = (angle, fc.time)
            if fc.altitude < ENTRY_ALTITUDE + ENTRY_WINDOW and angle + min(rate, 0.0) * LEAD < ENTRY_ALIGNMENT:
                return
            fc.sleep(BURN_CYCLE if angle > 4.0 * ENTRY_ALIGNMENT else 0.0)

    def entry(self, engines):
        fc, pad = self.fc, self.pad
        fc.ignite(engines)
        fc.throttle(0.0)                        # the least thrust until the gimbals have caught the swing
        r, v = pad.state(fc)
        entry, landing = self.burns(lit_entry=True)          # the miss as lit: what the lean must steer
        off = pad.offset(self.predict(r, v, fc.mass, entry=entry, landing=landing).point)
        fc.event("entry burn start", altitude_m=fc.altitude, airspeed_m_s=fc.airspeed,
                 miss_m=float(np.linalg.norm(off)))
        airspeed = Approach(self.entry_speed, periods=(BURN_CYCLE,))
        lean = np.zeros(2)
        captured, lit = False, fc.time
        while True:
            r, v = pad.state(fc)
            mass = fc.mass
            kept = self.solve_entry_speed(lambda e, la: self.predict(r, v, mass, entry=e, landing=la),
                                            fc.airspeed, lit_entry=True, lean=lean)
            airspeed.limit = self.entry_speed
            if not airspeed.ahead(fc.airspeed, fc.time):
                break

            def miss(trial):
                entry, landing = self.burns(lit_entry=True, lean=trial)
                return pad.offset(self.predict(r, v, mass, entry=entry, landing=landing).point)

            if not captured and fc.thrust > 0.0 and (fc.time > lit + CAPTURE_TIME or (
                    float(np.linalg.norm(fc.body_rates)) < CAPTURED and self.tail_angle() < ENTRY_ALIGNMENT)):
                captured = True
                fc.throttle(1.0)
            # the lean solved until HOLD before the burn's end, then held: the nose follows a
            # lean with a lag, and one solved over the last moments asks more than it can follow
            left = (fc.airspeed - self.entry_speed) * mass / max(fc.thrust, 1.0)
            if left > HOLD or not captured:
                lean, off = descent.solve_lean(miss, lean, MAX_ENTRY_LEAN if captured else 0.0)
            else:
                off = miss(lean)
            back = -fc.air_velocity / fc.airspeed
            fc.point_at(descent.thrust_direction(back, pad.local_to_eci((lean[0], lean[1], 0.0), fc.time)))
            self.measure_engines()
            fc.sleep(airspeed.next_update())
        fc.shutdown(engines)
        fc.event("entry burn end", airspeed_m_s=fc.airspeed, altitude_m=fc.altitude,
                 usable_propellant_kg=self.usable(), miss_m=float(np.linalg.norm(off)),
                 touchdown_propellant_kg=kept)

    # --- 4. aerodynamic descent ---------------------------------------------------
    def descend(self):
        fc, pad = self.fc, self.pad
        _, landing = self.burns()
        loss = self.ground_pressure * EXIT_AREA        # the air's push on the nozzle's exit
        full = self.engine_thrust - loss
        rule = Approach(0.0, rising=True, periods=(CYCLE, BURN_CYCLE))
        lean = np.zeros(2)
        trim = descent.LeanTrim(TRIM_TIME, TRIM_LIMIT)
        while True:
            mass, q, mach = fc.mass, fc.dynamic_pressure, fc.mach
            drag = fc.acceleration * G0
            self.predict.set_scale(self.drag.update(fc.time, mass, drag, q, mach))
            r, v = pad.state(fc)

            def miss(trial):
                return pad.offset(self.predict(r, v, mass, lean=trial, landing=landing).point)

            lean, off = descent.solve_lean(miss, lean, 1.0)
            back = -fc.air_velocity / fc.airspeed
            alpha = float(np.linalg.norm(lean)) * min(MAX_ALPHA, Q_ALPHA / max(q, 1.0))
            wanted = -alpha * lean / max(float(np.linalg.norm(lean)), 1e-9)    # the nose leans away
            flown = (pad.axes @ pad.from_eci(self.nose() - back, fc.time))[:2]
            asked = trim.command(wanted, flown, fc.time)
            fc.point_at(descent.lean_attitude(back, pad.local_to_eci((-asked[0], -asked[1], 0.0), fc.time),
                                              float(np.linalg.norm(asked))))
            due = powered_descent.ignition_due(fc.clearance, -fc.vertical_speed, mass, full, fc.gravity, drag,
                                               LEAD, LANDING, loss)
            if not rule.ahead(due, fc.time):
                break
            fc.sleep(rule.next_update())
        fc.event("descent end", miss_m=float(np.linalg.norm(off)), lean=float(np.linalg.norm(lean)),
                 drag_scale=self.drag.scale)

    # --- 5. landing burn ------------------------------------------------------------
    def land(self, engines):
        fc, pad = self.fc, self.pad
        fc.deploy_legs()
        fc.ignite(engines)
        fc.event("landing burn start", altitude_m=fc.altitude, airspeed_m_s=fc.airspeed,
                 usable_propellant_kg=self.usable())
        cutoff = Approach(LANDING.cutoff_height, periods=(BURN_CYCLE,))
        while True:
            offset, velocity = pad.local(fc)
            height, fall = fc.clearance, -fc.vertical_speed
            if powered_descent.cutoff_due(height, fall, LANDING) or not cutoff.ahead(height, fc.time):
                break
            nose = pad.axes @ pad.from_eci(self.nose(), fc.time)
            pushing = fc.thrust / fc.mass * nose[:2]
            air = pad.axes @ pad.from_eci(fc.air_velocity, fc.time)
            loss = fc.air_pressure * EXIT_AREA             # the air's push on the nozzle's exit
            direction, throttle = powered_descent.command(offset, velocity, height, fc.mass, self.engine_thrust - loss,
                                                          fc.gravity, fc.dynamic_pressure, air, LANDING, pushing, loss)
            fc.point_at(pad.local_to_eci(direction, fc.time))
            fc.throttle(throttle)
            fc.sleep(cutoff.next_update())
        fc.shutdown(engines)
        fc.release()
        fc.event("landing burn end", clearance_m=fc.clearance, vertical_speed_m_s=fc.vertical_speed,
                 usable_propellant_kg=self.usable())
