"""Impact predictions (fc.impact_point, fc.time_to_impact) against the integrator.

The prediction is the vacuum two-body conic meeting the WGS84 ellipsoid
(rocketsim.flight.impact). Reference: the reference integrator
(rocketsim.dynamics.reference, DOP853 at 1e-12) flying the same state in
the same point-mass field (J2 set to zero, no air): at the predicted time
the integrated body must stand on the ellipsoid at the predicted point,
and above it all the way there. Then a flown case with J2 (the shipped
ballistic arc from Spaceport America, vacuum) measures what leaving J2 out
costs.
"""

import math

import numpy as np
import pytest

from rocketsim.constants import DEG, EARTH_J2, EARTH_MU, EARTH_RADIUS_EQ, EARTH_RADIUS_POLAR
from rocketsim.dynamics.reference import integrate_reference
from rocketsim.layout import R, make_params, make_state
from rocketsim.flight.impact import predict_impact
from rocketsim.frames.earth_fixed import ecef_to_eci, eci_to_ecef
from rocketsim.frames.geodetic import ecef_to_geodetic, enu_basis, geodetic_to_ecef
from rocketsim.scenario.load import load
from rocketsim.api.telemetry_flight import fly_to_file as fly
from rocketsim.telemetry.reader import messages
from tests.conftest import ROOT


def launch_state(lat_deg, lon_deg, height, speed, elevation_deg, heading_deg, t=0.0):
    """ECI position and velocity at mission time ``t`` of a point ``height`` m above
    (lat, lon) moving at ``speed`` m/s (inertial) ``elevation`` above the horizon."""
    lat, lon = lat_deg * DEG, lon_deg * DEG
    r = ecef_to_eci(geodetic_to_ecef(lat, lon, height), t)
    east, north, up = enu_basis(lat, lon)
    el, hd = elevation_deg * DEG, heading_deg * DEG
    d_ecef = math.cos(el) * (math.sin(hd) * east + math.cos(hd) * north) + math.sin(el) * up
    return r, speed * ecef_to_eci(d_ecef, t)


def fly_reference(r, v, times):
    """Positions (m, ECI) of the reference integrator at ``times`` (s), point mass only."""
    p = make_params(1.0, (1.0, 1.0, 1.0), EARTH_MU, EARTH_RADIUS_EQ, 0.0, EARTH_RADIUS_POLAR)
    ys = integrate_reference(make_state(r, v), 0.0, float(times[-1]), p, t_eval=times)
    return ys[:, R:R + 3]


@pytest.mark.parametrize("case", [
    (32.99, -106.98, 80e3, 2500.0, 60.0, 20.0),      # a sounding arc northbound
    (-39.26, 177.87, 150e3, 6500.0, 5.0, 190.0),     # a long suborbital arc southbound
    (5.0, -52.0, 30e3, 1200.0, -30.0, 90.0),         # already falling
])
def test_the_predicted_impact_is_where_the_integrator_meets_the_ground(case):
    r, v = launch_state(*case)
    impact = predict_impact(r, v, 0.0, EARTH_MU)
    assert impact is not None and impact.time > 0
    times = np.linspace(0.0, impact.time, 400)
    path = fly_reference(r, v, times)
    at_impact = path[-1]
    assert np.linalg.norm(at_impact - impact.position) < 0.05          # m
    heights = ecef_to_geodetic(eci_to_ecef(path, times))[2]
    assert abs(heights[-1]) < 0.05                                      # on the ground (m)
    assert np.all(heights[:-1] > 0.0)                                   # and not before
    lat, lon, _ = ecef_to_geodetic(eci_to_ecef(at_impact, impact.time))
    assert impact.latitude == pytest.approx(lat, abs=1e-8)
    assert math.remainder(impact.longitude - lon, 2 * math.pi) == pytest.approx(0.0, abs=1e-8)
    # the speed at impact: vis-viva on the integrated path's energy
    assert impact.speed == pytest.approx(math.sqrt(v @ v + 2 * EARTH_MU * (
        1 / np.linalg.norm(at_impact) - 1 / np.linalg.norm(r))), rel=1e-9)


def test_the_earth_turns_under_a_long_flight():
    """The same inertial arc started an hour later meets the same inertial point, which
    by then has turned omega_E * 3600 s (WGS84 rate) further east under the
    ground: the impact longitude lies that much further west."""
    r, v = launch_state(0.0, 0.0, 100e3, 3000.0, 45.0, 0.0)
    first = predict_impact(r, v, 0.0, EARTH_MU)
    later = predict_impact(r, v, 3600.0, EARTH_MU)
    shift = math.remainder(first.longitude - later.longitude, 2 * math.pi)
    assert shift == pytest.approx(7.2921159e-5 * 3600.0, abs=1e-12)
    assert later.time == pytest.approx(first.time, abs=1e-9)


