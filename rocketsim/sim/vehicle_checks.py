"""Once-per-step checks of a vehicle with aerodynamics: breakup, heat shield, touchdown.

The world calls :meth:`VehicleChecks.after_step` after every step of a body
that has an ``aero:`` section (and steps such a body one step at a time while
it is in the air's reach or near the ground, so nothing is missed inside a
batch). Each check is a pure function of the state (:mod:`rocketsim.vehicle.limits`,
:mod:`rocketsim.vehicle.heating`, :mod:`rocketsim.vehicle.contact`); this
class holds only what must persist between steps: the heat shield's
temperature and whether touchdown has been reported.

Events (figures in SI units, degrees where named):

* ``breakup``: ``cause`` ("bending" or "axial load"), ``q_alpha_Pa_deg``,
  ``dynamic_pressure_Pa``, ``angle_of_attack_deg``, ``axial_load_g``; the body
  stops flying;
* ``heat shield failure``: ``shield_temperature_K``, ``heat_flux_W_m2``; the body stops flying;
* ``touchdown``: ``vertical_speed_m_s`` (negative: down), ``horizontal_speed_m_s``,
  ``tilt_deg`` (body x from the local vertical), ``distance_to_target_m`` (horizontal,
  from the centre of mass to the mission's target pad, else the launch site), and
  about Earth ``latitude_deg``, ``longitude_deg`` (geodetic, WGS84) of the centre of mass;
* a first contact faster than :data:`CRASH_SPEED` (10 m/s down) is a crash: the world
  records an ``impact`` with those figures instead and the body stops flying;
* ``tip-over``: the touchdown figures (speeds, tilt, distance, where) at the step where
  a body that has touched down, still on the ground, leans past the tilt at which its
  centre of mass leaves the footprint of its feet
  (:func:`~rocketsim.vehicle.contact.tip_over_angle`): it is falling over, and stops
  flying (a landing that ends on its side is lost, however slow);
* a vehicle with parachutes adds the landing point ``latitude_deg``, ``longitude_deg``
  and the ``descent_time_s`` (from apogee) and ``drift_time_s`` (from the first
  deployment) to its touchdown; one that touches down under a deployed parachute is
  recovered: its flight ends there (on any of its contact points: on its side too).
"""

from __future__ import annotations

import math

import numpy as np

from rocketsim.jit import Entries, compile_beside
from rocketsim.atmosphere.table import TOP
from rocketsim.bodies.orientation import BODIES as ORIENTED, spin_rate
from rocketsim.constants import (AIR_CP, CO2_CP, DEG, G0, HEAT_SHIELD_LIMIT, MARS_MU,
                                STRUCTURE_AXIAL_LIMIT_G, STRUCTURE_Q_ALPHA_LIMIT)
from rocketsim.dynamics.derivative import held_derivative
from rocketsim.dynamics.central import WATCH_RADIUS
from rocketsim.dynamics.third_bodies import FIELD_CENTER, field_of, nbody_flag
from rocketsim.ephemeris.solar_system import BODIES
from rocketsim.layout import P_RADIUS, Q, R, V
from rocketsim.flight.conditions import NO_CONDITION
from rocketsim.flight.navigation import ANSWER, STATE, hand_over_buffer, tanks
from rocketsim.flight.sensors import NO_ERRORS
from rocketsim.flight.readings import StateView
from rocketsim.frames.earth_fixed import eci_to_ecef
from rocketsim.frames.quaternion import quat_rotate
from rocketsim.stepping import quiet, runs
from rocketsim.stepping.checked_step import advance_checked, step_figures
from rocketsim.vehicle.aero import A_REACH
from rocketsim.vehicle.contact import axis_up, contact_heights, footprint, tip_over_angle
from rocketsim.vehicle.heating import advance_shield, sutton_graves, sutton_graves_constant
from rocketsim.vehicle.parachutes import CH_DEPLOYED
from rocketsim.vehicle.limits import breakup

