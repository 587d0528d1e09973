"""The classic range: a procedural equatorial launch site, generated from the scenario's seed.

``site: classic`` in a scenario stands for the site :func:`classic_site` makes
from the scenario's ``seed``: a procedural equatorial range launching due
east, kept so that programs written for the original planar simulator still
fly as they did (docs/physics.md#classic-range). It is an ordinary
:class:`~rocketsim.scenario.start_spec.SiteSpec`, the shape of a real site's file,
with ``model: classic`` (the original model flies from it: see
:func:`rocketsim.dynamics.derivative.held_derivative` and
:func:`rocketsim.atmosphere.day.profile_table`) and two pads downrange that a
mission can name as its target (``target: {pad: drone ship}``):

* the pad on the equator (latitude 0, height 0 on the WGS84 ellipsoid) at a
  longitude drawn uniformly from [-180, 180) deg; pad azimuth 90 deg, due east;
* ``landing zone``: on the equator, :data:`LANDING_ZONE_RANGE` downrange (east);
* ``drone ship``: on the equator, :data:`DRONE_SHIP_RANGE` downrange.

Distances are along the equator, where the ellipsoid's arc is ``a * dlon``
exactly (``a`` the WGS84 equatorial radius). Each quantity is drawn from its
own stream (``SeedSequence(seed, spawn_key=(crc32(name),))``, the sensors'
scheme), so the same seed gives the same range on every machine and adding a
quantity never moves another.
"""

from __future__ import annotations

import math

from rocketsim.constants import DEG, EARTH_RADIUS_EQ

CLASSIC = "classic"                          # what a scenario writes: site: classic
LANDING_ZONE_RANGE = (10e3, 40e3)            # m downrange, uniform
DRONE_SHIP_RANGE = (400e3, 700e3)            # m downrange, uniform


def _uniform(seed: int, name: str, low: float, high: float) -> float:
    """One draw, uniform in [low, high), from the stream of ``name`` under ``seed``."""
    import numpy as np      # here, not at the top: validating a real site's scenario stays light

    from rocketsim.flight.sensors import stream_key
    sequence = np.random.SeedSequence(entropy=seed, spawn_key=(stream_key(f"classic range/{name}"),))
    return float(low + (high - low) * np.random.Generator(np.random.PCG64(sequence)).random())


def _wrapped(lon: float) -> float:
    """Longitude (rad) wrapped into [-pi, pi)."""
    return (lon + math.pi) % (2.0 * math.pi) - math.pi


def classic_site(seed: int) -> dict:
    """The classic range of ``seed``: a site mapping in SI units (angles in radians,
    as :class:`~rocketsim.scenario.start_spec.SiteSpec` stores them), ready to validate."""
    seed = int(seed)
    lon = _uniform(seed, "pad longitude", -math.pi, math.pi)
    zone = _uniform(seed, "landing zone range", *LANDING_ZONE_RANGE)
    ship = _uniform(seed, "drone ship range", *DRONE_SHIP_RANGE)
    return {
        "name": f"classic range {seed}",
        "latitude": "0 rad",
        "longitude": f"{lon!r} rad",
        "height": 0.0,
        "pad_azimuth": "90 deg",
        "model": CLASSIC,
        "pads": [
            {"name": "landing zone", "latitude": "0 rad",
             "longitude": f"{_wrapped(lon + zone / EARTH_RADIUS_EQ)!r} rad"},
            {"name": "drone ship", "latitude": "0 rad",
             "longitude": f"{_wrapped(lon + ship / EARTH_RADIUS_EQ)!r} rad"},
        ],
        "source": (f"generated from seed {seed} (rocketsim.scenario.classic_range): pad at "
                   f"{lon / DEG:.4f} deg E on the equator, landing zone {zone / 1e3:.1f} km and "
                   f"drone ship {ship / 1e3:.1f} km downrange, launching due east"),
    }
