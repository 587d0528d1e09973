"""The flight summary: each body's events, final state, and what its flight was.

Figures in SI units (m, s, m/s), angles in degrees, each name with one meaning
(:mod:`rocketsim.telemetry.names`). Per body:

* ``events``: the body's events, each with its ``time_s`` and figures;
* ``final``: its last state: ``time_s``, ``position_m`` and ``velocity_m_s`` (the
  central body's inertial frame), ``latitude_deg``, ``longitude_deg``, ``altitude_m``
  (above the ellipsoid), ``inertial_speed_m_s`` and ``surface_speed_m_s`` (over the
  central body's turning ground); a staged body's adds the liquid propellant left in
  its tanks (``propellant_kg``) and the part of it above each stage's unusable reserve
  (``usable_propellant_kg``: what its engines could still burn, the margin a landing
  kept);
* ``orbit``, for a body in orbit at the end only (its osculating periapsis above the
  central body's equatorial radius: it does not come down): the elements of its last
  state (:func:`rocketsim.sim.sampling.orbit`) with units in their names and the
  ``central_body`` (``earth``, ``moon``, ``mars``, ``sun``) they are about;
* ``flight``, for a body that is not: what a suborbital flight is read by, from its
  telemetry samples in flight (:mod:`rocketsim.sim.sample_watch`; a separated stage's
  from its stack's, from the pad): the apogee above
  the ground and its time, the ground's height, the largest speed over the ground,
  Mach, dynamic pressure and sensed acceleration (in g), where it started; the rail
  exit (``off_rail``: time, speed, static margin) when it left a rail; and where and
  how it came down (``landing_kind`` touchdown or impact, its time, place, speed over
  the ground and ``drift_m``, from where it started, along the ground) when it did;
* ``touchdown``: the first ground contact's figures (a body that touched down).

``world`` is a :class:`~rocketsim.sim.world.World`.
"""

from __future__ import annotations

import math

import numpy as np

from rocketsim.constants import DEG
from rocketsim.frames.geodetic import geodetic_to_ecef
from rocketsim.sim import sampling
from rocketsim.vehicle.engines import S_RESERVE

_ORBIT_UNITS = {"semi_major_axis": "semi_major_axis_m", "periapsis_altitude": "periapsis_altitude_m",
                "apoapsis_altitude": "apoapsis_altitude_m", "period": "period_s"}


def summary(world) -> dict:
    """Events, final state and orbit or flight of each body of ``world``."""
    bodies = {}
    for body in world.bodies:
        lat, lon, height = world.where(body)
        record = {
            "events": body.events,
            "final": {
                "time_s": body.t,
                "position_m": body.position.tolist(),
                "velocity_m_s": body.velocity.tolist(),
                "latitude_deg": lat / DEG,
                "longitude_deg": lon / DEG,
                "altitude_m": height,
                "inertial_speed_m_s": float(np.linalg.norm(body.velocity)),
                "surface_speed_m_s": float(np.linalg.norm(body.view().surface_velocity)),
            },
        }
        orbit = sampling.orbit(body, world.gmst0)
        if in_orbit(orbit, body.flying):
            record["orbit"] = {**{_ORBIT_UNITS.get(k, k): v for k, v in orbit.items()},
                               "central_body": body.central}
        else:
            figures = world.sample_watch.figures(body.name) if world.sample_watch is not None else None
            record["flight"] = flight(body.events, figures)
        vehicle = body.vehicle
        if vehicle is not None and vehicle.n_tanks:
            left = vehicle.stage_propellant(body.y)
            record["final"].update(
                propellant_kg=float(left.sum()),
                usable_propellant_kg=float(np.maximum(left - vehicle.arrays.stage[:, S_RESERVE], 0.0).sum()))
        landed = [e for e in body.events if e["name"] == "touchdown"]
        if landed:      # the first contact's figures (speeds m/s, tilt deg, distance m)
            record["touchdown"] = {k: v for k, v in landed[0].items() if k != "name"}
        bodies[body.name] = record
    return {"epoch_utc": world.epoch.utc.isoformat(), "step_s": world.h,
            "mission_time_s": max(b.t for b in world.bodies), "bodies": bodies}


def in_orbit(orbit: dict, flying: bool) -> bool:
    """Whether a body with the osculating ``orbit`` (:func:`rocketsim.sim.sampling.orbit`'s
    fields) is in orbit: still flying, its periapsis above the central body's equatorial
    radius (a closed orbit or an escape that clears the body)."""
    return flying and orbit["periapsis_altitude"] > 0.0


def flight(events: list[dict], figures: dict | None) -> dict:
    """The ``flight`` part of a body's summary (see the module) from its ``events`` and its
    telemetry's flight ``figures`` (:meth:`rocketsim.sim.sample_watch.SampleWatch.figures`;
    None: flown without telemetry, the events' figures only)."""
    out = {} if figures is None else {k: v for k, v in figures.items() if not k.startswith("start_")}
    first = {}
    for event in events:
        first.setdefault(event["name"], event)
    rail = first.get("off_rail")
    if rail is not None:
        out.update(rail_exit_time_s=rail.get("at_s", rail["time_s"]),
                   rail_exit_surface_speed_m_s=rail["surface_speed_m_s"])
        if "stability_margin_cal" in rail:
            out["rail_exit_stability_margin_cal"] = rail["stability_margin_cal"]
    down = min((first[name] for name in ("touchdown", "impact") if name in first),
               key=lambda e: e["time_s"], default=None)
    if down is not None:
        speed = (down["surface_speed_m_s"] if down["name"] == "impact"
                 else math.hypot(down["vertical_speed_m_s"], down["horizontal_speed_m_s"]))
        out.update(landing_kind=down["name"], landing_time_s=down["time_s"], landing_surface_speed_m_s=speed)
        if "latitude_deg" in down:
            out.update(landing_latitude_deg=down["latitude_deg"], landing_longitude_deg=down["longitude_deg"])
            if figures is not None:
                out["drift_m"] = ground_distance(figures["start_latitude_deg"], figures["start_longitude_deg"],
                                                 down["latitude_deg"], down["longitude_deg"])
    return out


def ground_distance(lat0: float, lon0: float, lat1: float, lon1: float) -> float:
    """m from (``lat0``, ``lon0``) to (``lat1``, ``lon1``) (geodetic, deg, on WGS84) along
    the ground: their chord on the ellipsoid projected on the first point's horizontal,
    as the touchdown's distance to the pad is measured
    (:meth:`rocketsim.sim.vehicle_checks.VehicleChecks.touchdown_figures`); short of the
    geodesic by about ``d^2 / (6 R^2)`` of it: 4 mm at 10 km."""
    a = geodetic_to_ecef(lat0 * DEG, lon0 * DEG, 0.0)
    b = geodetic_to_ecef(lat1 * DEG, lon1 * DEG, 0.0)
    up = np.array([math.cos(lat0 * DEG) * math.cos(lon0 * DEG), math.cos(lat0 * DEG) * math.sin(lon0 * DEG),
                   math.sin(lat0 * DEG)])
    chord = b - a
    return float(np.linalg.norm(chord - (chord @ up) * up))
