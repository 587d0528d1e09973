"""The flight summary: each body's events, final state, orbit and touchdown.

Figures in SI units (m, s, m/s, kg), angles in degrees where a name says so; a
staged body's final state adds the liquid propellant left in its tanks
(``propellant_kg``) and the part of it above each stage's unusable reserve
(``usable_propellant_kg``: what its engines could still burn, the margin a
landing kept). The
orbit is the osculating one of the body's last state message
(:func:`rocketsim.sim.sampling.orbit`), about its ``central_body`` (``earth``,
``moon``, ``mars``), which the orbit events name too. ``world`` is a
:class:`~rocketsim.sim.world.World`.
"""

from __future__ import annotations

import numpy as np

from rocketsim.constants import DEG
from rocketsim.sim import sampling
from rocketsim.vehicle.engines import S_RESERVE

def summary(world) -> dict:
    """Events and final state of each body of ``world``."""
    bodies = {}
    for body in world.bodies:
        lat, lon, height = world.where(body)
        bodies[body.name] = {
            "events": body.events,
            "final": {
                "time_s": body.t,
                "position_m": body.position.tolist(),
                "velocity_m_s": body.velocity.tolist(),
                "latitude_deg": lat / DEG,
                "longitude_deg": lon / DEG,
                "altitude_m": height,
                "speed_m_s": float(np.linalg.norm(body.velocity)),
            },
            "orbit": {**sampling.orbit(body, world.gmst0), "central_body": body.central},
        }
        vehicle = body.vehicle
        if vehicle is not None and vehicle.n_tanks:
            left = vehicle.stage_propellant(body.y)
            bodies[body.name]["final"].update(
                propellant_kg=float(left.sum()),
                usable_propellant_kg=float(np.maximum(left - vehicle.arrays.stage[:, S_RESERVE], 0.0).sum()))
        landed = [e for e in body.events if e["name"] == "touchdown"]
        if landed:      # the first contact's figures (speeds m/s, tilt deg, distance m)
            bodies[body.name]["touchdown"] = {k: v for k, v in landed[0].items() if k != "name"}
    return {"epoch_utc": world.epoch.utc.isoformat(), "step_s": world.h,
            "mission_time_s": max(b.t for b in world.bodies), "bodies": bodies}
