"""The flight summary: each body's events, final state, orbit and touchdown.

Figures in SI units (m, s, m/s), angles in degrees where a name says so; the
orbit is the osculating one of the body's last state message
(:func:`rocketsim.sim.sampling.orbit`), about its ``central_body`` (``earth``,
``moon``, ``mars``), which the orbit events name too. ``world`` is a
:class:`~rocketsim.sim.world.World`.
"""

from __future__ import annotations

import numpy as np

from rocketsim.constants import DEG
from rocketsim.sim import sampling

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
        landed = [e for e in body.events if e["name"] == "touchdown"]
        if landed:      # the first contact's figures (speeds m/s, tilt deg, distance m)
            bodies[body.name]["touchdown"] = {k: v for k, v in landed[0].items() if k != "name"}
    return {"epoch_utc": world.epoch.utc.isoformat(), "step_s": world.h,
            "mission_time_s": max(b.t for b in world.bodies), "bodies": bodies}
