"""Parachutes: terminal descent, the opening lag and linear inflation, drift with the wind.

References:

* under a canopy of drag area ``C_D S`` a body of mass ``m`` falls at the
  terminal speed ``v_t = sqrt(2 m g / (rho C_D S))``; ``rho`` is the US 1976
  standard density at that height from the ``ussa1976`` package (Nollet, an
  independent implementation used only in tests) and ``g`` WGS84 normal
  gravity (Somigliana, NIMA TR8350.2 eq. 4-1) less the free-air gradient. The
  air thickens as the body falls, so it is never exactly at the terminal
  speed: the lag is ``v_t^2 / (2 H g)`` of it, about 2e-4, well inside 1 %;
* the drag area's law, written out: nothing during the lag, then linear.

The test body has no aerodynamics of its own (so the canopy is the only
drag). It is thrown 20 m/s up from 1 500 m and falls 1 000 m on a 10 m^2
canopy; the step is 50 ms (a descent of minutes at 6 m/s is smooth).
"""

import math

import numpy as np
import pytest

from rocketsim.frames.quaternion import quat_rotate
from rocketsim.layout import Q, W
from rocketsim.scenario.load import load
from rocketsim.sim.build import build_world
from rocketsim.vehicle.parachutes import CANOPY_RATE_TIME, CH_DEPLOYED, inflated

ussa1976 = pytest.importorskip("ussa1976")

MASS, CDS, LATITUDE = 20.0, 10.0, 32.99


def somigliana(latitude_deg: float) -> float:
    s2 = math.sin(math.radians(latitude_deg)) ** 2
    return 9.7803253359 * (1 + 0.00193185265241 * s2) / math.sqrt(1 - 0.00669437999013 * s2)


def scenario(chutes, height="1500 m", duration="240 s", weather=None) -> dict:
    data = {"name": "drop", "step": "0.05 s",
            "vehicle": {"name": "drop test", "stages": [{"name": "body", "length": "1 m",
                                                          "diameter": "0.2 m", "structure_mass": f"{MASS} kg",
                                                          "parachutes": chutes}]},
            "site": {"name": "range", "latitude": f"{LATITUDE} deg", "longitude": "-106.975 deg",
                     "height": height, "ground_height": "0 m"},     # thrown from up there
            "mission": {"epoch": "2026-06-01T12:00:00Z", "duration": duration,
                        "start": {"site": {"velocity": [0, 0, 20]}}}}
    if weather is not None:
        data["weather"] = weather
    return data


def density(height_m: float) -> float:
    return float(ussa1976.compute(z=np.array([height_m]), variables=["rho"])["rho"].values[0])


def test_terminal_descent_under_a_main_is_the_analytic_speed():
    world = build_world(load(scenario([{"name": "main", "cd_s": f"{CDS} m2", "lag": "1 s",
                                         "inflation": "2 s", "deploy": "apogee"}])))
    body = world.bodies[0]
    seen = {}

    def watch(t):
        lat, lon, h = world.where(body)
        for mark in (1000.0, 700.0):
            if mark not in seen and h < mark:
                seen[mark] = (h, float(body.view().vertical_speed))
        if len(seen) == 2:
            world.n_steps = world.k
    world.on_progress = watch
    world.run()
    names = [e["name"] for e in body.events]
    assert names[:4] == ["liftoff", "apogee", "parachute_deployed", "parachute_inflated"]
    for mark, (h, vertical) in seen.items():
        g = somigliana(LATITUDE) - 3.086e-6 * h
        terminal = math.sqrt(2 * MASS * g / (density(h) * CDS))
        print(f"\n[parachute] at {h:.1f} m: falling {-vertical:.4f} m/s, terminal {terminal:.4f} m/s")
        assert -vertical == pytest.approx(terminal, rel=0.01)
        assert -vertical == pytest.approx(terminal, rel=1e-3)        # the lag is ~2e-4


