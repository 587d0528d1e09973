"""The Moon and Mars missions flown from the launch pad.

scenarios/moon-from-pad.yaml and scenarios/mars-from-pad.yaml stack the
lunar and the Mars orbiter on a Falcon 9 (``spacecraft:``) at Cape Canaveral
SLC-40: the ascent to a 200 km parking orbit, the upper stage's separation
(it then deorbits itself, programs/stage_disposal.py), and the orbiter's own
mission (programs/lunar_orbit.py, programs/mars_orbit.py) from the orbit the
launcher left it in. The headless step is 0.1 s (the scenarios'): the
ascent's and the burns' closed loops need no finer one
(tests/flights/test_falcon9_ascent.py flies the ascent at 20 ms).

The Mars mission is flown whole, from the pad to Mars orbit: 4.1-4.3 s of CPU
(World.run, on a loaded 2-core machine with a warm kernel cache). Where the
time goes, the scenario's 311 d flown whole (9.2 s CPU): the ascent to the
parking orbit 0.8 s, the parking-orbit coast while the spent stage falls
0.9 s, the injection burn 0.6 s, cruise to Mars with the course corrections
1.2 s, the approach trims and the insertion 0.8 s, and the last 0.88 d
coasting in Mars orbit after the insertion (0.1 s sleep-rails steps) 5 s:
the test stops at 310.15 d, just after the insertion.

The Moon mission is flown whole too (5.9 s of CPU, same machine).
"""

import datetime as dt
import json
from pathlib import Path

import numpy as np
import pytest

from rocketsim.constants import EARTH_MU, MOON_RADIUS
from rocketsim.dynamics.nbody import FIELD_ROT
from rocketsim.dynamics.third_bodies import field_of
from rocketsim.scenario.load import load
from rocketsim.api.recorder import Recorder
from rocketsim.api.run import Run
from rocketsim.sim.build import build_world
from tests.plot_checks import assert_the_plot_reads

SCENARIOS = Path(__file__).resolve().parents[2] / "scenarios"
DAY = 86400.0


def event(body, name):
    found = [e for e in body.events if e["name"] == name]
    assert found, [e["name"] for e in body.events]
    return found[-1]


def check_ascent(world, inclination_deg):
    orbiter = world.bodies[0]
    orbit = event(orbiter, "orbit")
    assert 190e3 < orbit["periapsis_altitude_m"] < 215e3
    assert 190e3 < orbit["apoapsis_altitude_m"] < 215e3
    assert abs(orbit["inclination_deg"] - inclination_deg) < 0.5
    separation = [e for e in orbiter.events if e["name"] == "separation"]
    assert [e["stage"] for e in separation] == ["booster", "second stage"]
    assert [s.name for s in orbiter.stack.stages] == ["service module"]
    stage = next(b for b in world.bodies if b.name == separation[-1]["separated_body"])
    assert event(stage, "deorbit")["periapsis_altitude_m"] < -400e3
    return orbiter


def test_moon_from_the_pad_to_lunar_orbit():
    """From SLC-40 to a ~100 km orbit about the Moon, flown whole as ``rocketsim fly``
    flies it (World.run, the scenario's 3.7 d). References: the program's plan (a
    Lambert arc to a 100 km periapsis, circularised there: tests/flights/test_moon_mission.py
    checks the same program from a parking orbit) and the Hohmann-like injection's
    cost from 200 km, ~3.1 km/s plus the burn's gravity loss."""
    world = build_world(load(SCENARIOS / "moon-from-pad.yaml"))
    with Recorder(0) as telemetry:          # kept in memory: its plot is drawn below
        summary = world.run(telemetry)
    assert_the_plot_reads(Run(telemetry.run, telemetry.samples), "moon-from-pad")
    orbiter = check_ascent(world, 28.45)
    names = [e["name"] for e in orbiter.events]
    at = iter(names)
    assert all(name in at for name in ["liftoff", "max_q", "MECO", "orbit", "tli", "soi_handover",
                                       "approach_trim", "loi", "lunar_orbit"]), names     # in this order
    handovers = [(e["from"], e["to"]) for e in orbiter.events if e["name"] == "soi_handover"]
    assert handovers == [("earth", "moon")]
    tli, loi = event(orbiter, "tli"), event(orbiter, "loi")
    orbit = summary["bodies"][orbiter.name]["orbit"]
    print(f"\n[moon from the pad] TLI {tli['delta_v_m_s']:.0f} m/s, LOI {loi['delta_v_m_s']:.0f} m/s at "
          f"{loi['time_s'] / DAY:.2f} d: {orbit['periapsis_altitude_m'] / 1e3:.1f} x "
          f"{orbit['apoapsis_altitude_m'] / 1e3:.1f} km about the Moon")
    # launched 8 h off the plane that holds the Moon at arrival, the injection costs
    # a little more than the coplanar ~3.1 km/s
    assert tli["left_m_s"] < 0.5 and 3.1e3 < tli["delta_v_m_s"] < 3.4e3
    assert loi["left_m_s"] < 0.5 and 3.0 * DAY < loi["time_s"] < 3.8 * DAY
    assert orbiter.central == "moon" and orbit["eccentricity"] < 1.0
    assert 80e3 < orbit["periapsis_altitude_m"] < 120e3
    assert orbit["apoapsis_altitude_m"] < 150e3
    assert abs(orbit["semi_major_axis_m"] - MOON_RADIUS
               - 0.5 * (orbit["periapsis_altitude_m"] + orbit["apoapsis_altitude_m"])) < 1.0


