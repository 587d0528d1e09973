"""What a program reads: gravity, attitude angles, speeds, and sensor errors."""

import json
import math

import numpy as np
import pytest

from rocketsim.scenario.load import load
from rocketsim.api.telemetry_flight import fly_to_file as fly
from rocketsim.telemetry.reader import messages, raw_messages
from tests.conftest import ROOT, VEHICLE

RECORD = """
import math
def main(fc):
    fc.event("readings", g=fc.gravity, g_eff=fc.effectiveGravity, pitch=fc.pitch,
             heading=fc.heading, roll=fc.roll, vs=fc.vertical_speed, hs=fc.horizontal_speed,
             alt=fc.altitude)
"""


def pad_scenario(write, latitude="0 deg", elevation="90 deg", velocity="[0, 0, 0]"):
    write("vehicle.yaml", VEHICLE)
    write("program.py", RECORD)
    return write("scenario.yaml", f"""\
        name: pad
        vehicle: vehicle.yaml
        site: {{name: pad, latitude: {latitude}, longitude: 10 deg, pad_azimuth: 90 deg}}
        program: program.py
        mission:
          epoch: 2026-11-26T12:00:00Z
          start: {{site: {{elevation: {elevation}, velocity: {velocity}}}}}
          duration: 0.02 s
        """)


def readings(path, tmp_path):
    summary = fly(load(path), tmp_path / "run.mcap")
    return summary["bodies"]["probe"]["events"][0]


def test_effective_gravity_on_the_pad_at_the_equator(write, tmp_path):
    """9.78 m/s^2 on the pad at the equator (+-0.01). Reference:
    WGS84 normal gravity at the equator, 9.7803 m/s^2, is gravity less the
    centrifugal omega^2 a = 0.0339 m/s^2; the effective gravity of a vehicle
    at rest on the pad is exactly that difference."""
    r = readings(pad_scenario(write), tmp_path)
    assert r["g_eff"] == pytest.approx(9.78, abs=0.01)
    assert r["g"] - r["g_eff"] == pytest.approx(7.2921159e-5 ** 2 * 6378137.0, rel=1e-6)


def test_effective_gravity_is_nearly_zero_in_a_circular_orbit(scenario, tmp_path):
    """Below 0.05 m/s^2 in a circular orbit (J2 leaves a little)."""
    path = scenario(RECORD, duration="0.02 s")
    events = fly(load(path), tmp_path / "run.mcap")["bodies"]["probe"]["events"]
    assert abs(events[0]["g_eff"]) < 0.05


def test_attitude_angles_on_the_pad(write, tmp_path):
    """Nose 30 deg above the horizon towards the east: pitch 30, heading 90, roll 0."""
    r = readings(pad_scenario(write, latitude="28.5 deg", elevation="30 deg"), tmp_path)
    assert math.degrees(r["pitch"]) == pytest.approx(30.0, abs=1e-9)
    assert math.degrees(r["heading"]) == pytest.approx(90.0, abs=1e-9)
    assert r["roll"] == pytest.approx(0.0, abs=1e-9)


def test_vertical_and_horizontal_speed_are_relative_to_the_ground(write, tmp_path):
    r = readings(pad_scenario(write, velocity="[30 m/s, 40 m/s, 100 m/s]"), tmp_path)
    assert r["vs"] == pytest.approx(100.0, abs=1e-9)
    assert r["hs"] == pytest.approx(50.0, abs=1e-9)


NAVIGATE = """
def main(fc):
    while True:
        fc.log(repr([float(x) for x in fc.position]))
        fc.step()
"""


