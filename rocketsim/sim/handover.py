"""A body crossing into another sphere of influence is handed over to that body.

The frame is re-centred on the new central body with its IAU pole as ``z``
(:func:`rocketsim.dynamics.central.recentre`): position, velocity and attitude
are the same, seen from the new centre. The handover's instant is sampled in
both frames, and a staged vehicle flies in its new central body's air (Mars's
reference atmosphere about Mars, none about the Moon). Each function takes the
:class:`~rocketsim.sim.world.World` first.
"""

from __future__ import annotations

from rocketsim.dynamics.central import air_about, next_center, recentre
from rocketsim.layout import P_MU
from rocketsim.sim.body import Body

def watch_soi(world, body: Body) -> None:
    """Hand ``body`` over to the body whose sphere of influence it has crossed into."""
    new = next_center(body.y, body.p, body.t)
    if new is not None:
        hand_over(world, body, new)


def hand_over(world, body: Body, new: str) -> None:
    """Re-centre ``body`` on ``new`` now: a sample in the old frame, the
    ``soi_handover`` event (``from``, ``to``), a sample in the new one."""
    old = body.central
    if world.telemetry is not None:
        world.record(body, leaving=True)
    body.y, body.p = recentre(body.y, body.p, body.t, new, world.gmst0)
    body.central, body.mu, body._view = new, float(body.p[P_MU]), None
    if body.vehicle is not None:
        fly_in_air_of(world, body)
    world.event(body, "soi_handover", {"from": old, "to": new})
    if world.telemetry is not None:
        world.record(body)


def fly_in_air_of(world, body: Body) -> None:
    """Give a staged vehicle the air of its central body (none about the Moon)."""
    body.vehicle.arrays = body.vehicle.arrays._replace(air=air_about(body.central, world.atmosphere).arrays())