def test_the_spacecraft_is_stacked_on_the_launcher():
    vehicle = load(SCENARIOS / "moon-from-pad.yaml").scenario.vehicle
    assert [s.name for s in vehicle.stages] == ["booster", "second stage", "service module"]
    assert vehicle.payload.name == "orbiter" and vehicle.payload.mass == 1000.0   # the orbiter's own
    assert vehicle.fairing.mass == 1900.0                                          # the launcher's
    from rocketsim.scenario.stage_selection import stack_spacecraft
    with pytest.raises(ValueError, match="both the vehicle and the spacecraft: booster"):
        stack_spacecraft(vehicle, vehicle)


def window_2026():
    """The 2026 Earth-Mars window as ``rocketsim windows --target mars`` lists it
    (its default objective, total delta-v; departures searched over Oct-Nov 2026,
    which the whole year's default search also finds best: 2026-11-01 05:41:50
    UTC, C3 9.2729 km^2/s^2, 310.231 days)."""
    from click.testing import CliRunner

    from rocketsim_cli.main import main
    result = CliRunner().invoke(main, ["windows", "--target", "mars", "--from", "2026-10-01", "--to",
                                       "2026-12-01", "--step", "2d", "--count", "1", "--format", "json"])
    assert result.exit_code == 0, result.output
    return json.loads(result.stdout)[0]


def departure_asymptote(r, v, mu):
    """(v-infinity m/s, unit asymptote) of the two-body hyperbola through ``r``, ``v``."""
    h = np.cross(r, v)
    e = np.cross(v, h) / mu - r / np.linalg.norm(r)
    ecc = float(np.linalg.norm(e))
    nu = np.arccos(-1.0 / ecc)
    q = np.cross(h, e) / np.linalg.norm(np.cross(h, e))
    return float(np.sqrt(v @ v - 2.0 * mu / np.linalg.norm(r))), np.cos(nu) * e / ecc + np.sin(nu) * q