def test_realistic_sensors_change_what_the_program_reads_not_the_physics(scenario, tmp_path):
    """The position a program reads carries the 2 m (1 sigma) navigation error;
    the physics runs on the truth: the state telemetry of a truth run and of a
    realistic run is bit-identical, and two seeds read different noise."""
    runs = {}
    for name, extra in [("truth", ""), ("realistic", "sensors: realistic\n"),
                        ("seed2", "sensors: realistic\nseed: 2\n")]:
        out = tmp_path / f"{name}.mcap"
        fly(load(scenario(NAVIGATE, duration="20 s", extra=extra)), out)
        runs[name] = out
    states = {k: [m for m in raw_messages(v) if m[0] == "/probe/state"] for k, v in runs.items()}
    assert states["truth"] == states["realistic"] == states["seed2"]
    read = {k: np.array([json.loads(m["message"]) for _, _, m in messages(v, ["/log"])])
            for k, v in runs.items()}
    error = read["realistic"] - read["truth"]
    assert 0.3 < np.abs(error).max() < 10.0           # metres: a 2 m-class error
    assert not np.array_equal(read["realistic"], read["seed2"])


def test_orbit_altitudes_are_over_the_central_body(probe_about, tmp_path):
    """Away from Earth, fc.periapsis, fc.apoapsis and fc.altitude are heights over the
    central body: a probe started in a 400 km circular orbit of Mars (the scenario's
    altitude over Mars's equatorial radius, 3396.19 km, IAU) reads ~400 km for all three
    (Earth-referenced they would read about -2 980 km)."""
    path = probe_about("mars", "altitude: 400 km, inclination: 25 deg, elements: osculating", """
def main(fc):
    fc.event("readings", periapsis=fc.periapsis, apoapsis=fc.apoapsis, alt=fc.altitude,
             central=fc.central_body)
""", duration="0.02 s", epoch="2027-09-08T00:00:00Z")
    r = readings(path, tmp_path)
    assert r["central"] == "mars"
    for name in ("periapsis", "apoapsis", "alt"):
        assert r[name] == pytest.approx(400e3, abs=5e3), name     # J2's osculating swing: a few km


SENSED = """
def main(fc):
    fc.event("start", g=fc.acceleration)
    fc.sleep(8.0)
    fc.event("standing", g=fc.acceleration)
"""


def test_accelerometers_read_the_grounds_push_on_the_pad_and_nothing_in_a_coast(write, scenario, tmp_path):
    """fc.acceleration (in g) is what accelerometers read,
    every force but gravity. References: (1) a body coasting in vacuum feels no
    force but gravity: 0 g to rounding; (2) the LM-class lander standing on its legs
    on an equatorial pad, settled after 8 s, is pushed up by the ground with the
    weight less the centrifugal term: WGS84 normal gravity at the equator,
    gamma_e = 9.7803253359 m/s^2 (NIMA TR8350.2, table 3.4), over G0 = 9.80665."""
    coast = fly(load(scenario(SENSED, duration="10 s")), tmp_path / "coast.mcap")
    events = {e["name"]: e for e in coast["bodies"]["probe"]["events"]}
    assert abs(events["start"]["g"]) < 1e-12 and abs(events["standing"]["g"]) < 1e-12

    write("program.py", SENSED)
    path = write("scenario.yaml", f"""\
        name: pad
        vehicle: {ROOT / 'vehicles' / 'lander.yaml'}
        site: {{name: pad, latitude: 0 deg, longitude: 10 deg, pad_azimuth: 90 deg}}
        program: program.py
        mission:
          epoch: 2026-11-26T12:00:00Z
          start: {{site: {{}}}}
          duration: 10 s
        """)
    pad = fly(load(path), tmp_path / "pad.mcap")
    events = {e["name"]: e for e in pad["bodies"]["lander"]["events"]}
    assert events["standing"]["g"] == pytest.approx(9.7803253359 / 9.80665, rel=5e-5)   # 1.0e-5 measured


HEATING = """
def main(fc):
    fc.event("air", q=fc.heating, rho=fc.air_density, v=fc.airspeed, shield=fc.shield_temperature)
"""


