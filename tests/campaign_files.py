"""Small campaigns for the campaign tests: a short vacuum arc flown at a large step.

The arc: a 300 kg rigid body (no aerodynamics, so no air acts on it: a vacuum
arc) released from the ground at a site on the ellipsoid (height 0) with
``SPEED`` m/s at ``ELEVATION`` above the horizon, due north; it comes down about
1 km away some 19 s later, and the flight ends at its impact. At a 0.05 s step a
run takes a few milliseconds of flight.
"""

from __future__ import annotations

import math
import textwrap
from pathlib import Path

SPEED = 106.4               # m/s
ELEVATION = math.radians(60.0)
LATITUDE = 33.0             # deg

SCENARIO = f"""\
name: arc
vehicle:
  name: slug
  rigid_body: {{mass: 300 kg, inertia: [4.86, 402.4, 402.4]}}
site: {{name: range, latitude: {LATITUDE} deg, longitude: -106.9 deg, height: 0 m, pad_azimuth: 0 deg}}
mission:
  epoch: 2026-11-26T15:00:00Z
  start:
    site:
      velocity: [0 m/s, {SPEED * math.cos(ELEVATION)!r} m/s, {SPEED * math.sin(ELEVATION)!r} m/s]
      elevation: 60 deg
  duration: 30 s
step: 0.05 s
"""


def write_arc(folder: Path, campaign: str, program: str | None = None) -> Path:
    """The arc scenario (with ``program``'s text as its program, if given) and the
    campaign ``campaign`` (YAML, its ``scenario: arc.yaml``) in ``folder``; the
    campaign file's path."""
    folder.mkdir(parents=True, exist_ok=True)
    scenario = SCENARIO
    if program is not None:
        (folder / "program.py").write_text(textwrap.dedent(program))
        scenario += "program: program.py\n"
    (folder / "arc.yaml").write_text(scenario)
    path = folder / "campaign.yaml"
    path.write_text(textwrap.dedent(campaign))
    return path


# a campaign of every kind of dispersion, small enough to fly in a few seconds
MIXED = """\
name: mixed
scenario: arc.yaml
runs: 12
seed: 11
dispersions:
  v_north: {path: "mission.start.site.velocity[1]", kind: normal, sigma: 1 %}
  v_up: {path: "mission.start.site.velocity[2]", kind: normal, sigma: 2 m/s, min: 88 m/s, max: 96 m/s}
  mass: {path: vehicle.rigid_body.mass, kind: uniform, low: -5 %, high: 5 %}
  elevation: {path: mission.start.site.elevation, kind: uniform, low: 55 deg, high: 65 deg}
  step: {path: step, kind: choice, values: [0.05, 0.04]}
  noise: {path: seed, kind: seed}
  slip: {kind: slip, distribution: normal, sigma: 1 h}
"""