def test_mars_from_the_pad_to_mars_orbit():
    """From SLC-40 to a 400 x 33 000 km orbit about Mars, flown whole as ``rocketsim
    fly`` flies it (World.run), stopped at 310.15 d, just after the insertion.

    References: the departure against the window ``rocketsim windows`` finds
    (Lambert arcs on the project's ephemerides, tests/unit/transfer/test_windows.py and the
    ERFA/lamberthub peer of tests/peers/test_windows_peer.py): the flown hyperbola's
    v-infinity and asymptote just after the injection (two-body about Earth,
    the Moon and Sun perturb it little in the 0.1 s since) against the window's
    sqrt(C3) and departure asymptote (declination, right ascension, J2000); the
    launch is 5.35 h after the window's departure and its arc is re-solved
    from there, which moves these by ~2 m/s and ~0.2 deg. The arrival against
    the planned orbit (the program's 400 km x 33 000 km) and the window's
    arrival date."""
    loaded = load(SCENARIOS / "mars-from-pad.yaml")
    object.__setattr__(loaded.scenario.mission, "duration", 310.15 * DAY)
    world = build_world(loaded)
    orbiter = world.bodies[0]
    after_tmi = {}

    def watch(t):
        if not after_tmi and any(e["name"] == "tmi" for e in orbiter.events):
            rotation = field_of(orbiter.p)[FIELD_ROT:FIELD_ROT + 9].reshape(3, 3)     # frame -> J2000
            after_tmi.update(r=rotation @ orbiter.position, v=rotation @ orbiter.velocity)
    world.on_progress = watch
    with Recorder(0) as telemetry:          # kept in memory: its plot is drawn below
        summary = world.run(telemetry)
    assert_the_plot_reads(Run(telemetry.run, telemetry.samples), "mars-from-pad")
    window = window_2026()

    check_ascent(world, 30.66)
    names = [e["name"] for e in orbiter.events]
    milestones = ["liftoff", "max_q", "MECO", "orbit", "tmi", "soi_handover", "course_correction",
                  "course_correction", "soi_handover", "approach_trim", "moi", "mars_orbit"]
    at = iter(names)
    assert all(name in at for name in milestones), names       # in this order
    handovers = [(e["from"], e["to"]) for e in orbiter.events if e["name"] == "soi_handover"]
    assert handovers == [("earth", "sun"), ("sun", "mars")]

    tmi, moi = event(orbiter, "tmi"), event(orbiter, "moi")
    v_inf, asymptote = departure_asymptote(after_tmi["r"], after_tmi["v"], EARTH_MU)
    dec, ra = np.degrees(np.arcsin(asymptote[2])), np.degrees(np.arctan2(asymptote[1], asymptote[0]))
    wanted = np.radians([window["dla_deg"], window["rla_deg"]])
    planned = np.array([np.cos(wanted[0]) * np.cos(wanted[1]), np.cos(wanted[0]) * np.sin(wanted[1]),
                        np.sin(wanted[0])])
    off = np.degrees(np.arccos(min(1.0, float(asymptote @ planned))))
    arrival = (dt.datetime.fromisoformat(window["arrival_utc"].replace("Z", "+00:00"))
               - loaded.scenario.mission.epoch).total_seconds()        # mission time, s
    orbit = summary["bodies"][orbiter.name]["orbit"]
    departure = dt.datetime.fromisoformat(window["departure_utc"].replace("Z", "+00:00"))
    # the scenario launches when SLC-40 passes under the plane holding the window's asymptote
    assert abs((loaded.scenario.mission.epoch - departure).total_seconds() / 3600.0 - 5.35) < 0.05
    print(f"\n[mars from the pad] TMI {tmi['delta_v_m_s']:.0f} m/s: C3 {v_inf ** 2 / 1e6:.3f} km^2/s^2 "
          f"(window {window['c3_km2_s2']}), asymptote dec {dec:.2f} RA {ra % 360:.2f} deg ({off:.3f} deg "
          f"off the window's); MOI {moi['delta_v_m_s']:.0f} m/s at {moi['time_s'] / DAY:.3f} d "
          f"(window's arrival {arrival / DAY:.3f} d): {orbit['periapsis_altitude_m'] / 1e3:.0f} x "
          f"{orbit['apoapsis_altitude_m'] / 1e3:.0f} km about Mars")

    assert tmi["left_m_s"] < 0.5 and 3.64e3 < tmi["delta_v_m_s"] < 3.8e3
    assert abs(v_inf - np.sqrt(window["c3_km2_s2"] * 1e6)) < 15.0      # C3 within 0.1 km^2/s^2
    assert off < 0.5
    # inserted: a closed orbit about Mars near the one planned, on the window's day
    assert moi["left_m_s"] < 0.5
    assert orbiter.central == "mars" and orbit["eccentricity"] < 1.0
    # the program's figures as the burn ends, then the osculating orbit 0.03 d later
    # (Mars's J2 moves the osculating apoapsis by ~300 km between periapsis and here)
    inserted = event(orbiter, "mars_orbit")
    assert abs(inserted["periapsis_altitude_m"] - 400e3) < 50e3
    assert abs(inserted["apoapsis_altitude_m"] - 33000e3) < 500e3
    assert abs(orbit["periapsis_altitude_m"] - 400e3) < 50e3
    assert abs(orbit["apoapsis_altitude_m"] - 33000e3) < 1000e3
    assert abs(moi["time_s"] - arrival) < 0.5 * DAY
