"""The events of a flight that nobody commands: liftoff, max-Q, burn-out, orbit.

One :class:`FlightEvents` watches one body; the world calls
:meth:`FlightEvents.after_step` after every (batch of) step(s). Definitions:

* ``liftoff`` — a body that started on a site has risen 1 m above its
  starting height (figures: mass).
* ``max_q`` — the peak of the dynamic pressure on a staged vehicle,
  reported once ``q`` has fallen 5 % below a peak of at least 1 kPa (figures
  at the peak: ``dynamic_pressure_Pa``, ``mach``, ``altitude_m`` above the
  ellipsoid, the instant ``at_s``).
* ``stage_dry`` — a stage's usable propellant is gone (the engine model
  flags the instant); named ``MECO`` for the vehicle's first stage and
  ``SECO`` for its second when that is how the burn ends. A stage without
  tanks (solid motors only) has none.
* ``burnout`` — a solid motor's curve has ended (figures: the motor, the
  instant ``burnout_s``, its total impulse).
* ``apogee`` — a vehicle with parachutes that rose from the ground has begun to
  come down (its vertical speed over the ground turned negative; figures:
  ``height_agl_m`` above the ground: the site's flat ground, or the ellipsoid,
  and where: ``latitude_deg``, ``longitude_deg``).
* ``parachute_deployed`` — a parachute's trigger fired (its YAML trigger, at the
  end of the step in which it was met, or ``fc.deploy_parachute``; figures: the
  parachute, the trigger, ``height_agl_m``, ``vertical_speed_m_s``);
  ``parachute_inflated`` when its drag area is full (figures: the parachute,
  ``at_s``, the exact instant); ``parachute_released`` when a parachute another
  one ``releases`` is cut away (figures: the parachute, ``by``, ``at_s``).
* ``off_rail`` — the vehicle's last rail button has left its launch rail
  (figures: the instant ``at_s``, the speed along the rail ``surface_speed_m_s``, and,
  when the aerodynamics give a centre of pressure, the static margin
  ``stability_margin_cal``: ``(x_cm - x_cp) / d`` in calibers of the reference
  diameter, stations from the base, positive when the centre of pressure is
  behind the centre of mass).
* ``orbit`` — the first time a body that did not start in orbit coasts (no
  thrust) with a periapsis above 100 km (the Karman line): the elements as
  figures.

Commanded events (``ignition``, ``shutdown``, ``separation``) are recorded by
the flight computer and the world where the command is given.
"""

from __future__ import annotations

import math

import numpy as np

from rocketsim.atmosphere.table import TOP
from rocketsim.constants import DEG, EARTH_RADIUS_EQ
from rocketsim.vehicle.engines import C_ON, E_STAGE, E_TAIL, S_DRY, S_DRY_AT, S_TANKS
from rocketsim.vehicle.aero import A_AREA, A_GROUND, A_ON, centre_of_pressure
from rocketsim.vehicle.motors import M_CURVE0, M_IGNITION, M_IMPULSE, M_POINTS
from rocketsim.vehicle.parachutes import CH_CUT_BY, CH_DEPLOYED, CH_INFLATION, CH_LAG, cut_away, deploy
from rocketsim.vehicle.rail import RL_OFF_AT, RL_OFF_SPEED, RL_ON
from rocketsim.scenario.vehicle import AfterTrigger, HeightTrigger
from rocketsim.sim.vehicle_checks import ground_motion
from rocketsim.stepping import quiet

LIFTOFF_HEIGHT = 1.0          # m above the starting height
MAX_Q_MIN = 1000.0            # Pa, a peak smaller than this is not "max-Q"
MAX_Q_DROP = 0.95             # reported once q < 95 % of the peak
ORBIT_PERIAPSIS = 100e3       # m above the equatorial radius
# the cheap bound below which no orbit is possible (1 ppm under the test's radius: rounding)
ORBIT_PERIAPSIS_BOUND = (EARTH_RADIUS_EQ + ORBIT_PERIAPSIS) * (1.0 - 1e-6)


