"""Mars entry (scenarios/mars-entry.yaml): deorbit, ballistic entry, parachute conditions.

A capsule in a 400 km Mars orbit burns ~110 m/s retrograde, falls half an
orbit and enters behind its heat shield through the Mars reference
atmosphere (rocketsim.atmosphere.mars) down to parachute conditions: Mach
below 2 more than 7 km up (the disk-gap-band parachutes of Viking, Phoenix
and the Mars Science Laboratory opened between Mach 1.1 and 2.1, 6-13 km
up). The shield must stay below 2 400 K (docs/physics.md#heating). Reference for the
heating: Allen & Eggers (NACA Report 1381, 1958): in a ballistic entry
through an exponential atmosphere the stagnation heat flux ``~ sqrt(rho) v^3``
peaks where ``v = e^(-1/6) v_E = 0.85 v_E`` (v_E the entry speed); gravity
and curvature on a shallow path shift it a little, hence 5 %.
The headless step is 0.1 s (the entry's time scales are tens of seconds).
"""

import math
from pathlib import Path

import numpy as np

from rocketsim.atmosphere.mars import mars_table
from rocketsim.bodies.orientation import spin_rate
from rocketsim.constants import HEAT_SHIELD_LIMIT, SUTTON_GRAVES_MARS
from rocketsim.dynamics.derivative import radial_height
from rocketsim.scenario.load import load
from rocketsim.sim.build import build_world
from rocketsim.vehicle.heating import sutton_graves

SCENARIO = Path(__file__).resolve().parents[1] / "scenarios" / "mars-entry.yaml"


def test_the_capsule_reaches_parachute_conditions_with_its_shield_intact():
    world = build_world(load(SCENARIO))
    body = world.bodies[0]
    air = mars_table()
    nose = body.checks.shield.nose_radius
    peak = {"flux": 0.0, "speed": 0.0, "temperature": body.checks.temperature}

    def watch(t):
        if len(body.events) < 4:                # before the entry interface (150 km): no air
            return
        r, v = body.position, body.velocity
        rho = float(air.at(radial_height(body.y, body.p))[0][0])
        speed = float(np.linalg.norm(v - np.cross((0.0, 0.0, spin_rate("mars")), r)))
        flux = sutton_graves(rho, speed, nose, SUTTON_GRAVES_MARS)
        if flux > peak["flux"]:
            peak.update(flux=flux, speed=speed)
        peak["temperature"] = max(peak["temperature"], body.checks.temperature)
        if any(e["name"] == "parachute_conditions" for e in body.events):
            world.n_steps = world.k             # the descent under the parachute is not flown
    world.on_progress = watch
    world.run()
    events = {e["name"]: e for e in body.events}
    assert "heat shield failure" not in events and "breakup" not in events and body.flying
    assert body.central == "mars" and events["deorbit"]["left_m_s"] < 2.0
    chute = events["parachute_conditions"]
    entry_speed = events["entry_interface"]["speed_m_s"]
    print(f"\n[mars entry] entry {entry_speed:.0f} m/s; peak {peak['flux'] / 1e4:.1f} W/cm^2 at "
          f"{peak['speed']:.0f} m/s; shield {peak['temperature']:.0f} K; parachute at Mach "
          f"{chute['mach']:.2f}, {chute['height_m'] / 1e3:.1f} km")
    assert chute["mach"] < 2.0 and chute["height_m"] > 7e3
    assert 300.0 < peak["temperature"] < HEAT_SHIELD_LIMIT
    assert peak["flux"] > 1e4
    assert abs(peak["speed"] / entry_speed - math.exp(-1.0 / 6.0)) < 0.05