def test_the_drag_area_waits_out_the_lag_then_grows_linearly():
    world = build_world(load(scenario([{"name": "drogue", "cd_s": "1 m2", "lag": "1.5 s",
                                         "inflation": "0.8 s", "deploy": "program"}])))
    chute = world.bodies[0].vehicle.arrays.chute
    chute[0, CH_DEPLOYED] = 10.0
    for t, expected in ((9.0, 0.0), (11.5, 0.0), (11.9, 0.5), (12.3, 1.0), (50.0, 1.0)):
        assert inflated(t, chute, 0) == pytest.approx(expected, abs=1e-12)


def test_a_canopy_drifts_with_the_wind():
    knots = 8.0 / (1852.0 / 3600.0)            # a westerly of 8 m/s at every height
    wind = {"kind": "sounding", "columns": {"PRES": [1013.0, 850.0, 500.0], "HGHT": [0.0, 1500.0, 5600.0],
                                            "TEMP": [15.0, 5.0, -20.0], "DRCT": [270.0] * 3,
                                            "SKNT": [knots] * 3}}
    data = scenario([{"name": "main", "cd_s": f"{CDS} m2", "lag": "0.5 s", "inflation": "1 s",
                      "deploy": "apogee"}], duration="60 s", weather=wind)
    world = build_world(load(data))
    world.run()
    east = float(world.bodies[0].view().surface_velocity @ world.bodies[0].view().enu[0])
    print(f"\n[parachute] under the canopy in a westerly of 8 m/s: drifting east at {east:.3f} m/s")
    assert east == pytest.approx(8.0, abs=0.05)


def test_a_body_without_contact_points_comes_down_on_the_sites_flat_ground():
    """With ``ground_height`` the ground is that high above the ellipsoid: the falling body
    ends in an impact there (its centre of mass below it, within one step's fall)."""
    data = scenario([{"name": "main", "cd_s": f"{CDS} m2", "lag": "1 s", "inflation": "2 s",
                      "deploy": "apogee"}], height="1100 m", duration="60 s")
    data["site"]["ground_height"] = "1000 m"
    world = build_world(load(data))
    world.run()
    body = world.bodies[0]
    assert body.events[-1]["name"] == "impact" and not body.flying
    assert 1000.0 - 6.5 * 0.05 < world.where(body)[2] < 1000.0


def test_a_main_that_releases_the_drogue_descends_on_its_own_drag_area():
    """``releases: [drogue]``: the drogue is cut away when the main begins to inflate, so
    the descent is the main's terminal speed alone (not the two drag areas added)."""
    chutes = [{"name": "drogue", "cd_s": "1 m2", "lag": "0.5 s", "inflation": "0.5 s", "deploy": "apogee"},
              {"name": "main", "cd_s": f"{CDS} m2", "lag": "1 s", "inflation": "2 s", "releases": ["drogue"],
               "deploy": {"after": {"event": "parachute_inflated", "delay": "3 s"}}}]
    world = build_world(load(scenario(chutes)))
    body = world.bodies[0]
    seen = {}

    def watch(t):
        h = world.where(body)[2]
        if h < 1000.0 and not seen:
            seen["at"] = (h, float(body.view().vertical_speed))
            world.n_steps = world.k
    world.on_progress = watch
    world.run()
    events = {e["name"]: e for e in body.events}
    main = next(e for e in body.events if e["name"] == "parachute_deployed" and e["parachute"] == "main")
    assert events["parachute_released"]["parachute"] == "drogue"
    assert events["parachute_released"]["at_s"] == pytest.approx(main["time_s"] + 1.0, abs=1e-12)
    h, vertical = seen["at"]
    g = somigliana(LATITUDE) - 3.086e-6 * h
    assert -vertical == pytest.approx(math.sqrt(2 * MASS * g / (density(h) * CDS)), rel=1e-3)


