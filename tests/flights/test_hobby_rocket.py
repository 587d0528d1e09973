"""The worked example, scenarios/hobby-rocket.yaml: a 4895L1395 rocket off a rail, two parachutes.

Checked against independent figures: the motor's total impulse (its
designation, 4 895 N s) delivered by burnout; the landing under the main at
a few m/s is a touchdown, not an impact (docs/physics.md#parachutes); the
touchdown's distance from the pad is the horizontal distance of its reported
landing point from the site, by pymap3d (a peer used only in tests); the
descent and drift times are the differences of the events' times; the
rocket comes to rest on the site's flat ground at the pad's height. The whole
flight (about 170 s, 20 ms steps) takes seconds.
"""

import math
from pathlib import Path

import pytest

from rocketsim.scenario.load import load
from rocketsim.sim.build import build_world

pymap3d = pytest.importorskip("pymap3d")

SCENARIO = Path(__file__).resolve().parents[2] / "scenarios" / "hobby-rocket.yaml"


@pytest.fixture(scope="module")
def flight():
    loaded = load(SCENARIO)
    world = build_world(loaded)
    world.run()
    body = world.bodies[0]
    return loaded.scenario, body, {e["name"] + (f":{e['parachute']}" if "parachute" in e else ""): e
                                   for e in body.events}


def test_the_flight_runs_its_sequence_and_lands_under_the_main(flight):
    _, body, events = flight
    names = [e["name"] for e in body.events]
    assert names == ["liftoff", "off_rail", "burnout", "max_q", "apogee", "parachute_deployed",
                     "parachute_inflated", "parachute_deployed", "parachute_inflated", "touchdown"]
    off = events["off_rail"]
    assert 20.0 < off["surface_speed_m_s"] < 40.0 and 1.5 < off["stability_margin_cal"] < 4.0
    assert events["burnout"]["total_impulse_N_s"] == pytest.approx(4895.0, rel=0.01)
    touchdown = events["touchdown"]
    print(f"\n[hobby] off the rail {off['surface_speed_m_s']:.1f} m/s, margin {off['stability_margin_cal']:.2f} cal; "
          f"apogee {events['apogee']['height_agl_m']:.0f} m; touchdown {touchdown['vertical_speed_m_s']:.2f} m/s, "
          f"{touchdown['distance_to_target_m']:.0f} m from the pad")
    assert -8.0 < touchdown["vertical_speed_m_s"] < -5.0
    assert not body.flying            # recovered: the flight ends at touchdown
    # on the site's flat ground at the pad's height (ground_height 1 380 m), tail down
    # (tilt 0 deg), hanging from the shock cord at the top of its stage: the base touched,
    # the centre of mass is its station above it
    x_cm = body.vehicle.mass_properties(body.y)[1]
    assert body.view().geodetic[2] - 1380.0 == pytest.approx(x_cm, abs=0.05)
    assert touchdown["tilt_deg"] < 5.0
    main = events["parachute_deployed:main"]
    assert main["trigger"] == "height 300 m" and 295.0 < main["height_agl_m"] <= 300.0
    assert events["parachute_deployed:drogue"]["time_s"] == events["apogee"]["time_s"]


def test_the_landing_figures_are_those_of_the_reported_point(flight):
    scenario, body, events = flight
    touchdown = events["touchdown"]
    site = scenario.site
    e, n, _ = pymap3d.geodetic2enu(touchdown["latitude_deg"], touchdown["longitude_deg"], 0.0,
                                   math.degrees(site.latitude), math.degrees(site.longitude), 0.0)
    assert touchdown["distance_to_target_m"] == pytest.approx(math.hypot(e, n), rel=1e-3)
    assert touchdown["descent_time_s"] == pytest.approx(touchdown["time_s"] - events["apogee"]["time_s"], abs=1e-9)
    assert touchdown["drift_time_s"] == pytest.approx(
        touchdown["time_s"] - events["parachute_deployed:drogue"]["time_s"], abs=1e-9)