def test_heating_is_sutton_graves_on_the_air_the_program_reads(write, tmp_path):
    """fc.heating: a probe leaving the pad at 2 km/s through sea-level
    air. Reference: Sutton & Graves (NASA TR R-376, 1971), q = k sqrt(rho / r_n) v^3 with
    k = 1.7415e-4 kg^0.5/m for air, on the 1 m reference nose radius of a vehicle without
    a heat shield; US 1976 sea-level density 1.225 kg/m^3; no shield, no temperature."""
    write("vehicle.yaml", VEHICLE)
    write("program.py", HEATING)
    path = write("scenario.yaml", """\
        name: pad
        vehicle: vehicle.yaml
        site: {name: pad, latitude: 0 deg, longitude: 10 deg, pad_azimuth: 90 deg}
        program: program.py
        mission:
          epoch: 2026-11-26T12:00:00Z
          start: {site: {elevation: 90 deg, velocity: [0, 0, 2000]}}
          duration: 0.02 s
        """)
    r = fly(load(path), tmp_path / "run.mcap")["bodies"]["probe"]["events"][0]
    assert r["rho"] == pytest.approx(1.225, rel=1e-3)
    assert r["v"] == pytest.approx(2000.0, rel=1e-3)
    assert r["q"] == pytest.approx(1.7415e-4 * math.sqrt(r["rho"] / 1.0) * r["v"] ** 3, rel=1e-12)
    assert math.isnan(r["shield"])


RADAR = """
def main(fc):
    fc.event("radar", radar=fc.radar_altitude, clearance=fc.clearance, altitude=fc.altitude,
             body=fc.central_body)
"""


def test_radar_altitude_over_the_moon_is_the_height_over_the_moon(probe_about, tmp_path):
    """A probe in a circular 100 km lunar orbit (n-body field, the Moon's frame): the radar
    and the clearance read its height over the Moon's surface, as fc.altitude does (truth
    sensors: the same number), about 100 km (the 1737.4 km sphere of IAU 2015). They read
    the WGS84 height of the Moon-centred position before, -4 540 km."""
    path = probe_about("moon", "altitude: 100 km, inclination: 80 deg, elements: osculating", RADAR)
    r = fly(load(path), tmp_path / "run.mcap")["bodies"]["probe"]["events"][0]
    assert r["body"] == "moon"
    assert r["radar"] == r["altitude"] == r["clearance"]
    assert r["radar"] == pytest.approx(100e3, abs=10.0)


def test_a_views_place_readings_alone_are_those_of_all_its_readings():
    """A view reads the place's readings (height, climb rate, ground speed, local axes,
    surface velocity) alone where they are read first: the same bits as the same slots of
    all its readings, and as a view made of the same numbers by its constructor (numba's
    dispatcher, not the entries bound for views of a state), about Earth and a Moon-like
    body, on random states from the pad to far out."""
    import numpy as np

    from rocketsim.flight.readings import CLIMB, ENU, GROUND_SPEED, HEIGHT, LATITUDE, SURFACE, StateView
    from rocketsim.layout import make_params

    place = list(range(LATITUDE, GROUND_SPEED + 1)) + list(range(ENU, SURFACE + 3))
    rng = np.random.default_rng(7)
    moon = make_params(1.0, (1.0, 1.0, 1.0), 4.9028e12, 1737400.0, 2.03e-4, 1737400.0)
    for p in (None, moon):
        for _ in range(500):
            y = np.zeros(20)
            y[0:3] = rng.normal(size=3) * rng.uniform(6.0e6, 5.0e7)
            y[3:6] = rng.normal(size=3) * rng.uniform(0.0, 1.1e4)
            q = rng.normal(size=4)
            y[6:10] = q / np.linalg.norm(q)
            t = float(rng.uniform(0.0, 1e5))
            alone, whole = StateView.of_state(t, y, p=p), StateView.of_state(t, y, p=p)
            made = StateView(t, y[0:3], y[3:6], y[6:10], y[10:13], p=p)
            assert alone.vertical_speed == whole._buffer[CLIMB] and alone.height == whole._buffer[HEIGHT]
            np.testing.assert_array_equal(alone._place[place], whole._buffer[place])
            np.testing.assert_array_equal(whole._buffer, made._buffer)