def test_a_body_swings_under_its_canopy_at_the_pendulum_frequency():
    """The canopy pulls at the shock cord's attachment, the stage's top by default, 0.5 m
    above this body's centre of mass. Started 5 deg off the vertical, the body swings
    about its centre of mass as a damped pendulum: the drag ``F = m g`` at the terminal
    speed, always along the airflow (up), pulls the top back, ``I theta'' = -d m g sin
    theta - I theta'/tau`` (tau the canopy's rate damping, 1 s), so it swings at
    ``omega = sqrt(d m g / I - 1/(4 tau^2))``, ``I = m (r^2/2 + L^2/12)`` the thin shell's
    pitch inertia (the centre of mass falls straight: the drag does not depend on the
    attitude of a body without aerodynamics). The period is measured from the zero
    crossings of the swing's rate (free of the 1e-4 rad lean of the airflow that the
    Coriolis drift gives) over 4-10 s, amplitude 1.8 to 0.1 deg (sin theta ~ theta
    within 2e-4), sampled at every 50 ms step (1/17 of a period)."""
    data = scenario([{"name": "main", "cd_s": f"{CDS} m2", "lag": "0 s", "inflation": "0.1 s",
                      "deploy": "apogee"}], duration="10 s")
    data["telemetry"] = {"rate": 20}                               # a sample every step
    data["mission"]["start"]["site"]["elevation"] = "85 deg"       # tilted towards the pad azimuth
    world = build_world(load(data))
    body = world.bodies[0]
    trace = []

    def watch(t):
        view = body.view()
        axis = quat_rotate(body.y[Q:Q + 4], np.array([1.0, 0.0, 0.0]))
        rates = quat_rotate(body.y[Q:Q + 4], body.y[W:W + 3])        # inertial axes
        trace.append((t, axis, rates, view.enu[2], view.geodetic[2]))
    world.on_progress = watch
    world.run()
    t = np.array([row[0] for row in trace])
    _, axis0, _, up0, _ = trace[0]
    assert math.degrees(math.acos(axis0 @ up0)) == pytest.approx(5.0, abs=1e-3)
    hinge = np.cross(up0, axis0) / np.linalg.norm(np.cross(up0, axis0))     # the swing's axis
    swing = np.array([row[2] @ hinge for row in trace])
    late = t >= 4.0
    t, swing = t[late], swing[late]
    cross = np.nonzero(np.sign(swing[1:]) != np.sign(swing[:-1]))[0]
    at = t[cross] - swing[cross] * (t[cross + 1] - t[cross]) / (swing[cross + 1] - swing[cross])
    period = 2.0 * float(np.mean(np.diff(at)))
    radius, length, arm = 0.1, 1.0, 0.5
    inertia = MASS * (radius ** 2 / 2 + length ** 2 / 12)
    g = somigliana(LATITUDE) - 3.086e-6 * float(np.mean([row[4] for row in trace]))
    omega = math.sqrt(arm * MASS * g / inertia - 1.0 / (4.0 * CANOPY_RATE_TIME ** 2))
    print(f"\n[parachute] swing period {period:.5f} s over {len(at)} crossings, the damped "
          f"pendulum's {2 * math.pi / omega:.5f} s")
    assert len(at) >= 10
    assert period == pytest.approx(2 * math.pi / omega, rel=1e-3)