def test_no_impact_from_an_orbit_or_an_escape():
    r, v = launch_state(0.0, 0.0, 400e3, 7700.0, 0.0, 90.0)
    assert predict_impact(r, v, 0.0, EARTH_MU) is None                 # 400 km circular-ish
    r, v = launch_state(0.0, 0.0, 400e3, 12_000.0, 30.0, 90.0)
    assert predict_impact(r, v, 0.0, EARTH_MU) is None                 # hyperbolic, climbing


PROGRAM = '''
def main(fc):
    fc.wait_until(lambda: fc.vertical_speed < 0.0)
    lat, lon = fc.impact_point
    fc.event("prediction", latitude=lat, longitude=lon, time_to_impact=fc.time_to_impact)
'''


def test_a_flown_ballistic_arc_lands_near_the_prediction(tmp_path):
    """The shipped vacuum arc from Spaceport America (1.2 km/s at 85 deg), flown
    with J2 at 0.1 s steps (the largest headless step, to keep the test short;
    RK4's error on this arc is far below a metre). Predicted at apogee (73 km,
    125 s before the ground), the flown impact lies 111 m from the prediction,
    towards the equator, and 0.012 s later (measured). That is J2, which the
    vacuum prediction leaves out: its pull along the meridian,
    ``3 mu J2 R^2 / r^4 sin(phi) cos(phi)`` (the latitudinal term of the J2
    acceleration, docs/physics.md#j2), is 0.0142 m/s^2 at 33 deg and 40 km, and
    ``a t^2 / 2`` over 125 s is 111 m.
    """
    program = tmp_path / "predict.py"
    program.write_text(PROGRAM)
    text = (ROOT / "scenarios" / "spaceport-ballistic.yaml").read_text()
    text = text.replace("../vehicles/", f"{ROOT}/vehicles/").replace("site: sites/", f"site: {ROOT}/scenarios/sites/")
    text = text.replace("program: programs/apogee.py", f"program: {program}")
    scenario = tmp_path / "arc.yaml"
    scenario.write_text(text)
    summary = fly(load(scenario), tmp_path / "arc.mcap", step=0.1, duration=260.0)
    name, record = next(iter(summary["bodies"].items()))
    predicted = next(e for e in record["events"] if e["name"] == "prediction")
    # where the flown path crosses the ground: the 10 Hz telemetry's last three samples above
    # it, their altitudes fitted by a parabola (the arc under gravity alone: exact to the
    # change of gravity over 0.3 s) and carried to nought, their place likewise
    samples = [m for _, _, m in messages(tmp_path / "arc.mcap", [f"/{name}/state"])]
    above = [m for m in samples if m["t"] > predicted["time_s"] and m["altitude"] > 1.0][-3:]
    t3 = np.array([m["t"] for m in above])
    fit = np.polyfit(t3 - t3[-1], [m["altitude"] for m in above], 2)
    hit_t = t3[-1] + min(r.real for r in np.roots(fit) if abs(r.imag) < 1e-12 and r.real > 0)
    lat = np.polyval(np.polyfit(t3, [m["latitude_deg"] for m in above], 2), hit_t) * DEG
    lon = np.polyval(np.polyfit(t3, [m["longitude_deg"] for m in above], 2), hit_t) * DEG
    north = (predicted["latitude"] - lat) * 6.37e6
    east = math.remainder(predicted["longitude"] - lon, 2 * math.pi) * 6.37e6 * math.cos(lat)
    print(f"impact prediction at apogee vs flown (J2): {math.hypot(north, east):.1f} m, "
          f"{predicted['time_s'] + predicted['time_to_impact'] - hit_t:+.3f} s")
    fall = predicted["time_to_impact"]
    r = EARTH_RADIUS_EQ + 40e3
    j2_pull = 3 * EARTH_MU * EARTH_J2 * EARTH_RADIUS_EQ ** 2 / r ** 4 * math.sin(lat) * math.cos(lat)
    assert north == pytest.approx(0.5 * j2_pull * fall ** 2, rel=0.2)   # towards the equator
    assert abs(east) < 5.0
    assert predicted["time_s"] + predicted["time_to_impact"] == pytest.approx(hit_t, abs=0.05)
    # the world records the impact where the path crossed the ground, not at the end of
    # the 0.1 s step below it (up to 120 m down at 1.2 km/s): its time, the final state's
    # altitude and the last sample's are the crossing's
    impact = next(e for e in record["events"] if e["name"] == "impact")
    print(f"impact: {impact['time_s'] - hit_t:+.2e} s from the samples' crossing, final altitude "
          f"{record['final']['altitude_m']:+.2e} m")
    assert impact["time_s"] == pytest.approx(hit_t, abs=1e-4)
    assert record["final"]["altitude_m"] == pytest.approx(0.0, abs=1e-3)
    assert samples[-1]["altitude"] == pytest.approx(0.0, abs=1e-3) and samples[-1]["t"] == impact["time_s"]
    assert impact["latitude_deg"] == pytest.approx(lat / DEG, abs=1e-7)        # 1 cm