class FlightEvents:
    """The uncommanded events of one body (see the module)."""

    def __init__(self, world, body, on_ground: bool, stage_names: list[str]):
        self.world = world
        self.body = body
        self.start_height = body.view().geodetic[2] if on_ground else None
        self.lifted = not on_ground
        self.peak = None                          # (q, t, mach, altitude)
        self.max_q_done = False
        self.dry_seen: set[str] = set()
        self.burnt_out: set[str] = set()           # solid motors whose curve has ended
        self.on_rail = body.vehicle is not None and body.vehicle.arrays.rail[RL_ON] > 0.5
        self.rising = False                        # has risen since leaving the ground (apogee)
        self.apogee_at = None                      # s, mission time of the apogee event
        self.inflated_seen: set[str] = set()       # parachutes whose drag area is full, by name
        self.released_seen: set[str] = set()       # parachutes cut away, by name
        self.stage_names = stage_names            # the whole vehicle's, for MECO/SECO
        self.in_orbit = in_orbit(body.view().orbit)   # starting in orbit is not achieving it

    def after_step(self) -> None:
        """Watch the body's new state. The view (and its kernels) is built only while
        liftoff or max-Q is pending, or the orbit test has passed its cheap bound
        (:func:`periapsis_bound`): a few microseconds per step otherwise."""
        body = self.body
        if not self.lifted and body.view().geodetic[2] > self.start_height + LIFTOFF_HEIGHT:
            self.lifted = True
            self.world.event(body, "liftoff", {"mass_kg": body.mass})
        if body.vehicle is not None:        # a rigid body feels no air: no max-Q to watch
            if not self.max_q_done:
                self._max_q(body.view())
            self._stages_dry()
            if body.vehicle.n_motors:
                self._burnouts()
            if self.on_rail and body.vehicle.arrays.rail[RL_ON] < 0.5:
                self._off_rail()
            if body.vehicle.parachutes:
                self._parachutes()
        if not self.in_orbit and self.lifted and periapsis_bound(body.y, body.mu) > ORBIT_PERIAPSIS_BOUND:
            self._orbit(body.view())

    def liftoff_height(self) -> float:
        """m over the ellipsoid (the readings' height) above which liftoff is reported;
        inf once lifted off."""
        return math.inf if self.lifted else self.start_height + LIFTOFF_HEIGHT

    def run_watch(self, watch) -> float:
        """Fill the slots of a compiled run's ``watch`` that these events decide
        (:mod:`rocketsim.stepping.quiet`: max-Q pending, its definitions, the orbit test's
        bound, the liftoff height, the next motor burn-out); returns the dynamic-pressure
        peak so far (Pa; nan: none). The run needs the body's parachutes none."""
        body = self.body
        watch[quiet.WATCH_MAX_Q] = 0.0 if self.max_q_done else 1.0
        watch[quiet.WATCH_MAX_Q_MIN], watch[quiet.WATCH_MAX_Q_DROP] = MAX_Q_MIN, MAX_Q_DROP
        watch[quiet.WATCH_ORBIT] = math.inf if self.in_orbit else ORBIT_PERIAPSIS_BOUND
        watch[quiet.WATCH_LIFTOFF] = self.liftoff_height()
        model = body.vehicle
        motor, curve = model.arrays.motor, model.arrays.curve
        watch[quiet.WATCH_BURNOUT] = min((_curve_end(motor, curve, i) for i, name in enumerate(model.motor_names)
                                     if name not in self.burnt_out), default=math.inf)
        return math.nan if self.peak is None else self.peak[0]

    def peak_at(self, t: float, y) -> None:
        """A compiled run found the peak of the dynamic pressure at state ``y`` of mission
        time ``t`` (s): keep it as :meth:`_max_q` would have, from the truth's view there."""
        view = self.body.view_of(t, y)
        self.peak = (view.dynamic_pressure, t, view.mach, view.geodetic[2])

    def _max_q(self, view) -> None:
        if body_has_no_air(view):
            return
        q = view.dynamic_pressure
        if self.peak is None or q > self.peak[0]:
            self.peak = (q, self.body.t, view.mach, view.geodetic[2])
        elif self.peak[0] >= MAX_Q_MIN and q < MAX_Q_DROP * self.peak[0]:
            self.max_q_done = True
            q_peak, t_peak, mach, altitude = self.peak
            self.world.event(self.body, "max_q", {"dynamic_pressure_Pa": q_peak, "mach": mach, "altitude_m": altitude,
                                                  "at_s": t_peak})

    def _stages_dry(self) -> None:
        model = self.body.vehicle
        stage = model.arrays.stage
        for s, name in enumerate(model.stage_names):
            if stage[s, S_DRY] > 0.5 and name not in self.dry_seen and stage[s, S_TANKS] > 0:
                self.dry_seen.add(name)
                index = self.stage_names.index(name) if name in self.stage_names else -1
                label = {0: "MECO", 1: "SECO"}.get(index, "stage_dry")
                self.world.event(self.body, label, {"stage": name, "burnout_s": float(stage[s, S_DRY_AT])})

    def _parachutes(self) -> None:
        body = self.body
        model = body.vehicle
        chute = model.arrays.chute
        up, surface = ground_motion(body.central, body.t, body.y)
        vertical = float(surface @ up)
        lat, lon, h = self.world.where(body)
        height = h - model.arrays.aero.ref[A_GROUND]     # above the ground
        if self.start_height is not None and self.lifted and self.apogee_at is None:
            if vertical > 0.0:
                self.rising = True
            elif self.rising:
                self.apogee_at = body.t
                self.world.event(body, "apogee", {"height_agl_m": height, "latitude_deg": lat / DEG,
                                                  "longitude_deg": lon / DEG})
        for i, spec in enumerate(model.parachutes):
            if math.isnan(chute[i, CH_DEPLOYED]):
                trigger = spec.deploy
                if trigger == "apogee":
                    due = self.apogee_at is not None
                elif isinstance(trigger, HeightTrigger):
                    due = self.lifted and vertical < 0.0 and height <= trigger.height
                elif isinstance(trigger, AfterTrigger):
                    after = trigger.after
                    due = any(e["name"] == after.event and body.t >= e["time_s"] + after.delay - 1e-9
                              for e in body.events)
                else:
                    due = False
                if due:
                    self.deploy(i, _trigger_name(trigger), vertical, height)
            else:
                if spec.name not in self.inflated_seen:
                    full = chute[i, CH_DEPLOYED] + chute[i, CH_LAG] + chute[i, CH_INFLATION]
                    if body.t >= full:
                        self.inflated_seen.add(spec.name)
                        self.world.event(body, "parachute_inflated", {"parachute": spec.name,
                                                                      "at_s": float(full)})
                if spec.name not in self.released_seen and cut_away(body.t, chute, i):
                    self.released_seen.add(spec.name)
                    j = int(chute[i, CH_CUT_BY])
                    self.world.event(body, "parachute_released", {
                        "parachute": spec.name, "by": model.parachutes[j].name,
                        "at_s": float(chute[j, CH_DEPLOYED] + chute[j, CH_LAG])})

    def inherit(self, other: "FlightEvents") -> None:
        """Take over what ``other`` (the stack's watcher, at a separation) has seen of the
        motors, the parachutes and the apogee, so a separated stage reports none twice."""
        self.dry_seen = set(other.dry_seen)
        self.max_q_done = other.max_q_done
        self.burnt_out = set(other.burnt_out)
        self.inflated_seen = set(other.inflated_seen)
        self.released_seen = set(other.released_seen)
        self.apogee_at, self.rising = other.apogee_at, other.rising

    def deploy(self, i: int, trigger: str, vertical: float | None = None, height: float | None = None) -> bool:
        """Deploy the body's parachute ``i`` now (``trigger``: what fired it) and record
        it; False if it was already out."""
        body = self.body
        if not deploy(body.vehicle.arrays.chute, i, body.t):
            return False
        if vertical is None:
            up, surface = ground_motion(body.central, body.t, body.y)
            vertical = float(surface @ up)
            height = self.world.where(body)[2] - body.vehicle.arrays.aero.ref[A_GROUND]
        self.world.event(body, "parachute_deployed", {"parachute": body.vehicle.parachutes[i].name,
                                                      "trigger": trigger, "height_agl_m": height,
                                                      "vertical_speed_m_s": vertical})
        return True

    def recovery(self) -> dict:
        """The touchdown figures of a vehicle with parachutes: the landing point and the
        descent (from apogee) and drift (from the first deployment) times, s."""
        body = self.body
        lat, lon, _ = self.world.where(body)
        deployed = body.vehicle.arrays.chute[:, CH_DEPLOYED]
        figures = {"latitude_deg": lat / DEG, "longitude_deg": lon / DEG}
        if self.apogee_at is not None:
            figures["descent_time_s"] = body.t - self.apogee_at
        if not np.all(np.isnan(deployed)):
            figures["drift_time_s"] = body.t - float(np.nanmin(deployed))
        return figures

    def _off_rail(self) -> None:
        self.on_rail = False
        model = self.body.vehicle
        rail, aero = model.arrays.rail, model.arrays.aero
        figures = {"at_s": float(rail[RL_OFF_AT]), "surface_speed_m_s": float(rail[RL_OFF_SPEED])}
        if aero.ref[A_ON] > 0.5:
            x_cp = centre_of_pressure(aero.ref, aero.fin)
            if not math.isnan(x_cp):
                diameter = math.sqrt(4.0 * aero.ref[A_AREA] / math.pi)
                figures["stability_margin_cal"] = (model.mass_properties(self.body.y)[1] - x_cp) / diameter
        self.world.event(self.body, "off_rail", figures)

    def _burnouts(self) -> None:
        model = self.body.vehicle
        motor, curve = model.arrays.motor, model.arrays.curve
        for i, name in enumerate(model.motor_names):
            end = _curve_end(motor, curve, i)
            if name not in self.burnt_out and self.body.t >= end:
                self.burnt_out.add(name)
                self.world.event(self.body, "burnout", {"motor": name, "burnout_s": float(end),
                                                        "total_impulse_N_s": float(motor[i, M_IMPULSE])})

    def _orbit(self, view) -> None:
        orbit = view.orbit
        if not in_orbit(orbit):         # tested first: cheaper than the engines' states
            return
        if self.body.vehicle is None or coasting(self.body.vehicle, self.body.y, self.body.t):
            self.in_orbit = True
            self.world.event(self.body, "orbit", {
                "periapsis_altitude_m": orbit.periapsis - EARTH_RADIUS_EQ,
                "apoapsis_altitude_m": orbit.apoapsis - EARTH_RADIUS_EQ,
                "inclination_deg": orbit.i / DEG, "eccentricity": orbit.e})


