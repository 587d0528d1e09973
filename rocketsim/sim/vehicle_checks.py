"""Once-per-step checks of a vehicle with aerodynamics: breakup, heat shield, touchdown.

The world calls :meth:`VehicleChecks.after_step` after every step of a body
that has an ``aero:`` section (and steps such a body one step at a time while
it is in the air's reach or near the ground, so nothing is missed inside a
batch). Each check is a pure function of the state (:mod:`rocketsim.vehicle.limits`,
:mod:`rocketsim.vehicle.heating`, :mod:`rocketsim.vehicle.contact`); this
class holds only what must persist between steps: the heat shield's
temperature and whether touchdown has been reported.

Events (figures in SI units, degrees where named):

* ``breakup``: ``cause`` ("bending" or "axial load"), ``q_alpha_pa_deg``,
  ``dynamic_pressure_pa``, ``angle_of_attack_deg``, ``axial_load_g``; the body
  stops flying;
* ``heat shield failure``: ``temperature_k``, ``heat_flux_w_m2``; the body stops flying;
* ``touchdown``: ``vertical_speed_m_s`` (negative: down), ``horizontal_speed_m_s``,
  ``tilt_deg`` (body x from the local vertical), ``distance_to_pad_m`` (horizontal,
  from the centre of mass to the pad).
"""

from __future__ import annotations

import math

import numpy as np

from rocketsim.atmosphere.table import TOP
from rocketsim.bodies.gravity import point_mass_j2
from rocketsim.constants import (AIR_CP, CO2_CP, DEG, HEAT_SHIELD_LIMIT, MARS_MU,
                                 SUTTON_GRAVES_EARTH, SUTTON_GRAVES_MARS)
from rocketsim.dynamics.derivative import derivative
from rocketsim.dynamics.state import P_J2, P_MU, P_POLAR_RADIUS, P_RADIUS, Q, R, V, W
from rocketsim.flight.readings import StateView
from rocketsim.frames.earth_fixed import eci_to_ecef
from rocketsim.frames.quaternion import quat_rotate
from rocketsim.vehicle.aero import A_REACH
from rocketsim.vehicle.contact import K_X, K_Y, K_Z, point_height
from rocketsim.vehicle.heating import advance_shield, sutton_graves
from rocketsim.vehicle.limits import breakup