def test_a_finned_rocket_hangs_tail_down_and_falls_with_its_own_axial_drag():
    """A finned rocket falling nose first turns to hang from its canopy's attachment (its
    top): tail down within 1 deg, so its own drag is axial, tail first (``C_A`` 0.85
    subsonic, docs/physics.md#axial-force), on its 0.2 m section. It then falls at
    ``sqrt(2 m g / (rho (C_D S + C_A S_ref)))``: 1.3 % more drag area than the canopy's,
    0.7 % slower than the canopy alone (whose speed it still meets within 1 %)."""
    data = scenario([{"name": "main", "cd_s": "2 m2", "lag": "3 s", "inflation": "1 s",
                      "deploy": "apogee"}])
    data["mission"]["start"]["site"].update(velocity=[0, 5, 20], elevation="75 deg")
    data["vehicle"] = finned(data["vehicle"]["stages"][0]["parachutes"])
    world = build_world(load(data))
    body = world.bodies[0]
    seen = {}

    def watch(t):
        view = body.view()
        up = float(quat_rotate(body.y[Q:Q + 4], np.array([1.0, 0.0, 0.0])) @ view.enu[2])
        if "nose down" not in seen and up < -0.5:
            seen["nose down"] = t                   # weathercocked on the way down
        if view.geodetic[2] < 1000.0:
            seen["at"] = (view.geodetic[2], float(view.vertical_speed), up)
            world.n_steps = world.k
    world.on_progress = watch
    world.run()
    h, vertical, up = seen["at"]
    assert "nose down" in seen
    assert math.degrees(math.acos(min(1.0, up))) < 1.0
    g = somigliana(LATITUDE) - 3.086e-6 * h
    own = 0.85 * math.pi / 4 * 0.2 ** 2
    hanging = math.sqrt(2 * 8.0 * g / (density(h) * (2.0 + own)))
    canopy = math.sqrt(2 * 8.0 * g / (density(h) * 2.0))
    print(f"\n[parachute] hanging at {h:.1f} m: falling {-vertical:.4f} m/s, terminal with the body's "
          f"axial drag {hanging:.4f}, canopy alone {canopy:.4f} m/s")
    assert -vertical == pytest.approx(hanging, rel=1e-3)
    assert -vertical == pytest.approx(canopy, rel=0.01)


def finned(chutes, mass="8 kg") -> dict:
    """A finned rocket 1.5 m long, 0.2 m across, with the default body contact springs."""
    return {"name": "finned", "stages": [{
        "name": "body", "length": "1.5 m", "diameter": "0.2 m", "structure_mass": mass,
        "parachutes": chutes}],
        "aero": {"nose": {"length": "0.3 m", "shape": "ogive"},
                 "fins": [{"stage": "body", "count": 4, "position": "0 m", "root_chord": "0.25 m",
                           "tip_chord": "0.1 m", "span": "0.15 m", "sweep": "0.15 m"}]}}


@pytest.mark.parametrize("mass, cds", [("8 kg", 2.0), ("20 kg", 5.0)])
def test_a_rocket_under_its_canopy_touches_down_tail_first_on_the_default_springs(mass, cds):
    """Dropped from 120 m over the site's flat ground (1 000 m) under its canopy, a light
    rocket touches down on its base at the terminal speed (as above, with its own axial
    drag, within 1 %: the touchdown's speed is carried from the step before the contact)
    and is recovered: a touchdown with its landing figures, not a breakup or an impact.
    The default body springs are softened for its dry mass (1e4 N/m per kg): the 2e7 N/m
    of a launcher's would throw it back up in the first contact step."""
    data = scenario([{"name": "main", "cd_s": f"{cds} m2", "lag": "0.5 s", "inflation": "0.5 s",
                      "deploy": "apogee"}], height="1100 m", duration="60 s")
    data["site"]["ground_height"] = "1000 m"
    data["vehicle"] = finned(data["vehicle"]["stages"][0]["parachutes"], mass)
    world = build_world(load(data))
    world.run()
    body = world.bodies[0]
    names = [e["name"] for e in body.events]
    assert "breakup" not in names and "impact" not in names
    touchdown = body.events[-1]
    assert touchdown["name"] == "touchdown" and not body.flying
    m = float(mass.split()[0])
    g = somigliana(LATITUDE) - 3.086e-6 * 1000.0
    terminal = math.sqrt(2 * m * g / (density(1000.0) * (cds + 0.85 * math.pi / 4 * 0.2 ** 2)))
    print(f"\n[parachute] {mass} rocket: touchdown {-touchdown['vertical_speed_m_s']:.4f} m/s, "
          f"terminal {terminal:.4f} m/s, tilt {touchdown['tilt_deg']:.2f} deg")
    assert -touchdown["vertical_speed_m_s"] == pytest.approx(terminal, rel=0.01)
    assert touchdown["tilt_deg"] < 2.0
    assert {"latitude_deg", "longitude_deg", "descent_time_s", "drift_time_s"} <= set(touchdown)
