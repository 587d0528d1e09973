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

from rocketsim.scenario.load import load
from rocketsim.sim.build import build_world
from rocketsim.vehicle.parachutes import CH_DEPLOYED, inflated

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
                     "height": height},
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
