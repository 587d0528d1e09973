"""A launch rail: the vehicle slides along it until its last button leaves, then flies free.

Reference: a body of constant mass ``m`` pushed along an inclined rail by a
constant thrust ``T`` with no drag, against gravity ``g`` at the rail's
inclination ``theta`` above the horizon, leaves a rail of travel ``L`` at

    v = sqrt(2 L (T/m - g sin theta)),   t = sqrt(2 L / (T/m - g sin theta))

(uniform acceleration). ``g`` is the site's effective gravity (gravity with
the centrifugal term), WGS84 normal gravity by Somigliana's formula (NIMA
TR8350.2 eq. 4-1), written out here; the rail is fixed to the turning
ground, whose Coriolis push is across the rail and so does not count. The
test rocket has no aerodynamics (no drag) and a motor of constant thrust
that burns 1 ug of propellant (constant mass to 1e-10), rising from nothing to
its thrust over 10 us (a shift of 5 us, counted in the expected time). The
flights are 2 s long at the 20 ms step.
"""

import math

import pytest

from rocketsim.scenario.load import load
from rocketsim.sim.build import build_world

LATITUDE = 32.99
MASS, THRUST, RAIL, BUTTON = 20.0, 1000.0, 5.2, 0.4          # kg, N, m, m


def somigliana(latitude_deg: float) -> float:
    """WGS84 normal gravity on the ellipsoid (m/s^2), NIMA TR8350.2 eq. 4-1."""
    s2 = math.sin(math.radians(latitude_deg)) ** 2
    return 9.7803253359 * (1 + 0.00193185265241 * s2) / math.sqrt(1 - 0.00669437999013 * s2)


def scenario(inclination: float, ignition: float = 0.0, aero: bool = False) -> dict:
    stage = {"name": "rocket", "length": "2 m", "diameter": "0.1 m", "structure_mass": f"{MASS - 0.5} kg",
             "motors": [{"name": "test motor", "thrust": [[1e-5, THRUST], [1.5, THRUST], [1.50001, 0.0]],
                         "position": "0 m", "diameter": "50 mm", "length": "0.3 m",
                         "propellant_mass": "1e-9 kg", "total_mass": "0.500000001 kg",
                         "ignition": f"{ignition} s"}]}
    vehicle = {"name": "rail rocket", "stages": [stage]}
    if aero:
        vehicle["aero"] = {"nose": {"length": "0.4 m", "shape": "ogive"},
                           "fins": [{"stage": "rocket", "count": 4, "position": "0.3 m", "root_chord": "0.2 m",
                                     "tip_chord": "0.1 m", "span": "0.1 m", "sweep": "0.05 m"}],
                           "body_contact_stiffness": 2e5, "body_contact_damping": 2e3}
    return {"name": "rail", "vehicle": vehicle,
            "site": {"name": "range", "latitude": f"{LATITUDE} deg", "longitude": "-106.975 deg",
                     "height": "1380 m"},
            "mission": {"epoch": "2026-06-01T12:00:00Z", "duration": "2 s",
                        "start": {"site": {"rail": {"length": f"{RAIL} m", "inclination": f"{inclination} deg",
                                                    "heading": "30 deg", "last_button": f"{BUTTON} m"}}}}}


@pytest.mark.parametrize("inclination", [90.0, 80.0])
def test_off_rail_speed_is_that_of_uniform_acceleration_along_the_rail(inclination):
    world = build_world(load(scenario(inclination, ignition=0.5)))
    world.run()
    body = world.bodies[0]
    off = next(e for e in body.events if e["name"] == "off_rail")
    # WGS84 normal gravity at the pad's height (free-air gradient 3.086e-6 /s^2 per m)
    g = somigliana(LATITUDE) - 3.086e-6 * 1380.0
    a = THRUST / MASS - g * math.sin(math.radians(inclination))
    travel = RAIL - BUTTON
    speed, duration = math.sqrt(2 * travel * a), math.sqrt(2 * travel / a)
    print(f"\n[rail] {inclination:g} deg: off the rail at T+{off['at_s']:.5f} s, {off['surface_speed_m_s']:.5f} m/s; "
          f"uniform acceleration T+{0.5 + duration:.5f} s, {speed:.5f} m/s")
    assert off["surface_speed_m_s"] == pytest.approx(speed, rel=2e-5)
    assert off["at_s"] == pytest.approx(0.5 + 5e-6 + duration, rel=2e-5)
    assert "stability_margin_cal" not in off            # no aerodynamics, no centre of pressure


def test_the_rail_holds_the_rocket_at_its_foot_before_ignition_and_keeps_its_attitude():
    world = build_world(load(scenario(80.0, ignition=1.0)))
    body = world.bodies[0]
    start = body.y.copy()
    q0 = body.vehicle.arrays.rail.copy()
    world.n_steps = 45                       # 0.9 s: waiting for the motor
    world.run()
    from rocketsim.frames.earth_fixed import eci_to_ecef
    moved = eci_to_ecef(body.y[0:3], body.t) - eci_to_ecef(start[0:3], 0.0)
    assert float((moved ** 2).sum()) ** 0.5 < 1e-6       # at rest on the turning ground
    assert q0[0] == 1.0 and body.vehicle.arrays.rail[0] == 1.0
    assert not any(e["name"] == "off_rail" for e in body.events)


def test_off_the_rail_a_finned_rocket_reports_its_static_margin():
    world = build_world(load(scenario(85.0, aero=True)))
    world.run()
    body = world.bodies[0]
    off = next(e for e in body.events if e["name"] == "off_rail")
    aero = body.vehicle.arrays.aero
    # Barrowman: the centre of pressure of nose and fins, their slopes as weights
    nose_slope, nose_x = 2 * aero.ref[4], aero.ref[3]
    fins = aero.fin
    x_cp = (nose_slope * nose_x + (fins[:, 1] * fins[:, 0]).sum()) / (nose_slope + fins[:, 1].sum())
    x_cm = body.vehicle.mass_properties(body.y)[1]
    assert off["stability_margin_cal"] == pytest.approx((x_cm - x_cp) / 0.1, rel=1e-9)
    assert off["stability_margin_cal"] > 1.0         # a stable rocket: the fins well aft


def test_a_rail_under_a_rigid_body_is_an_input_error():
    from rocketsim.errors import InputError
    data = scenario(85.0)
    data["vehicle"] = {"name": "block", "rigid_body": {"mass": "10 kg", "inertia": [1, 1, 1]}}
    with pytest.raises(InputError, match="goes with a staged vehicle"):
        load(data)
