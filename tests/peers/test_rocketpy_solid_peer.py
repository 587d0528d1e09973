"""The hobby rocket (solid motor, rail, drogue and main) flown here and in RocketPy.

RocketPy (https://github.com/RocketPy-Team/RocketPy, a peer used only in
tests) flies vehicles/hobby-rocket.yaml's figures: the same 4895L1395 file,
the same five BATES grains burning on their cores only
(``only_radial_burn``), the case as the motor's dry mass with a thin shell's
inertia, the rest of the rocket's mass, centre of mass and inertia from our
own mass model (the inputs), our default axial-force table as its drag
curve, the same nose and fins, the same 5.2 m rail at 85 deg towards north
(no rail buttons there and ``last_button: 0`` here: the base leaves the top of
the rail in both), the standard atmosphere and no wind, and the same
parachutes (RocketPy has no inflation time: its lag is ours plus half the
inflation, the centroid of our linear growth). The pad is on the ellipsoid,
RocketPy's ground at elevation 0.

Agreement required: off-rail speed within 1 %, apogee within 3 % (as the
liquid peer test), the touchdown speed under the main within 3 %, once the
one difference of the descents is accounted for: here the drogue stays on
its harness when the main opens (drag areas add), RocketPy flies each
parachute alone, the latest replacing the one before; so RocketPy's speed
under the main alone is scaled by ``sqrt(C_D S_main / (C_D S_main + C_D S_drogue))``;
and flown again with the main releasing the drogue (``releases``), the
speeds agree unscaled.
What differs and is not matched: RocketPy's Earth does not turn and its
gravity is Somigliana's, not point mass + J2; after the rail, RocketPy
flies from the upper button's exit, we do from the base's; under its
canopies RocketPy flies a point mass with the parachute's drag only, we keep
the body's own (small) drag.
"""

import math
from pathlib import Path

import numpy as np
import pytest

rocketpy = pytest.importorskip("rocketpy")

from rocketsim.scenario.load import load  # noqa: E402
from rocketsim.scenario.yaml_source import read_yaml  # noqa: E402
from rocketsim.sim.build import build_world  # noqa: E402
from rocketsim.vehicle.aero import NOSE_FIRST_CA, NOSE_FIRST_MACH  # noqa: E402
from tests.aero_vehicles import shipped  # noqa: E402
from tests.rocketpy_rockets import rocketpy_rocket  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
LAT, LON = 32.99, -106.975
RAIL, INCLINATION, HEADING = 5.2, 85.0, 0.0


def _ours(release_drogue: bool = False):
    vehicle = read_yaml(ROOT / "vehicles" / "hobby-rocket.yaml").data
    if release_drogue:      # RocketPy's way: the main replaces the drogue
        vehicle["stages"][0]["parachutes"][1]["releases"] = ["drogue"]
    data = {"name": "peer", "vehicle": vehicle,
            "site": {"name": "pad", "latitude": f"{LAT} deg", "longitude": f"{LON} deg", "height": "0 m"},
            "mission": {"epoch": "2026-06-13T15:00:00Z", "duration": "400 s",
                        "start": {"site": {"rail": {"length": f"{RAIL} m", "inclination": f"{INCLINATION} deg",
                                                    "heading": f"{HEADING} deg"}}}}}
    world = build_world(load(data, base_dir=ROOT / "vehicles"))    # the motor file beside the vehicle
    world.run()
    return {e["name"] + (f":{e['parachute']}" if "parachute" in e else ""): e for e in world.bodies[0].events}


def _rocketpy():
    from rocketpy import Environment, Flight
    drag = list(zip(NOSE_FIRST_MACH.tolist(), NOSE_FIRST_CA.tolist()))
    rocket, _ = rocketpy_rocket(shipped("hobby-rocket.yaml"), drag, parachutes=True)
    env = Environment(latitude=LAT, longitude=LON, elevation=0.0)
    env.set_atmospheric_model(type="standard_atmosphere")
    return Flight(rocket=rocket, environment=env, rail_length=RAIL, inclination=INCLINATION,
                  heading=HEADING, rtol=1e-8, max_time=400)


def test_off_rail_apogee_and_landing_agree_with_rocketpy():
    ours = _ours()
    flight = _rocketpy()
    off, apogee, touchdown = ours["off_rail"], ours["apogee"]["height_agl_m"], ours["touchdown"]
    peer_off = float(flight.out_of_rail_velocity)
    peer_apogee = float(flight.apogee - flight.env.elevation)
    drogue, main = (c.cd_s for c in shipped("hobby-rocket.yaml").stages[0].parachutes)
    peer_landing = abs(float(flight.impact_velocity)) * math.sqrt(main / (main + drogue))
    print(f"\n[peer] off the rail: rocketsim {off['surface_speed_m_s']:.2f} m/s, RocketPy {peer_off:.2f} m/s; "
          f"apogee {apogee:.1f} m against {peer_apogee:.1f} m ({100 * (apogee / peer_apogee - 1):+.2f} %); "
          f"touchdown {-touchdown['vertical_speed_m_s']:.2f} m/s against {peer_landing:.2f} m/s")
    assert off["surface_speed_m_s"] == pytest.approx(peer_off, rel=0.01)
    assert apogee == pytest.approx(peer_apogee, rel=0.03)
    assert -touchdown["vertical_speed_m_s"] == pytest.approx(peer_landing, rel=0.03)
    assert np.isfinite(touchdown["drift_time_s"])
    # with the drogue released by the main, as RocketPy flies them: no scaling
    released = _ours(release_drogue=True)["touchdown"]
    print(f"[peer] the drogue released by the main: touchdown {-released['vertical_speed_m_s']:.2f} m/s "
          f"against {abs(float(flight.impact_velocity)):.2f} m/s")
    assert -released["vertical_speed_m_s"] == pytest.approx(abs(float(flight.impact_velocity)), rel=0.03)