def test_the_telemetry_carries_the_motor_thrust_and_the_burning_mass():
    """The state messages' thrust is the file's curve interpolated linearly (numpy, on
    the raw points) and the mass falls by the impulse delivered, m0 I(t) / I_total."""
    import numpy as np
    import rocketsim
    run = rocketsim.fly(SCENARIO, duration=3.0)
    table = run.bodies["hobby-rocket"].table(units=False)
    raw = [line.split() for line in (SCENARIO.parents[1] / "motors" / "Cesaroni_4895L1395-P.eng")
           .read_text().splitlines() if line.strip() and not line.startswith(";")][1:]
    t_curve = np.array([0.0] + [float(a) for a, _ in raw])
    f_curve = np.array([0.0] + [float(b) for _, b in raw])
    fine = np.linspace(0.0, 3.45, 345001)
    impulse = np.concatenate(([0.0], np.cumsum(0.5 * (np.interp(fine[1:], t_curve, f_curve)
                                                     + np.interp(fine[:-1], t_curve, f_curve)) * np.diff(fine))))
    for t in (0.5, 1.0, 2.5):
        row = table.loc[t]
        assert row["thrust"] == pytest.approx(np.interp(t, t_curve, f_curve), rel=1e-12)
        burnt = 2.475 * np.interp(t, fine, impulse) / impulse[-1]
        assert row["mass"] == pytest.approx(16.423 - burnt, abs=1e-6)
        assert row["engines_running"] == 1


def test_the_summary_reads_as_a_hobby_flight(flight):
    """Flown through the front door (its telemetry kept in memory): the summary has no orbit
    but the flight: the apogee above the ground (the highest sample's altitude less the
    site's ground, 1 380 m; within centimetres of the apogee event, found at the step where
    the climb turned), the largest speed over the ground (worked out here from the samples'
    state: ``|v - omega z x r|``, omega the simulator's Earth rate), Mach, q (the max_q
    event's peak, found step by step, within 1 %), the largest load (at most the thrust
    over the mass, the drag taking its share), the rail exit and the landing, where the
    touchdown was and at what speed, drifted from the start as far as the touchdown's
    distance to the pad (the launch site: the rocket starts 8 cm from it on its rail)."""
    import numpy as np
    import rocketsim
    from rocketsim_cli.summary import format_summary
    run = rocketsim.fly(SCENARIO)
    _, _, events = flight
    body = run.summary["bodies"]["hobby-rocket"]
    assert "orbit" not in body and run.bodies["hobby-rocket"].orbit is None
    f = body["flight"]
    table = run.bodies["hobby-rocket"].table()
    assert f["ground_height_m"] == 1380.0
    assert f["apogee_height_agl_m"] == table["altitude_m"].max() - 1380.0
    assert f["apogee_height_agl_m"] == pytest.approx(events["apogee"]["height_agl_m"], abs=0.05)
    in_flight = table[table.index < events["touchdown"]["time_s"]]
    r = in_flight[["position_x_m", "position_y_m", "position_z_m"]].to_numpy()
    v = in_flight[["velocity_x_m_s", "velocity_y_m_s", "velocity_z_m_s"]].to_numpy()
    from rocketsim.constants import EARTH_OMEGA
    over_ground = np.linalg.norm(v - EARTH_OMEGA * np.stack([-r[:, 1], r[:, 0], 0 * r[:, 0]], axis=1), axis=1)
    assert f["max_surface_speed_m_s"] == pytest.approx(over_ground.max(), rel=1e-9)
    assert 250.0 < f["max_surface_speed_m_s"] < 300.0 and 0.7 < f["max_mach"] < 0.9
    assert f["max_dynamic_pressure_Pa"] == pytest.approx(events["max_q"]["dynamic_pressure_Pa"], rel=0.01)
    thrust_over_weight = (in_flight["thrust_N"] / in_flight["mass_kg"]).max() / 9.80665
    assert 0.9 * thrust_over_weight < f["max_sensed_acceleration_g"] <= thrust_over_weight
    assert f["rail_exit_surface_speed_m_s"] == events["off_rail"]["surface_speed_m_s"]
    assert f["rail_exit_stability_margin_cal"] == events["off_rail"]["stability_margin_cal"]
    down = events["touchdown"]
    assert f["landing_kind"] == "touchdown" and f["landing_time_s"] == down["time_s"]
    assert f["landing_surface_speed_m_s"] == pytest.approx(math.hypot(down["vertical_speed_m_s"],
                                                                      down["horizontal_speed_m_s"]))
    assert f["drift_m"] == pytest.approx(down["distance_to_target_m"], abs=1.0)
    text = format_summary(run.summary)
    print("\n" + text)
    assert "apogee 2,9" in text and "m above the ground" in text and "Mach 0.8" in text and " g" in text
    assert "rail exit" in text and "touchdown: T+" in text and "orbit" not in text