AIRBORNE_CLEARANCE = 1.0       # m: lowest contact point this high = in the air (a bounce is not a new flight)
# m/s down at the first contact: beyond this no legs or shock absorber survive (a Falcon 9
# booster lands at 1-2 m/s, an Apollo capsule splashed down at ~9 m/s under its parachutes);
# the body ends in an impact instead of a touchdown (the contact springs would bounce it back)
CRASH_SPEED = 10.0
TIP_MARGIN = 0.5 * DEG       # rad: the compiled runs hand a landed body to Python this far short of tipping
# what advance_checked reads when the autopilot does not steer in its call (unused)
_NO_STEERING = (np.full(6, math.nan), False)
# what a compiled run that asks nothing is given to ask with (unused)
_ASKS_NOBODY = (runs.NOBODY, hand_over_buffer(0))


def _advance_arguments(body, k0: int, h: float, n: int, steering: tuple | None) -> tuple:
    """The arguments of :func:`advance_checked` for :meth:`VehicleChecks.advance`'s call."""
    steer = steering is not None
    code, fins = steering if steer else _NO_STEERING
    errors, j, _ = estimate_errors(body, k0) if steer else (NO_ERRORS, 0, 0)
    return body.y, k0, h, n, body.p, body.vehicle.arrays, steer, code, fins, errors, j, nbody_flag(body.p)


def estimate_errors(body, k: int) -> tuple[np.ndarray, int, int]:
    """``(errors, j, gauges)``: what a compiled step or run reads of the navigation estimate
    of the staged vehicle ``body`` from step ``k`` on: its sensors' errors
    (:meth:`rocketsim.flight.sensors.Sensors.run_errors`, with the gauges of its tanks;
    :data:`~rocketsim.flight.sensors.NO_ERRORS` for the truth), the row of step ``k`` and
    the state slot of its first tank."""
    sensors = body.sensors
    if sensors is None or sensors.perfect:
        return NO_ERRORS, 0, 0
    errors, first = sensors.run_errors(k, tanks(body.vehicle))
    return errors, k - first, body.vehicle.tanks.start


