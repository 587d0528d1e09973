"""The Mars mission (scenarios/mars-orbit.yaml) flown whole.

In the 2026 window that ``rocketsim windows --target mars`` finds (departure
2026-11-01 05:41:50 UTC, 310.2-day transfer; its mission fragment gives the
scenario's epoch), the orbiter injects itself from a 200 km parking orbit,
leaves Earth's sphere of influence for the Sun's, corrects its course twice,
enters Mars's sphere and captures into a 400 x 33 000 km orbit. Must hold:
Mars orbit inserted. The headless step is 0.1 s (the burns'
closed loops need no finer one) and cruise rails carry the 310 days.
"""

from pathlib import Path

from rocketsim.constants import MARS_RADIUS_EQ
from rocketsim.scenario.load import load
from rocketsim.sim.build import build_world
from rocketsim.telemetry.reader import messages
from rocketsim.telemetry.writer import TelemetryWriter
from tests.plot_checks import assert_the_plot_reads

SCENARIO = Path(__file__).resolve().parents[2] / "scenarios" / "mars-orbit.yaml"


def test_the_orbiter_is_captured_by_mars(tmp_path):
    # flown as `rocketsim fly` flies it, telemetry included: every sample of the
    # heliocentric leg is written about the Sun (no prime meridian there)
    world = build_world(load(SCENARIO))
    out = tmp_path / "mars.mcap"
    with TelemetryWriter(out, 0, "") as telemetry:
        summary = world.run(telemetry)
    body = world.bodies[0]
    assert_the_plot_reads(out, "mars-orbit")
    centres = [m["central_body"] for _, _, m in messages(out, [f"/{body.name}/state"])]
    assert [c for i, c in enumerate(centres) if i == 0 or c != centres[i - 1]] == ["earth", "sun", "mars"]
    handovers = [(e["from"], e["to"]) for e in body.events if e["name"] == "soi_handover"]
    assert handovers == [("earth", "sun"), ("sun", "mars")]
    names = [e["name"] for e in body.events]
    for name in ("tmi", "course_correction", "moi", "mars_orbit"):
        assert name in names, names
    moi = next(e for e in body.events if e["name"] == "moi")
    assert moi["left_m_s"] < 0.5
    orbit = summary["bodies"][body.name]["orbit"]
    print(f"\n[mars] TMI {next(e for e in body.events if e['name'] == 'tmi')['delta_v_m_s']:.0f} m/s, "
          f"MOI {moi['delta_v_m_s']:.0f} m/s at {moi['time_s'] / 86400:.2f} d; orbit "
          f"{orbit['periapsis_altitude_m'] / 1e3:.0f} x {orbit['apoapsis_altitude_m'] / 1e3:.0f} km")
    # captured: a closed orbit about Mars, periapsis above the air's 151 km rails
    # floor and near the 400 km aimed for, apoapsis near the 33 000 km aimed for
    assert body.central == "mars" and orbit["eccentricity"] < 1.0
    assert 200e3 < orbit["periapsis_altitude_m"] < 600e3
    assert abs(orbit["apoapsis_altitude_m"] - 33000e3) < 1000e3
    assert abs(orbit["semi_major_axis_m"] - MARS_RADIUS_EQ
               - 0.5 * (orbit["periapsis_altitude_m"] + orbit["apoapsis_altitude_m"])) < 1.0
