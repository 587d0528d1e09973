"""The Moon mission (scenarios/moon-orbit.yaml) flown whole.

From a 200 km parking orbit the lunar orbiter injects itself towards the
Moon, cruises on cruise rails through the n-body field, hands over to the
Moon's sphere of influence, trims its approach and enters a lunar orbit.
Must hold: periapsis 80-120 km above the Moon's mean radius
(1 737.4 km, IAU 2015). The scenario's headless step is 0.1 s (the burns'
closed loops need no finer one) so the test adds a few seconds, not a minute.
"""

from pathlib import Path

from rocketsim.constants import MOON_RADIUS
from rocketsim.scenario.load import load
from rocketsim.api.recorder import Recorder
from rocketsim.api.run import Run
from rocketsim.sim.build import build_world
from tests.plot_checks import assert_the_plot_reads

SCENARIO = Path(__file__).resolve().parents[2] / "scenarios" / "moon-orbit.yaml"


def test_the_orbiter_reaches_a_100_km_lunar_orbit():
    world = build_world(load(SCENARIO))
    batches = []
    world.on_progress = batches.append
    with Recorder(0) as telemetry:          # kept in memory: its plot is drawn below
        summary = world.run(telemetry)
    assert_the_plot_reads(Run(telemetry.run, telemetry.samples), "moon-orbit")
    body = world.bodies[0]
    names = [e["name"] for e in body.events]
    for name in ("tli", "soi_handover", "approach_trim", "loi", "lunar_orbit"):
        assert name in names, names
    handover = next(e for e in body.events if e["name"] == "soi_handover")
    assert (handover["from"], handover["to"]) == ("earth", "moon")
    loi = next(e for e in body.events if e["name"] == "loi")
    assert loi["left_m_s"] < 0.5                  # the burn reached its target
    assert body.central == "moon"
    orbit = summary["bodies"][body.name]["orbit"]
    print(f"\n[moon] TLI {next(e for e in body.events if e['name'] == 'tli')['delta_v_m_s']:.0f} m/s, "
          f"LOI {loi['delta_v_m_s']:.0f} m/s at {loi['time_s'] / 86400:.2f} d; orbit "
          f"{orbit['periapsis_altitude_m'] / 1e3:.1f} x {orbit['apoapsis_altitude_m'] / 1e3:.1f} km; "
          f"{len(batches)} batches")
    assert 80e3 < orbit["periapsis_altitude_m"] < 120e3
    assert orbit["apoapsis_altitude_m"] < 150e3
    # the orbit's radii are about the Moon: a = R_moon + mean altitude
    assert abs(orbit["semi_major_axis_m"] - MOON_RADIUS
               - 0.5 * (orbit["periapsis_altitude_m"] + orbit["apoapsis_altitude_m"])) < 1.0
    # cruise rails carried the 3.9-day coast (at 0.1 s steps it would take 3.4 million)
    assert len(batches) < 150_000
