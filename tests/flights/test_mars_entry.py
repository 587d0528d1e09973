"""Mars entry (scenarios/mars-entry.yaml): deorbit, ballistic entry, parachute conditions, descent.

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
import pytest

from rocketsim.atmosphere.mars import mars_table
from rocketsim.bodies.orientation import spin_rate
from rocketsim.constants import HEAT_SHIELD_LIMIT, SUTTON_GRAVES_MARS
from rocketsim.dynamics.derivative import radial_height
from rocketsim.scenario.load import load
from rocketsim.api.recorder import Recorder
from rocketsim.api.run import Run
from rocketsim.sim.build import build_world
from tests.plot_checks import assert_the_plot_reads
from rocketsim.vehicle.heating import sutton_graves

SCENARIO = Path(__file__).resolve().parents[2] / "scenarios" / "mars-entry.yaml"


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
    entry_speed = events["entry_interface"]["inertial_speed_m_s"]
    print(f"\n[mars entry] entry {entry_speed:.0f} m/s; peak {peak['flux'] / 1e4:.1f} W/cm^2 at "
          f"{peak['speed']:.0f} m/s; shield {peak['temperature']:.0f} K; parachute at Mach "
          f"{chute['mach']:.2f}, {chute['altitude_m'] / 1e3:.1f} km")
    assert chute["mach"] < 2.0 and chute["altitude_m"] > 7e3
    assert 300.0 < peak["temperature"] < HEAT_SHIELD_LIMIT
    assert peak["flux"] > 1e4
    assert abs(peak["speed"] / entry_speed - math.exp(-1.0 / 6.0)) < 0.05


def test_the_capsule_descends_under_its_disk_gap_band_at_the_quasi_steady_speed():
    """Under the disk-gap-band (C_D S = 218 m^2, the Mars Science Laboratory's 21.5 m
    canopy at C_D 0.6, Cruz et al. 2014) plus the capsule's own axial drag (C_A A,
    the vehicle file's table at the flight's Mach) the capsule falls at the terminal
    speed ``v_t = sqrt(2 m g / (rho sum C_D A))`` corrected for the thickening air:
    keeping to ``v_t(h)`` takes a deceleration ``v^2 / (2 H)`` (H the density scale
    height), so ``v = v_t sqrt(1 + v^2 / (2 H g))``, 3 % faster at 3 km on Mars. The
    density is the NASA Glenn Mars model written out here (p = 0.699 exp(-0.00009 h)
    kPa, T = -31 - 0.000998 h C, rho = p / (0.1921 (T + 273.1))), g = mu / r^2 less the
    centrifugal term of Mars's turn. Within 1.5 % (the capsule's attitude under the
    canopy, hence its own drag, is not held exactly)."""
    world = build_world(load(SCENARIO))
    body = world.bodies[0]
    seen = {}

    def watch(t):
        if not any(e["name"] == "parachute_inflated" for e in body.events):
            return
        h = radial_height(body.y, body.p)
        for mark in (5000.0, 3000.0):
            if mark not in seen and h < mark:
                r, v = body.position, body.velocity
                air = v - np.cross((0.0, 0.0, spin_rate("mars")), r)
                seen[mark] = (h, float(np.linalg.norm(air)), body.mass, r.copy(), float(body.view().mach))
    world.on_progress = watch
    with Recorder(0) as telemetry:          # kept in memory: its plot is drawn below
        world.run(telemetry)
    assert_the_plot_reads(Run(telemetry.run, telemetry.samples), "mars-entry")
    events = [e["name"] for e in body.events]
    assert events[-3:] == ["parachute_conditions", "parachute_deployed", "parachute_inflated"]
    assert body.flying and "impact" not in events
    table = [(0.0, 1.0), (0.8, 1.05), (1.2, 1.35), (2.0, 1.5)]      # vehicles/mars-entry-capsule.yaml
    for mark, (h, speed, mass, r, mach) in seen.items():
        temperature = -31.0 - 0.000998 * h + 273.1
        rho = 0.699 * math.exp(-0.00009 * h) / (0.1921 * temperature)
        scale = 1.0 / (0.00009 - 0.000998 / temperature)             # -1 / (d ln rho / dh)
        rn = float(np.linalg.norm(r))
        cos_lat2 = (r[0] ** 2 + r[1] ** 2) / rn ** 2
        g = 4.282837362e13 / rn ** 2 - spin_rate("mars") ** 2 * rn * cos_lat2
        area = 218.0 + float(np.interp(mach, *zip(*table))) * math.pi / 4 * 4.5 ** 2
        terminal = math.sqrt(2 * mass * g / (rho * area))
        steady = terminal * math.sqrt(1.0 / (1.0 - terminal ** 2 / (2 * scale * g)))
        print(f"\n[mars chute] at {h:.0f} m: {speed:.2f} m/s; terminal {terminal:.2f}, quasi-steady {steady:.2f}")
        assert speed == pytest.approx(steady, rel=0.015)