class VehicleChecks:
    """Per-body state of the checks; ``pad_ecef`` the target pad (Earth-fixed, m) or None;
    ``limits`` the vehicle file's ``aero.limits`` (None: the defaults)."""

    def __init__(self, heat_shield=None, pad_ecef=None, limits=None):
        self.shield = heat_shield
        self.limits = (STRUCTURE_Q_ALPHA_LIMIT, STRUCTURE_AXIAL_LIMIT_G)
        if limits is not None:
            self.limits = (limits.q_alpha or STRUCTURE_Q_ALPHA_LIMIT,
                           limits.axial_load / G0 if limits.axial_load else STRUCTURE_AXIAL_LIMIT_G)
        self.temperature = heat_shield.initial_temperature if heat_shield is not None else math.nan
        self.pad = None if pad_ecef is None else np.asarray(pad_ecef, dtype=float)
        self.touched_down = True     # a vehicle only touches down after being in the air
        self.landed = False         # a touchdown has been reported
        self.previous = None        # (t, y) before the last step, for the touchdown figures
        self._arrays = self._in_flight = self._watched = self._feet = None
        self._kernels = Entries()   # step_figures bound to the vehicle's arrays
        self._figures = None        # (state, step_figures of it) from the last advance

    def every_step(self, body) -> bool:
        """True while the body must be stepped one step at a time (in the air or near the ground)."""
        self._bind(body.vehicle.arrays)
        x, y, z = body.y[R:R + 3].tolist()          # plain floats: a few times faster than r @ r
        return math.sqrt(x * x + y * y + z * z) - body.p[P_RADIUS] < self._watched

    def _bind(self, arrays) -> None:
        """Derive what the checks need from a vehicle's arrays, once per model (a new
        model at staging): its flight loads without contact, and the radius (m, over
        the equatorial radius) below which the air can reach it."""
        if self._arrays is not arrays:
            self._arrays = arrays
            self._in_flight = arrays._replace(aero=arrays.aero._replace(contact=arrays.aero.contact[:0]))
            self._watched = TOP + float(arrays.aero.ref[A_REACH])
            self._feet = None       # its footprint, found at the first touchdown (scipy's hull)

    def advance(self, body, k0: int, h: float, n: int, steering: tuple | None = None) -> tuple[np.ndarray, int]:
        """Advance ``body`` like :func:`rocketsim.dynamics.rk4.advance` (up to ``n`` steps
        of ``h`` seconds from step ``k0``; returns ``(y, steps taken)``) and compute the
        checks' figures at the new state in the same compiled call
        (:func:`~rocketsim.stepping.checked_step.advance_checked`: the vehicle's arrays
        are unboxed once, not two or three times); :meth:`after_step`
        reads them if the body's state is still that one. ``steering``: the autopilot's
        step to run first in that call, ``(command code, fins)`` from
        :meth:`rocketsim.flight.fc.FlightComputer.autopilot`, or None."""
        arrays = body.vehicle.arrays
        y, taken, near, figures = body.kernels.call(advance_checked, arrays,
                                                    *_advance_arguments(body, k0, h, n, steering))
        self._figures = None if near else (y, figures)
        return y, taken

    def fly_run(self, body, k0: int, h: float, n: int, steering: tuple | None, events,
                condition: np.ndarray, samples: tuple, between=None) -> tuple[np.ndarray, int, int, int]:
        """Fly ``body`` up to ``n`` steps of ``h`` seconds from step ``k0`` in one compiled
        call, returning after the first step the Python side may have something to do
        with (:func:`rocketsim.stepping.runs.fly_run`); returns ``(y, steps taken, reason,
        samples computed)``. ``samples``: ``(every, rows, record, sampler)``, the
        telemetry samples the run computes (see :func:`~rocketsim.stepping.runs.fly_run`).
        The checks' state is left as :meth:`after_step` would have left it before the
        last step (the shield's temperature, the contact flag, the state before the
        step), the figures of the last step for :meth:`after_step` to read, and the
        flight events ``events`` (:class:`~rocketsim.sim.flight_events.FlightEvents`)
        told of a new dynamic-pressure peak. ``steering`` as in :meth:`advance`, run
        before every step; ``condition``: the program's compiled condition
        (:mod:`rocketsim.flight.conditions`; no rows: none).

        ``between(k)``: asked after each step ``k`` but the last with nothing for the
        Python side, the body's state, time and checks as after it (a program's condition
        read in Python; the body's state is the one the run handed over, in its buffer with
        the step's navigation estimate, :attr:`rocketsim.sim.body.Body.handed`), whether
        the run ends there: then the reason is :data:`~rocketsim.stepping.runs.QUIET`, the
        state returned is the body's as the condition left it (a command it gave, an
        engine lit, changes it) and the checks' state is as :meth:`after_step` leaves it
        after that step."""
        if between is None:
            arguments, carry = self._run_arguments(body, k0, h, n, steering, events, condition, samples)
            y, before, taken, figures, reason, y_peak, filled = body.kernels.call(
                runs.fly_run, body.vehicle.arrays, *arguments)
        else:
            handed = hand_over_buffer(len(body.y))
            state, shielded = handed[STATE:], self.shield is not None
            given = (state, handed)

            def question(k: int) -> None:
                body.y, body.handed, body.t = state, given, k * h
                if shielded:
                    self.temperature = float(carry[quiet.CARRY_TEMPERATURE])
                handed[ANSWER] = between(k)

            with runs.asking(question) as asking:
                arguments, carry = self._run_arguments(body, k0, h, n, steering, events, condition, samples,
                                                       (asking.ask, handed))
                y, before, taken, figures, reason, y_peak, filled = body.kernels.call(
                    runs.fly_run, body.vehicle.arrays, *arguments)
            if reason == runs.QUIET:        # the state as the condition left it (a command may change it)
                y = state.copy()
        self.temperature = float(carry[quiet.CARRY_TEMPERATURE])
        self.touched_down = bool(carry[quiet.CARRY_TOUCHED] > 0.5)
        if reason == runs.QUIET:
            self.previous, self._figures = ((k0 + taken) * h, y.copy()), None
        else:
            if taken > 1:
                self.previous = ((k0 + taken - 1) * h, before.copy())
            self._figures = (y, figures)
        if carry[quiet.CARRY_PEAK_STEP] > 0.0:
            events.peak_at((k0 + int(carry[quiet.CARRY_PEAK_STEP])) * h, y_peak)
        return y, taken, reason, filled

    def compile_beside(self, body, h: float, samples: tuple | None) -> None:
        """On a cold cache, queue the kernels of this body's one-step advance (:meth:`advance`)
        and, given ``samples`` (as :meth:`fly_run`'s), of its compiled runs for a second
        process to compile (:func:`rocketsim.jit.compile_beside`): their types are the
        body's from its first step to its staging."""
        if samples is not None:
            compile_beside(runs.fly_run, self._run_arguments(body, 0, h, 1, None, body.watch, NO_CONDITION,
                                                             samples)[0])
        compile_beside(advance_checked, _advance_arguments(body, 0, h, 1, None))

    def _run_arguments(self, body, k0: int, h: float, n: int, steering: tuple | None, events,
                       condition: np.ndarray, samples: tuple, asks: tuple | None = None) -> tuple[tuple, np.ndarray]:
        """``(arguments of runs.fly_run, its carry)`` for :meth:`fly_run`'s call; ``asks``:
        ``(ask, buffer)``, what the run calls after each step and the buffer it hands the
        step over in (None: it asks nothing)."""
        arrays = body.vehicle.arrays
        self._bind(arrays)
        steer = steering is not None
        code, fins = steering if steer else _NO_STEERING
        watch = np.full(quiet.N_WATCH, math.inf)
        watch[quiet.WATCH_Q_ALPHA], watch[quiet.WATCH_AXIAL] = self.limits
        watch[quiet.WATCH_SHIELD] = 0.0
        if self.shield is not None:
            s = self.shield
            watch[quiet.WATCH_SHIELD:quiet.WATCH_HEAT_CAPACITY + 1] = (
                1.0, s.nose_radius, sutton_graves_constant(body.mu), _heat_capacity_of_air(body.mu),
                s.emissivity, s.area, s.mass * s.specific_heat)
        watch[quiet.WATCH_HEAT_LIMIT] = HEAT_SHIELD_LIMIT
        watch[quiet.WATCH_REACH] = self._watched
        watch[quiet.WATCH_CLEARANCE] = AIRBORNE_CLEARANCE
        watch[quiet.WATCH_TIP] = self._tip_watch(body)
        watch[quiet.WATCH_MU] = body.mu
        fp = field_of(body.p)
        if fp is not None:
            watch[quiet.WATCH_SOI] = WATCH_RADIUS[BODIES[int(fp[FIELD_CENTER])]]
        peak = events.run_watch(watch)
        carry = np.array((self.temperature, float(self.touched_down), peak, 0.0))
        return (body.y, k0, h, n, body.p, arrays, self._in_flight, steer, code, fins, *estimate_errors(body, k0),
                watch, carry, condition, asks is not None, *(asks or _ASKS_NOBODY), *samples, nbody_flag(body.p)), carry

    def after_step(self, world, body, h: float) -> dict | None:
        """Run the checks on the body's new state (after a step of ``h`` seconds). Returns
        the touchdown figures of a first contact faster than :data:`CRASH_SPEED` (a
        crash: the world ends the body with an impact), else None."""
        arrays = body.vehicle.arrays
        self._bind(arrays)
        figures, self._figures = self._figures, None
        if figures is not None and figures[0] is body.y:
            rho, air_temperature, speed, q, alpha, axial, lowest = figures[1]
        else:
            rho, air_temperature, speed, q, alpha, axial, lowest = self._kernels.call(
                step_figures, arrays, body.t, body.y, body.p, self._in_flight, arrays.aero.contact,
                nbody_flag(body.p))
        figures = breakup(q, alpha, axial, *self.limits)
        if figures is not None:
            world.event(body, "breakup", figures)
            body.flying = False
        if body.flying and rho > 0.0 and self.shield is not None:
            self._heat(world, body, rho, speed, air_temperature, h)
        if lowest > AIRBORNE_CLEARANCE:
            self.touched_down = False       # in the air: the next contact is a touchdown
        elif self.landed and body.flying and self._tilted(body):
            figures = self.touchdown_figures(body)
            if figures["tilt_deg"] * DEG > self._tip_over_angle(body):
                world.end_flight(body, "tip-over", figures)     # its centre of mass past its feet
                return None
        elif body.flying and not self.touched_down and self.previous is not None and (
                lowest <= 0.0 or self._reached_ground(body, h)):
            self.touched_down = True
            figures = self.touchdown_figures(body)
            if body.vehicle.parachutes and body.watch is not None:
                figures.update(body.watch.recovery())
            if figures["vertical_speed_m_s"] < -CRASH_SPEED:
                return figures
            world.event(body, "touchdown", figures)
            self.landed = True
            if np.any(~np.isnan(body.vehicle.arrays.chute[:, CH_DEPLOYED])):
                # down under a canopy: recovered, the flight of this body ends here
                body.flying = False
                if world.telemetry is not None:
                    world.record(body)
        self.previous = (body.t, body.y.copy())
        return None

    def _tip_over_angle(self, body) -> float:
        """:func:`~rocketsim.vehicle.contact.tip_over_angle` of the body now (rad)."""
        self._bind(body.vehicle.arrays)
        if self._feet is None:
            self._feet = footprint(self._arrays.aero.contact)
        return tip_over_angle(self._feet, body.vehicle.mass_properties(body.y)[1])

    def _tip_watch(self, body) -> float:
        """Cosine of the tilt from the geocentric radial past which a landed body may be
        tipping over: :meth:`_tip_over_angle` less :data:`TIP_MARGIN` (the radial and the
        ellipsoid's normal, which the tilt is measured from, differ by up to 0.19 deg);
        ``-inf`` before a touchdown."""
        return math.cos(max(self._tip_over_angle(body) - TIP_MARGIN, 0.0)) if self.landed else -math.inf

    def _tilted(self, body) -> bool:
        """Whether the body's x axis is tilted from the geocentric radial past :meth:`_tip_watch`."""
        return axis_up(body.y) < self._tip_watch(body)

    def _heat(self, world, body, rho, speed, air_temperature, h) -> None:
        s = self.shield
        k = sutton_graves_constant(body.mu)
        cp = _heat_capacity_of_air(body.mu)
        self.temperature = advance_shield(self.temperature, h, rho, speed, air_temperature, s.nose_radius,
                                          k, cp, s.emissivity, s.area, s.mass * s.specific_heat)
        if self.temperature > HEAT_SHIELD_LIMIT:
            world.event(body, "heat shield failure", {
                "shield_temperature_K": self.temperature,
                "heat_flux_W_m2": sutton_graves(rho, speed, s.nose_radius, k)})
            body.flying = False

    def _approach(self, body) -> tuple[np.ndarray, np.ndarray, float, float]:
        """``(up, surface velocity, vertical acceleration m/s^2, height m of the lowest contact
        point)`` of the state before the last step (the derivative's acceleration: gravity,
        thrust, drag)."""
        t0, y0 = self.previous
        up, surface = ground_motion(body.central, t0, y0)
        dy = np.zeros_like(y0)
        # derivative() itself: it is typed inline in its callers, so a call from Python would
        # compile a kernel of its own; the held derivative it calls is compiled for the steps
        held_derivative(t0, y0, body.p, dy, body.vehicle.arrays, t0, y0, nbody_flag(body.p))
        return up, surface, float(dy[V:V + 3] @ up), float(contact_heights(y0, body.p, body.vehicle).min())

    def _reached_ground(self, body, h: float) -> bool:
        """True if the lowest contact point, flying on from the state before the last step
        of ``h`` seconds, would have gone below the ground within it: a first contact whose
        springs threw the body back up inside the step (a light body on stiff springs)."""
        up, surface, vertical_acceleration, lowest = self._approach(body)
        return lowest + float(surface @ up) * h + 0.5 * vertical_acceleration * h * h <= 0.0

    def touchdown_figures(self, body) -> dict:
        """Vertical and horizontal speed over the ground, tilt, distance to the pad and
        (about Earth) where, at the instant the first contact point reached the ground.

        The step that touched down has already compressed the legs (by up to
        ``|v| h``), so the figures come from the state before that step, carried
        to the ground at the vertical acceleration the derivative gave there
        (gravity, thrust, drag): ``v_td = -sqrt(v^2 - 2 a h_lowest)``. The ground
        is the central body's (:func:`ground_motion`); the pad is on Earth.
        """
        t0, y0 = self.previous if self.previous is not None else (body.t, body.y)
        up, surface = ground_motion(body.central, t0, y0)
        vertical = float(surface @ up)
        across = surface - vertical * up
        if self.previous is not None:
            _, _, vertical_acceleration, lowest = self._approach(body)
            vertical = -math.sqrt(max(vertical ** 2 - 2.0 * vertical_acceleration * max(lowest, 0.0), 0.0))
        axis = quat_rotate(y0[Q:Q + 4], np.array([1.0, 0.0, 0.0]))
        tilt = math.acos(max(-1.0, min(1.0, float(axis @ up))))
        figures = {"vertical_speed_m_s": vertical,
                   "horizontal_speed_m_s": math.sqrt(across @ across),
                   "tilt_deg": tilt / DEG}
        if body.central == "earth":
            lat, lon, _ = StateView.of_state(t0, y0).geodetic
            figures.update(latitude_deg=lat / DEG, longitude_deg=lon / DEG)
        if self.pad is not None and body.central == "earth":
            offset = eci_to_ecef(y0[R:R + 3], t0) - self.pad
            up_ecef = eci_to_ecef(up, t0)
            figures["distance_to_target_m"] = float(np.linalg.norm(offset - (offset @ up_ecef) * up_ecef))
        return figures


def _heat_capacity_of_air(mu: float) -> float:
    """J/(kg K) of the air about the central body of ``mu``: the CO2 of Mars's, else air."""
    return CO2_CP if mu == MARS_MU else AIR_CP


def ground_motion(central: str, t: float, y) -> tuple[np.ndarray, np.ndarray]:
    """``(up, surface velocity)`` of state ``y`` at mission time ``t`` (s) over the ground
    of ``central``, in its frame's axes: about Earth the readings' (the WGS84 normal,
    the velocity relative to the ground turning at Earth's rate); about the Moon or
    Mars the radial direction (the contact heights are measured along the radius)
    and the velocity relative to the ground turning at the body's IAU rate about its
    pole, the frame's z (:mod:`rocketsim.dynamics.soi`); about the Sun no turn."""
    if central == "earth":
        view = StateView.of_state(t, y)
        return view.enu[2], view.surface_velocity
    r = y[R:R + 3]
    spin = spin_rate(central) if central in ORIENTED else 0.0
    return r / math.sqrt(r @ r), y[V:V + 3] - spin * np.array((-r[1], r[0], 0.0))
