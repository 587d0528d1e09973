"""``fc``: what a flight program sees of its vehicle, and how it hands back control.

The scheduling calls (:meth:`FlightComputer.step`, :meth:`~FlightComputer.sleep`,
:meth:`~FlightComputer.wait_until`), logging and events, and the readings.
All values are SI (m, s, kg, rad, Pa) unless a name ends in ``_deg``; vectors
are numpy arrays in the inertial frame (ECI of the mission epoch).

Readings come from the navigation estimate: the truth when the scenario's
``sensors`` is ``truth`` (the default), else the truth with the errors of
:mod:`rocketsim.flight.sensors`, drawn once per step; everything derived
(altitude, the orbit, directions, air data) inherits them. The physics always
runs on the truth.
"""

from __future__ import annotations

import math
import sys
from typing import Callable

import numpy as np

from rocketsim.constants import G0, MAX_DURATION, SECONDS_PER_DAY
from rocketsim.dynamics.central import planetocentric
from rocketsim.dynamics.third_bodies import nbody_flag
from rocketsim.ephemeris.solar_system import BODIES
from rocketsim.flight import arguments, conditions
from rocketsim.layout import P_RADIUS
from rocketsim.flight.accelerometer import sensed_acceleration
from rocketsim.flight.conditions import Condition
from rocketsim.flight.impact import predict_impact
from rocketsim.flight.readings import StateView
from rocketsim.frames.elements import Elements
from rocketsim.flight.autopilot import MODES, AttitudeCommand, steer
from rocketsim.flight.craft import Craft
from rocketsim.flight.navigation import Navigation
from rocketsim.vehicle.contact import contact_heights
from rocketsim.vehicle.control import Propulsion
from rocketsim.vehicle.heating import sutton_graves, sutton_graves_constant

MAX_CROSS = 1e3     # fc.steer_linear_tangent's cross-track share at most (its square stays finite)