class VehicleChecks:
    """Per-body state of the checks; ``pad_ecef`` the target pad (Earth-fixed, m) or None."""

    def __init__(self, heat_shield=None, pad_ecef=None):
        self.shield = heat_shield
        self.temperature = heat_shield.initial_temperature if heat_shield is not None else math.nan
        self.pad = None if pad_ecef is None else np.asarray(pad_ecef, dtype=float)
        self.touched_down = False
        self.previous = None        # (t, y) before the last step, for the touchdown figures

    def every_step(self, body) -> bool:
        """True while the body must be stepped one step at a time (in the air or near the ground)."""
        reach = body.vehicle.arrays.aero.ref[A_REACH]
        return float(np.linalg.norm(body.position)) - body.p[P_RADIUS] < TOP + reach

    def after_step(self, world, body, h: float) -> None:
        """Run the checks on the body's new state (after a step of ``h`` seconds)."""
        view = body.view()
        rho, _, air_temperature, _, _, v_air = view.air
        if rho > 0.0:
            self._structure(world, body, view)
            if body.flying and self.shield is not None:
                self._heat(world, body, rho, float(np.linalg.norm(v_air)), air_temperature, h)
        if body.flying and not self.touched_down and self._touching(body):
            self.touched_down = True
            world.event(body, "touchdown", self.touchdown_figures(body, view))
        self.previous = (body.t, body.y.copy())

    # --- the checks ------------------------------------------------------------
    def _structure(self, world, body, view) -> None:
        # flight loads only: thrust, air and RCS. The legs are idealised stiff
        # springs (a real leg's stroke crushes); their impact is not the structure's.
        arrays = body.vehicle.arrays
        in_flight = arrays._replace(aero=arrays.aero._replace(contact=arrays.aero.contact[:0]))
        dy = np.zeros_like(body.y)
        derivative(body.t, body.y, body.p, dy, in_flight)
        x, y, z = body.position
        gravity = np.array(point_mass_j2(x, y, z, body.p[P_MU], body.p[P_RADIUS], body.p[P_J2]))
        sensed = dy[V:V + 3] - gravity
        axial = float(quat_rotate(body.attitude, np.array([1.0, 0.0, 0.0])) @ sensed)
        figures = breakup(view.dynamic_pressure, view.angle_of_attack, axial)
        if figures is not None:
            world.event(body, "breakup", figures)
            body.flying = False

    def _heat(self, world, body, rho, speed, air_temperature, h) -> None:
        s = self.shield
        mars = body.mu == MARS_MU
        k, cp = (SUTTON_GRAVES_MARS, CO2_CP) if mars else (SUTTON_GRAVES_EARTH, AIR_CP)
        self.temperature = advance_shield(self.temperature, h, rho, speed, air_temperature, s.nose_radius,
                                          k, cp, s.emissivity, s.area, s.mass * s.specific_heat)
        if self.temperature > HEAT_SHIELD_LIMIT:
            world.event(body, "heat shield failure", {
                "temperature_k": self.temperature,
                "heat_flux_w_m2": sutton_graves(rho, speed, s.nose_radius, k)})
            body.flying = False

    def _touching(self, body) -> bool:
        heights = contact_heights(body.y, body.p, body.vehicle)
        return heights.size > 0 and float(heights.min()) <= 0.0

    def touchdown_figures(self, body, view) -> dict:
        """Vertical and horizontal speed over the ground, tilt and distance to the pad, at
        the instant the first contact point reached the ground.

        The step that touched down has already compressed the legs (by up to
        ``|v| h``), so the figures come from the state before that step, carried
        to the ground at the vertical acceleration the derivative gave there
        (gravity, thrust, drag): ``v_td = -sqrt(v^2 - 2 a h_lowest)``.
        """
        if self.previous is not None:
            t0, y0 = self.previous
            before = StateView(t0, y0[R:R + 3].copy(), y0[V:V + 3].copy(), y0[Q:Q + 4].copy(),
                               y0[W:W + 3].copy(), body.atmosphere, body.mu)
            dy = np.zeros_like(y0)
            derivative(t0, y0, body.p, dy, body.vehicle.arrays)
            up = before.enu[2]
            lowest = max(float(contact_heights(y0, body.p, body.vehicle).min()), 0.0)
            vertical = -math.sqrt(max(before.vertical_speed ** 2 - 2.0 * float(dy[V:V + 3] @ up) * lowest, 0.0))
            view, attitude = before, y0[Q:Q + 4]
        else:
            up, vertical, attitude = view.enu[2], view.vertical_speed, body.attitude
        axis = quat_rotate(attitude, np.array([1.0, 0.0, 0.0]))
        tilt = math.acos(max(-1.0, min(1.0, float(axis @ up))))
        figures = {"vertical_speed_m_s": vertical,
                   "horizontal_speed_m_s": view.horizontal_speed,
                   "tilt_deg": tilt / DEG}
        if self.pad is not None:
            offset = eci_to_ecef(view.position, view.t) - self.pad
            up_ecef = eci_to_ecef(up, view.t)
            figures["distance_to_pad_m"] = float(np.linalg.norm(offset - (offset @ up_ecef) * up_ecef))
        return figures


def contact_heights(y, p, vehicle) -> np.ndarray:
    """Height (m) of each contact point of ``vehicle`` above the ellipsoid, along the radius."""
    a = vehicle.arrays.aero
    x_cm = vehicle.mass_properties(y)[1]
    out = np.empty(a.contact.shape[0])
    for i, row in enumerate(a.contact):
        offset = quat_rotate(y[Q:Q + 4], np.array([row[K_X] - x_cm, row[K_Y], row[K_Z]]))
        px, py, pz = y[R:R + 3] + offset
        out[i] = point_height(px, py, pz, p[P_RADIUS], p[P_POLAR_RADIUS])
    return out