def _curve_end(motor, curve, i: int) -> float:
    """Mission time (s) at which solid motor ``i``'s thrust curve ends."""
    return motor[i, M_IGNITION] + curve[int(motor[i, M_CURVE0] + motor[i, M_POINTS]) - 1, 0]


def periapsis_bound(y, mu: float) -> float:
    """An upper bound (m) of the periapsis radius of state ``y`` (ECI position and
    velocity first, m and m/s) about ``mu`` (m^3/s^2): the semi-latus rectum
    ``|r x v|^2 / mu`` (the periapsis is ``p / (1 + e)``), in plain floats.
    Below :data:`ORBIT_PERIAPSIS_BOUND` the body cannot be in orbit and the elements
    are not computed."""
    x, y_, z, u, v, w = y[:6].tolist()
    hx, hy, hz = y_ * w - z * v, z * u - x * w, x * v - y_ * u
    return (hx * hx + hy * hy + hz * hz) / mu


def in_orbit(orbit) -> bool:
    """An ellipse whose periapsis clears 100 km above the equatorial radius."""
    return orbit.e < 1.0 and orbit.periapsis - EARTH_RADIUS_EQ > ORBIT_PERIAPSIS


def coasting(model, y, t: float) -> bool:
    """True when no engine of ``model`` thrusts: each is commanded off or its stage has
    run dry, and its tail-off is over; and no solid motor is inside its curve."""
    eng, cmd, stage = model.arrays.eng, model.arrays.cmd, model.arrays.stage
    clocks = y[model.clocks]
    for e in range(model.n_engines):
        s = int(eng[e, E_STAGE])
        if stage[s, S_DRY] > 0.5:
            if t - stage[s, S_DRY_AT] < eng[e, E_TAIL]:
                return False
        elif cmd[e, C_ON] > 0.5 or clocks[e] < eng[e, E_TAIL]:
            return False
    motor, curve = model.arrays.motor, model.arrays.curve
    for i in range(model.n_motors):
        since = t - motor[i, M_IGNITION]
        if 0.0 <= since <= curve[int(motor[i, M_CURVE0] + motor[i, M_POINTS]) - 1, 0]:
            return False
    return True


def body_has_no_air(view) -> bool:
    """True above the flight model's air (600 km): no dynamic pressure to watch."""
    return view.geodetic[2] > TOP or math.isnan(view.geodetic[2])


def _trigger_name(trigger) -> str:
    """How an event names a parachute's trigger: ``apogee``, ``height 300 m``, ``after burnout + 2 s``."""
    if isinstance(trigger, HeightTrigger):
        return f"height {trigger.height:g} m"
    if isinstance(trigger, AfterTrigger):
        return f"after {trigger.after.event} + {trigger.after.delay:g} s"
    return str(trigger)