class FlightComputer:
    """The program's handle on one body of the world."""

    def __init__(self, craft: Craft):
        self._craft = craft
        self._nav = Navigation(craft)
        self._view = self._nav.view             # the estimate of this step
        self._measured = self._nav.measured     # a scalar reading with its sensor's error
        self._command: AttitudeCommand | None = None
        self._engines: Propulsion | None = None
        self._fins = False          # grid fins steered by the autopilot (fc.deploy_grid_fins)
        self._legs = False          # fc.deploy_legs called
        self._rcs = False           # RCS thrusters steered by the autopilot (fc.rcs)

    # --- timing -------------------------------------------------------------
    def step(self) -> None:
        """Hand control back; the program resumes at the next step."""
        self._craft.hand_back(self._craft.time + self._craft.step_length)

    def sleep(self, seconds: float) -> None:
        """Hand control back for ``seconds`` of mission time (at least one step)."""
        seconds = arguments.duration("fc.sleep", seconds)
        self._craft.hand_back(self._craft.time + max(seconds, self._craft.step_length))

    def cruise(self, seconds: float) -> None:
        """Hand control back for ``seconds`` and allow cruise rails meanwhile.

        Far from every body (outside the central body's 2 000 km clearance
        shell) the vehicle is then advanced by RK4 steps sized by how fast its
        path turns (up to an hour each) instead of 20 ms ones; it falls back
        to 20 ms steps before an encounter and when it leaves the central
        body's sphere of influence. Example: ``fc.cruise(3 * 86400)``.
        """
        seconds = arguments.duration("fc.cruise", seconds)
        until = self._craft.time + max(seconds, self._craft.step_length)
        self._craft.allow_cruise(until)
        self._craft.hand_back(until)

    def wait_until(self, predicate: Callable[[], bool]) -> None:
        """Hand control back until ``predicate()`` is true (checked once per step, on the
        state at the start of the step). Any function of no arguments serves, e.g.
        ``fc.wait_until(lambda: fc.altitude < 10_000)``; a condition made with
        :meth:`below` and :meth:`above` reads the same and is tested in compiled code,
        so the vehicle flies many steps per call meanwhile:
        ``fc.wait_until(fc.below("altitude", 10_000))``."""
        predicate = arguments.condition("fc.wait_until", predicate)
        made_for = predicate.vehicle if isinstance(predicate, Condition) else None
        if made_for is not None and made_for is not self._craft.vehicle:
            raise ValueError("fc.wait_until(): the condition reads a stage's propellant of the stack "
                             "before it changed (staging, a fairing); make it again")
        self._craft.hand_back(self._craft.time + self._craft.step_length, predicate)

    def below(self, reading: str, value: float, stage: str | None = None, towards=None) -> Condition:
        """The condition ``reading < value`` for :meth:`wait_until`: ``reading`` is
        ``"altitude"`` (m), ``"vertical_speed"`` (m/s) or ``"time"`` (s), read as
        :attr:`altitude`, :attr:`vertical_speed` and :attr:`time`; ``"propellant"`` (kg)
        with a ``stage`` name, the sum of that stage's tanks in :attr:`propellant`; or
        ``"nose_angle"`` (rad, 0..pi) with a direction ``towards`` (ECI), the angle
        between the nose and it (compared by its cosine). Combine with ``&`` (and) and
        ``|`` (or). Example:
        ``fc.wait_until(fc.below("altitude", 70e3) & fc.below("vertical_speed", -900))``
        (:mod:`rocketsim.flight.conditions`)."""
        return self._compare("fc.below", reading, value, stage, towards, conditions.BELOW)

    def above(self, reading: str, value: float, stage: str | None = None, towards=None) -> Condition:
        """The condition ``reading > value`` for :meth:`wait_until` (as :meth:`below`).
        Example: ``fc.wait_until(fc.above("altitude", pad + 300))``."""
        return self._compare("fc.above", reading, value, stage, towards, conditions.ABOVE)

    def _compare(self, call: str, reading: str, value: float, stage, towards, op: float) -> Condition:
        reading = arguments.choice(call, "reading", reading, conditions.READINGS)
        value = arguments.number(call, "value", value)
        if stage is not None and reading != "propellant":
            raise ValueError(f"{call}(): stage goes with the reading propellant only")
        if towards is not None and reading != "nose_angle":
            raise ValueError(f"{call}(): towards goes with the reading nose_angle only")
        if reading == "propellant":
            vehicle = self._propulsion().model
            stage = arguments.choice(call, "stage", stage, vehicle.stage_names)
            return conditions.compare_propellant(self, vehicle, vehicle.stage_names.index(stage), value, op)
        if reading == "nose_angle":
            value = arguments.number(call, "value", value, 0.0, math.pi)
            v = arguments.vector(call, "towards", towards)
            norm = math.hypot(*v.tolist())      # finite: the components are within 1e150
            if not norm > 0.0:
                raise ValueError(f"{call}(): towards must be a non-zero vector")
            return conditions.compare_nose(self, v / norm, value, op)
        return conditions.compare(self, reading, value, op)

    # --- output -------------------------------------------------------------
    def log(self, *parts) -> None:
        """Write a line to the telemetry's ``/log`` channel."""
        self._craft.log(arguments.text("fc.log", "the line", " ".join(str(p) for p in parts)))

    def event(self, name: str, **figures) -> None:
        """Record a named event with its figures (numbers or strings)."""
        name, figures = arguments.text("fc.event", "name", str(name)), arguments.figures("fc.event", figures)
        self._craft.event(name, figures)

    def warm_up(self) -> None:
        """Read everything once (builds the air table, loads compiled kernels)."""
        view = self._view()
        for name in ("euler", "air", "orbit", "gravity", "effective_gravity", "angle_of_attack",
                     "time_to_apoapsis", "vertical_speed", "horizontal_speed", "mach"):
            getattr(view, name)
        body = self._craft
        if body.vehicle is not None:   # the compiled calls behind fc.engines, fc.thrust, fc.propellant
            engines, p_a = self._propulsion(), body.truth().air[1]
            engines.states(body.y, self._craft.time, p_a)
            engines.thrusts(body.y, self._craft.time, p_a)
            engines.propellant(body.y)

    # --- time ---------------------------------------------------------------
    @property
    def time(self) -> float:
        """Mission time, s since the epoch (liftoff)."""
        return self._craft.time

    @property
    def utc(self):
        """UTC as a timezone-aware datetime (leap seconds ignored)."""
        return self._craft.epoch.utc_at(self._craft.time)

    # --- where and how fast -------------------------------------------------
    @property
    def position(self) -> np.ndarray:
        """Centre-of-mass position, ECI, m."""
        return self._view().position.copy()

    @property
    def velocity(self) -> np.ndarray:
        """Orbital (inertial) velocity, ECI, m/s."""
        return self._view().velocity.copy()

    @property
    def surface_velocity(self) -> np.ndarray:
        """Velocity relative to the central body's turning ground (Earth's WGS84 rate, the
        Moon's or Mars's IAU rate after a handover), frame axes, m/s."""
        return self._view().surface_velocity.copy()

    @property
    def vertical_speed(self) -> float:
        """Rate of climb relative to the ground, m/s."""
        return self._view().vertical_speed

    @property
    def horizontal_speed(self) -> float:
        """Speed over the ground, m/s."""
        return self._view().horizontal_speed

    def _where(self) -> tuple[float, float, float]:
        """(latitude rad, longitude rad, height m) of the estimate (:meth:`_place`)."""
        return self._place(self._view(), "where")

    def _place(self, view: StateView, key: str) -> tuple[float, float, float]:
        """(latitude rad, longitude rad, height m) of ``view``'s position: geodetic on
        WGS84 about Earth, planetocentric over the central body's ellipsoid elsewhere
        (:func:`rocketsim.dynamics.central.planetocentric`, kept for the step as ``key``)."""
        body = self._craft
        if body.central == "earth":
            return view.geodetic
        if key not in self._nav.readings:
            self._nav.readings[key] = planetocentric(
                view.position, body.central, self._craft.epoch.jd_tt() + body.t / SECONDS_PER_DAY)
        return self._nav.readings[key]

    def _true_height(self) -> float:
        """Height of the true centre of mass over the central body's ground, m (what a radar
        measures, as :attr:`altitude` reads it: over WGS84 about Earth, over the central
        body's ellipsoid after a handover)."""
        self._view()                    # a new step clears the readings kept in _place
        return self._place(self._craft.truth(), "true place")[2]

    @property
    def altitude(self) -> float:
        """Height above the WGS84 ellipsoid, m; away from Earth (after a handover) above
        the central body's ellipsoid, along the radius."""
        return self._where()[2]

    @property
    def radar_altitude(self) -> float:
        """Height above the ground (the central body's ellipsoid: no terrain), with the
        radar's error, m."""
        return self._measured("radar_altitude", self._true_height)

    @property
    def latitude(self) -> float:
        """Geodetic latitude, rad (planetocentric away from Earth)."""
        return self._where()[0]

    @property
    def longitude(self) -> float:
        """Longitude, east positive, rad (from the central body's prime meridian)."""
        return self._where()[1]

    # --- directions (unit vectors, ECI) ----------------------------------------
    @property
    def prograde(self) -> np.ndarray:
        return self._view().prograde.copy()

    @property
    def retrograde(self) -> np.ndarray:
        return -self._view().prograde

    @property
    def surface_prograde(self) -> np.ndarray:
        return self._view().surface_prograde.copy()

    @property
    def surface_retrograde(self) -> np.ndarray:
        return -self._view().surface_prograde

    @property
    def normal(self) -> np.ndarray:
        """Orbit normal, ``r x v`` direction."""
        return self._view().normal.copy()

    @property
    def radial(self) -> np.ndarray:
        """Radial out, from the central body's centre."""
        return self._view().radial.copy()

    # --- attitude -----------------------------------------------------------
    @property
    def attitude(self) -> np.ndarray:
        """Unit quaternion (w, x, y, z), body axes -> ECI."""
        return self._view().attitude.copy()

    @property
    def body_rates(self) -> np.ndarray:
        """Body rates about x (roll), y, z, rad/s."""
        return self._view().body_rates.copy()

    @property
    def pitch(self) -> float:
        """Nose elevation above the local horizon, rad."""
        return self._view().euler[0]

    @property
    def heading(self) -> float:
        """Nose azimuth from north towards east, rad, [0, 2 pi)."""
        return self._view().euler[1]

    @property
    def roll(self) -> float:
        """Turn about the nose from the belly-to-the-ground attitude, rad."""
        return self._view().euler[2]

    # --- the air -------------------------------------------------------------
    @property
    def air_density(self) -> float:
        """Density of the air at the vehicle, kg/m^3 (zero above 600 km)."""
        return self._measured("air_density", lambda: self._view().air[0])

    @property
    def air_pressure(self) -> float:
        """Static pressure of the air at the vehicle, Pa (zero above 600 km)."""
        return self._measured("air_pressure", lambda: self._view().air[1])

    @property
    def air_temperature(self) -> float:
        """Temperature of the air at the vehicle, K."""
        return self._view().air[2]

    @property
    def speed_of_sound(self) -> float:
        """Speed of sound at the vehicle, m/s."""
        return self._view().air[3]

    @property
    def wind(self) -> np.ndarray:
        """The wind at the vehicle (air velocity over the ground), ECI, m/s."""
        return self._view().air[4].copy()

    @property
    def forecast(self):
        """The day's air over the site as the flight was given it: an
        :class:`~rocketsim.atmosphere.table.AtmosphereTable` (density, pressure,
        temperature, speed of sound and wind east/north against height every 50 m) of
        Earth's air (ValueError after a handover to another body)."""
        if self._craft.central != "earth":
            raise ValueError("the forecast is of Earth's air only")
        return self._view()._atmosphere()

    @property
    def air_velocity(self) -> np.ndarray:
        """Velocity relative to the air, ``v - omega_E x r - wind``, ECI, m/s."""
        return self._view().air[5].copy()

    @property
    def airspeed(self) -> float:
        """Speed relative to the air, m/s."""
        return self._measured("airspeed", lambda: self._view().airspeed)

    @property
    def mach(self) -> float:
        """Airspeed over the local speed of sound."""
        return self._measured("mach", lambda: self._view().mach)

    @property
    def dynamic_pressure(self) -> float:
        """``q = rho |v_air|^2 / 2``, Pa."""
        return self._measured("dynamic_pressure", lambda: self._view().dynamic_pressure)

    @property
    def angle_of_attack(self) -> float:
        """Angle between the nose and the air-relative velocity, rad."""
        return self._measured("angle_of_attack", lambda: self._view().angle_of_attack)

    # --- attitude (the autopilot steers with the engines' gimbals) --------------
    def point(self, pitch: float, heading: float, roll: float | None = None) -> None:
        """Point the nose ``pitch`` rad above the local horizon, ``heading`` rad from north,
        and, if ``roll`` (rad) is given, turned that far about the nose from belly to the
        ground (the angle :attr:`roll` reads); ``roll=None`` leaves roll free (damped).
        Example: ``fc.point(math.radians(10), math.radians(90), roll=math.radians(180))``."""
        pitch = arguments.angle("fc.point", "pitch", pitch, arguments.MAX_PITCH)
        heading, roll = arguments.angle("fc.point", "heading", heading), arguments.roll("fc.point", roll)
        self._steer(AttitudeCommand(pitch=pitch, heading=heading, roll=roll))

    def point_at(self, vector, frame: str = "eci", roll: float | None = None) -> None:
        """Point the nose along ``vector``: in ``"eci"`` axes, or ``"local"`` (east, north, up);
        ``roll`` (rad) as in :meth:`point`."""
        v = arguments.vector("fc.point_at", "vector", vector)
        frame = arguments.choice("fc.point_at", "frame", frame, ("eci", "local"))
        roll = arguments.roll("fc.point_at", roll)
        if frame == "local":
            v = v @ self._view().enu
        norm = math.sqrt(float(v @ v))  # finite: the components are within 1e150 (arguments.vector)
        if not norm > 0.0:
            raise ValueError("fc.point_at() needs a non-zero vector")
        self._steer(AttitudeCommand(direction=v / norm, roll=roll))

    def hold(self, mode: str, roll: float | None = None) -> None:
        """Follow a direction of the flight: one of prograde, retrograde, surface_prograde,
        surface_retrograde, normal, antinormal, radial, antiradial; ``roll`` (rad) as in
        :meth:`point`. Example: ``fc.hold("retrograde", roll=0.0)``."""
        mode, roll = arguments.choice("fc.hold", "mode", mode, MODES), arguments.roll("fc.hold", roll)
        self._steer(AttitudeCommand(mode=mode, roll=roll))

    def steer_linear_tangent(self, a: float, b: float, cross: float = 0.0, roll: float | None = None) -> None:
        """Linear-tangent steering, followed by the autopilot at every step in compiled code
        without waking the program: the nose ``atan(a + b tau)`` rad above the plane normal
        to the radius (``tau`` s from now), ahead along the velocity in the plane of
        :attr:`radial` and :attr:`velocity`, tilted by ``cross`` along :attr:`normal` (the
        direction of ``cos(pitch) h + sin(pitch) radial + cross normal``, ``h`` the unit
        horizontal velocity; ``|cross|`` at most :data:`MAX_CROSS`, a tilt of 89.94 deg
        out of the plane); ``roll`` (rad) as in :meth:`point`. Example:
        ``fc.steer_linear_tangent(0.6, -0.004)``: 31 deg now, 0 deg in 150 s."""
        call = "fc.steer_linear_tangent"
        a, b = arguments.number(call, "a", a), arguments.number(call, "b", b)
        cross, roll = arguments.number(call, "cross", cross, -MAX_CROSS, MAX_CROSS), arguments.roll(call, roll)
        self._steer(AttitudeCommand(law=(self._craft.time, a, b, cross), roll=roll))

    def release(self) -> None:
        """Stop steering (the gimbals stay where they are, the RCS thrusters stop)."""
        self._steer(None)

    def _steer(self, command: AttitudeCommand | None) -> None:
        self._command = command
        self._craft.command_attitude(command)

    def rcs(self, on: bool) -> None:
        """Hand the reaction-control thrusters to the autopilot (``on`` true) or take them
        away (false: every thruster stops). While on, the autopilot turns and holds the
        commanded attitude with them on all three axes, alongside the gimbals and grid
        fins, in a coast too (see :mod:`rocketsim.flight.autopilot`); they draw from
        their tanks. Records an ``rcs on`` / ``rcs off`` event. Example: ``fc.rcs(True)``."""
        on = arguments.flag("fc.rcs", "on", on)
        vehicle = self._craft.vehicle
        if vehicle is None or not len(vehicle.arrays.aero.rcs):
            raise ValueError(f"{self._craft.name} has no RCS thrusters")
        if not on:
            self._craft.stop_rcs()
        if on != self._rcs:
            self._rcs = on
            self.event("rcs on" if on else "rcs off")

    def autopilot(self, fold: bool = False) -> tuple | None:
        """Run the autopilot for this step (the world calls it once per step).

        With ``fold`` (the caller's compiled step can run the autopilot's step first)
        and nothing of it left to Python here (about Earth, in the air the vehicle flies
        through, the RCS off, and any estimate read earlier in this step made from the
        truth's current view: not after a staging within the step, where it steers on the
        estimate read before it; the compiled step makes the same estimate, the truth or
        with the sensors' errors), returns what that step reads instead, ``(command code, fins)``
        (:meth:`rocketsim.sim.vehicle_checks.VehicleChecks.advance`: the same compiled
        step, one call fewer); else runs it and returns None."""
        command = self._command
        body = self._craft
        if command is None or body.vehicle is None:
            return None
        folded = self.folded() if fold else None
        if folded is not None:
            return folded
        nav, truth = self._view(), body.truth()
        steer(command, nav, body.vehicle, self._propulsion(), body.y, self._craft.time,
              math.nan if nav is truth else truth.air[1], fins=self._fins, rcs=self._rcs)

    def folded(self) -> tuple | None:
        """What a compiled step reads to run this step's autopilot itself, ``(command
        code, fins)``, when nothing of it is left to Python (see :meth:`autopilot`);
        None when it is (or nothing is commanded). Runs nothing."""
        command = self._command
        body = self._craft
        if command is None or body.vehicle is None:
            return None
        nav = self._nav             # its estimate: none yet, an earlier step's, or this step's
        if not self._rcs and body.central == "earth" \
                and (nav.t != body.t or body.is_truth(nav.source)) and body.flies_in_days_air():
            return command.code, self._fins
        return None

    # --- landing ------------------------------------------------------------------
    def deploy_grid_fins(self) -> None:
        """Hand the grid fins to the autopilot: from now on it steers pitch, yaw and roll
        with them as well as with the gimbals (see :mod:`rocketsim.flight.autopilot`).
        Before this call they are held at zero deflection. The fins' drag and restoring
        moment are in the aerodynamics from the start (the model has no stowed
        fins). Records a ``grid fins deployed`` event. Example: ``fc.deploy_grid_fins()``."""
        if self._craft.vehicle is None or not len(self._craft.vehicle.arrays.aero.grid):
            raise ValueError(f"{self._craft.name} has no grid fins")
        if not self._fins:
            self._fins = True
            self.event("grid fins deployed")

    def deploy_legs(self) -> None:
        """Deploy the landing legs. The legs' contact points are modelled as out from the
        start (a vehicle stands on them on the pad), so this only records a ``legs
        deployed`` event; a program should still call it before landing. Example:
        ``fc.deploy_legs()``."""
        if self._craft.vehicle is None or not len(self._craft.vehicle.arrays.aero.contact):
            raise ValueError(f"{self._craft.name} has no legs")
        if not self._legs:
            self._legs = True
            self.event("legs deployed")

    @property
    def clearance(self) -> float:
        """Height of the lowest contact point (a leg's foot, an engine bell) above the
        ground, m: the radar altitude less the centre of mass's height over that point."""
        body = self._craft
        if body.vehicle is None or not len(body.vehicle.arrays.aero.contact):
            return self.radar_altitude
        self._view()
        if "clearance" not in self._nav.readings:
            lowest = float(contact_heights(body.y, body.p, body.vehicle).min())
            self._nav.readings["clearance"] = self.radar_altitude - (self._true_height() - lowest)
        return self._nav.readings["clearance"]

    def deploy_parachute(self, name: str) -> bool:
        """Deploy the parachute ``name`` now (whatever its trigger in the vehicle file): its
        opening lag and inflation follow (docs/physics.md#parachutes). Records
        ``parachute_deployed``; returns False if it was already out. ``ValueError`` if the
        vehicle has no parachute of that name. Example: ``fc.deploy_parachute("main")``."""
        vehicle = self._craft.vehicle
        names = [c.name for c in vehicle.parachutes] if vehicle is not None else []
        if name not in names:
            raise ValueError(f"{self._craft.name} has no parachute named {name!r}"
                             + (f" (parachutes: {', '.join(names)})" if names else ""))
        return self._craft.deploy_parachute(names.index(name))

    # --- the mission -----------------------------------------------------------
    @property
    def target(self):
        """The mission's target (``fc.target.orbit.altitude``, ``.inclination``; SI)."""
        return self._craft.target

    @property
    def pad_azimuth(self) -> float:
        """The launch site's pad azimuth from north, rad (nan without a site)."""
        return self._craft.pad_azimuth

    @property
    def stages(self) -> list[str]:
        """Names of the stages still attached, bottom first (empty for a rigid body)."""
        vehicle = self._craft.vehicle
        return list(vehicle.stage_names) if vehicle is not None else []

    # --- staging ------------------------------------------------------------
    def stage(self) -> str:
        """Separate the lowest stage now; this program flies on with the upper stack.

        The stage becomes a body of its own (flown by its program from the
        scenario's ``programs:``, if any). Returns its name.
        """
        self._nav.readings.pop("clearance", None)       # the stack's feet have changed
        return self._craft.stage()

    def jettison_fairing(self) -> tuple[str, str]:
        """Drop the payload fairing: it opens into two halves, bodies of their own
        (``fairing_1``, ``fairing_2``); returns their names."""
        return self._craft.jettison_fairing()

    def deploy_payload(self) -> str:
        """Release the payload (after the fairing): it becomes a body of its own, named
        ``payload``, coasting from the stack's centre-of-mass motion; returns its name."""
        return self._craft.deploy_payload()

    # --- predictions (vacuum two-body: rocketsim.flight.impact) ------------------
    @property
    def impact(self):
        """Where the coasting path meets the ground (the WGS84 ellipsoid) on the vacuum
        Kepler conic of the estimated state: an :class:`~rocketsim.flight.impact.Impact`
        (``time`` s from now, ``latitude``, ``longitude`` rad, ``position`` ECI m,
        ``speed`` m/s), or None for a path that clears the ground. No drag, no J2."""
        view = self._view()
        if "impact" not in self._nav.readings:
            body = self._craft
            if body.central != "earth":
                raise ValueError("impact predictions are for Earth (the WGS84 ellipsoid) only")
            self._nav.readings["impact"] = predict_impact(view.position, view.velocity, self._craft.time, body.mu)
        return self._nav.readings["impact"]

    @property
    def impact_point(self) -> tuple[float, float] | None:
        """(geodetic latitude, longitude) of the predicted impact, rad; None if none."""
        impact = self.impact
        return None if impact is None else (impact.latitude, impact.longitude)

    @property
    def time_to_impact(self) -> float:
        """Seconds to the predicted impact (inf on a path that clears the ground)."""
        impact = self.impact
        return math.inf if impact is None else impact.time

    # --- engines ------------------------------------------------------------
    def _propulsion(self):
        body = self._craft
        if body.vehicle is None:
            raise ValueError(f"{body.name} has no engines (a rigid_body vehicle)")
        if self._engines is None or self._engines.model is not body.vehicle:
            self._engines = Propulsion(body.vehicle)
        return self._engines

    def ignite(self, which=None) -> list[str]:
        """Command ignition of the engines and solid motors of the lowest stage that has any
        (``which=None``: the stage flying now, never the stages stacked above it), or of an
        engine, group, stage or motor by name (``"second stage"``, ``"Merlin 1D ring"``,
        ``"booster/Merlin 1D ring/3"``, ``"sustainer/K1000T"``), an engine by index, or a
        list of those. An engine's thrust follows after its ignition dead time and spool-up;
        a solid motor's curve starts now. Returns the engines that accepted (not already on,
        propellant left, an ignition left) and the motors lit (``ignition: program`` in the
        vehicle file, not lit yet: a motor lights once)."""
        which = arguments.engines("fc.ignite", which)
        propulsion = self._propulsion()
        chosen, motors = propulsion.choose(propulsion.lowest_stage() if which is None else which)
        names = propulsion.ignite(self._craft.y, chosen)
        motors = propulsion.light(self._craft.time, motors)
        if names or motors:
            self._craft.event("ignition", {"engines": names, **({"motors": motors} if motors else {})})
        return names + motors

    def shutdown(self, which=None) -> list[str]:
        """Command engines off (the tail-off follows); returns the engines that were on.
        ``ValueError`` if it names solid motors and no engine: a solid motor cannot be shut
        down."""
        which = arguments.engines("fc.shutdown", which)
        names = self._propulsion().shutdown(self._craft.y, which)
        if names:
            self._craft.event("shutdown", {"engines": names})
        return names

    def throttle(self, value: float, which=None) -> None:
        """Command a throttle (0-1 of vacuum thrust, clipped to each engine's range and
        reached at its slew rate)."""
        value, which = arguments.number("fc.throttle", "value", value), arguments.engines("fc.throttle", which)
        self._propulsion().throttle(self._craft.time, value, which)

    def limit_q(self, start: float | None, end: float | None = None, which=None) -> None:
        """Throttle back through max-Q in compiled code: from the next step on, at every
        step's start, each engine is commanded the throttle last given with
        :meth:`throttle` times ``(end - q) / (end - start)`` clipped to 0..1 (full below
        ``start`` Pa of dynamic pressure, zero at ``end``), then clipped to its range and
        slewed to, without waking the program. ``fc.limit_q(None)`` removes the law and
        commands the last throttle again. Example: ``fc.limit_q(33e3, 49.5e3)``."""
        which = arguments.engines("fc.limit_q", which)
        if start is None:
            if end is not None:
                raise ValueError("fc.limit_q(None) takes no end; it removes the law")
            start = end = math.nan
        else:
            start = arguments.number("fc.limit_q", "start", start, 0.0)
            if end is None:
                raise ValueError("fc.limit_q() needs an end (Pa), the dynamic pressure of zero throttle")
            end = arguments.number("fc.limit_q", "end", end, 0.0)
            if not end > start:
                raise ValueError(f"fc.limit_q(): end must be above start, got {start!r} .. {end!r}")
        self._propulsion().limit_q(self._craft.time, start, end, which)

    @property
    def engines(self) -> list[dict]:
        """Each engine now: name, on, spool, throttle, throttle_range, gimbal_rad, thrust_N,
        mass_flow_kg_s, ignitions_left, separated (flow separation)."""
        body = self._craft
        return self._propulsion().states(body.y, self._craft.time, body.truth().air[1])

    @property
    def thrust(self) -> float:
        """Total thrust of all engines and solid motors now, N."""
        body = self._craft
        if body.vehicle is None:
            return 0.0
        propulsion = self._propulsion()
        return float(propulsion.thrusts(body.y, self._craft.time, body.truth().air[1]).sum()) \
            + propulsion.motor_thrust(self._craft.time)

    @property
    def propellant(self) -> dict[str, float]:
        """Propellant left per tank and solid motor (``stage/tank``, ``stage/motor`` -> kg),
        with the gauge's error."""
        if self._craft.vehicle is None:
            return {}
        levels = self._propulsion().propellant(self._craft.y)
        return {name: self._measured(f"propellant/{name}", lambda m=mass: m) for name, mass in levels.items()}

    # --- mass, gravity, orbit ---------------------------------------------------
    @property
    def mass(self) -> float:
        """Current mass, kg."""
        return self._craft.mass

    @property
    def gravity(self) -> float:
        """Magnitude of the central body's local gravitational field (point mass + J2), m/s^2."""
        return self._view().gravity

    @property
    def effective_gravity(self) -> float:
        """Gravity less the centrifugal term of the inertial horizontal speed, m/s^2.

        9.78 on the pad at the equator, nearly zero in orbit.
        """
        return self._view().effective_gravity

    effectiveGravity = effective_gravity   # the name programs of the original simulator use

    @property
    def acceleration(self) -> float:
        """What the accelerometers read, in g (``G0`` = 9.80665 m/s^2): the magnitude of the
        sensed acceleration ``|dv/dt - g|``, every force but gravity per unit mass (thrust,
        air, RCS, the ground's push; :mod:`rocketsim.flight.accelerometer`). About 1 g
        standing on the pad once the legs carry the weight (a vehicle starts with its legs
        just touching: 0 g at T+0, settled within about a second), 0 coasting in vacuum;
        with the accelerometers' error (0.1 %).
        Example: ``fc.throttle(0.7) if fc.acceleration > 4.5 else None``."""
        def truth():
            body = self._craft
            arrays = None if body.vehicle is None else body.vehicle.arrays
            a = sensed_acceleration(body.t, body.y, body.p, arrays, nbody_flag(body.p))
            return math.sqrt(a @ a) / G0
        return self._measured("acceleration", truth)

    @property
    def heating(self) -> float:
        """Convective heating at the nose, W/m^2: the cold-wall stagnation-point heat flux
        of Sutton-Graves, ``k sqrt(rho / r_n) v^3`` (:func:`rocketsim.vehicle.heating.sutton_graves`,
        ``k`` of the central body's air), from the air density and airspeed the program
        reads (their errors included), on the heat shield's nose radius, or on a 1 m
        reference radius for a vehicle without a shield (the flux scales as
        ``1/sqrt(r_n)``). Zero out of the air. Example: ``fc.wait_until(lambda: fc.heating < 1135)``."""
        shield = self._craft.heat_shield
        return float(sutton_graves(self.air_density, self.airspeed,
                                   1.0 if shield is None else shield.nose_radius,
                                   sutton_graves_constant(self._craft.mu)))

    @property
    def shield_temperature(self) -> float:
        """The lumped heat shield's temperature, K, as the checks integrate it after every
        step (nan for a vehicle without a heat shield)."""
        return self._craft.shield_temperature

    @property
    def orbit(self) -> Elements:
        """Osculating orbital elements about the central body (ECI axes)."""
        return self._view().orbit

    @property
    def apoapsis(self) -> float:
        """Apoapsis altitude above the central body's equatorial radius, m (inf if unbound)."""
        return self._view().orbit.apoapsis - float(self._craft.p[P_RADIUS])

    @property
    def periapsis(self) -> float:
        """Periapsis altitude above the central body's equatorial radius, m."""
        return self._view().orbit.periapsis - float(self._craft.p[P_RADIUS])

    @property
    def inclination(self) -> float:
        return self._view().orbit.i

    @property
    def eccentricity(self) -> float:
        return self._view().orbit.e

    @property
    def period(self) -> float:
        """Orbital period, s (inf if unbound)."""
        return self._view().orbit.period

    @property
    def central_body(self) -> str:
        """The body the frame, gravity and orbit are about: "earth", or after a
        sphere-of-influence handover (``gravity: n-body``) "moon", "mars" or "sun"."""
        return self._craft.central

    def body_state(self, name: str, at: float | None = None) -> tuple[np.ndarray, np.ndarray]:
        """Position (m) and velocity (m/s) of ``name`` ("sun", "earth", "moon", "mars")
        relative to the central body, in the frame's axes, at mission time ``at`` (s;
        default now): the simulator's ephemeris. Example: ``r_moon, v_moon = fc.body_state("moon")``."""
        name = arguments.choice("fc.body_state", "name", name, BODIES)
        at = None if at is None else arguments.number("fc.body_state", "at", at, -MAX_DURATION, MAX_DURATION)
        return self._craft.body_state(name, at)

    def predict(self, seconds: float, delta_v=None, periapsis: bool = False):
        """Where the coast leads: ``(time, position, velocity)`` ``seconds`` from now
        (mission time s, m, m/s, frame axes) after an impulsive ``delta_v`` (m/s) if
        given, in the full field (DOP853); with ``periapsis`` it stops at the next
        periapsis about the central body if that comes first. Computed from the
        truth, not the navigation estimate. Example:
        ``t, r, v = fc.predict(86400, periapsis=True)``."""
        seconds = arguments.duration("fc.predict", seconds)
        delta_v = None if delta_v is None else arguments.velocity("fc.predict", "delta_v", delta_v)
        periapsis = arguments.flag("fc.predict", "periapsis", periapsis)
        if "scipy.integrate" not in sys.modules:    # its first import, ~0.15 s, is not the program's time
            from rocketsim.flight.cpu_budget import not_counted
            with not_counted():     # (which gives the step its whole budget again: only then)
                import scipy.integrate  # noqa: F401
        return self._craft.predict(seconds, delta_v, periapsis)

    @property
    def time_to_apoapsis(self) -> float:
        """Time to the next apoapsis, s (nan if unbound)."""
        return self._view().time_to_apoapsis

