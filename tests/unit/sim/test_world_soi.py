"""The world flies the n-body field and hands over at spheres of influence.

A body starts in Earth's ECI 600 km outside the Moon's sphere of influence
(Laplace radius ``a (mu_M / mu_E)^(2/5)`` = 66 200 km,
docs/physics.md#spheres-of-influence) closing on the Moon at 1 km/s. References:
the awake RK4 kernel of the same field flown without any handover in Earth's
frame (:func:`rocketsim.dynamics.rk4.advance`), the states re-expressed by
:func:`rocketsim.dynamics.central.to_frame` (ephemeris positions and IAU pole
rotations computed from the Moon's side, not the Earth's); DOP853 of the
lunar-centred field (:mod:`rocketsim.dynamics.reference`) for a cruise
that crosses the boundary.
"""

import numpy as np

from rocketsim.dynamics import soi
from rocketsim.dynamics.rk4 import advance
from rocketsim.dynamics.third_bodies import bodies_at, field_of, nbody_flag
from rocketsim.scenario.load import load
from rocketsim.dynamics.central import nbody_field, to_frame
from rocketsim.sim.build import build_world
from rocketsim.timescales import Epoch
import datetime as dt

EPOCH = "2026-11-26T12:00:00Z"


def approach_state(gap: float = 600e3, closing: float = 1000.0):
    """Earth-ECI position (m) and velocity (m/s) ``gap`` outside the Moon's sphere,
    closing on the Moon at ``closing`` m/s (relative to the Moon)."""
    epoch = Epoch.from_utc(dt.datetime(2026, 11, 26, 12, tzinfo=dt.timezone.utc))
    fp = nbody_field("earth", epoch.jd_tt(), epoch.gmst())
    s, u = bodies_at(fp, 0.0)
    moon, moon_v = s[2], u[2]
    out = moon / np.linalg.norm(moon)              # on the far side of the Moon from Earth
    side = np.cross(out, (0.0, 0.0, 1.0))
    side /= np.linalg.norm(side)
    r = moon + (soi.SOI["moon"] + gap) * out
    v = moon_v - closing * (0.98 * out + 0.2 * side)
    return r, v


def world_for(write, scenario, program=None, duration="900 s", gap=600e3):
    path = scenario(program, duration=duration)
    r, v = approach_state(gap)
    write("mission.yaml", f"""\
        epoch: {EPOCH}
        start:
          state:
            position: {r.tolist()}
            velocity: {v.tolist()}
        duration: {duration}
        gravity: n-body
        """)
    world = build_world(load(path))
    records = []
    body = world.bodies[0]
    world.on_progress = lambda t: records.append((body.t, body.y.copy(), body.p.copy(), body.central))
    return world, records


def test_handover_to_the_moon_keeps_position_and_velocity_continuous(write, scenario):
    # a body nobody flies: rails in its own field (bit-identical to awake); 600 km at
    # ~1 km/s crosses the boundary after ~10 min; 20 ms steps, batches of 0.1 s
    world, records = world_for(write, scenario)
    body = world.bodies[0]
    y0, p0 = body.y.copy(), body.p.copy()
    world.run()
    assert body.central == "moon"
    [handover] = [e for e in body.events if e["name"] == "soi_handover"]
    assert (handover["from"], handover["to"]) == ("earth", "moon")
    i = next(i for i, rec in enumerate(records) if rec[3] == "moon")
    t_a, y_a, p_a, _ = records[i - 1]          # the last state about Earth
    assert t_a < handover["time_s"] <= records[i][0]
    # at the handover: the Moon-centred state is the same point seen from the Moon
    assert abs(np.linalg.norm(y_a[:3] - bodies_at(field_of(p_a), t_a)[0][2]) - soi.SOI["moon"]) < 1e4
    # ten batches (1 s) later, back in Earth's frame, against a flight that never handed over
    t_b, y_b, p_b, _ = records[i + 9]
    k_a, k_b = round(t_a / world.h), round(t_b / world.h)
    reference, _ = advance(y_a, k_a, world.h, k_b - k_a, p_a.copy(), None, nbody_flag(p_a))
    r, v = to_frame(y_b[:3], y_b[3:6], p_b, p_a, t_b)
    print(f"\n[handover] t = {handover['time_s']:.2f} s, 1 s later: "
          f"{np.linalg.norm(r - reference[:3]):.2e} m, {np.linalg.norm(v - reference[3:6]):.2e} m/s")
    assert np.linalg.norm(r - reference[:3]) < 1e-9 * np.linalg.norm(reference[:3])
    assert np.linalg.norm(v - reference[3:6]) < 1e-9 * np.linalg.norm(reference[3:6])
    # the frame's z is the Moon's IAU pole (at the handover)
    rot = field_of(p_b)[3:12].reshape(3, 3)
    np.testing.assert_allclose(rot[:, 2], soi.frame_rotation("moon", field_of(p_b)[1] + t_b / 86400)[:, 2],
                               atol=1e-12)
    # and the Moon's gravity is central
    assert p_b[4] == soi.CENTRAL["moon"][0] and body.mu == soi.CENTRAL["moon"][0]
    assert p0[4] == soi.CENTRAL["earth"][0] and y0[0] != body.y[0]


def test_positions_about_mars_read_as_planetocentric_latitude_longitude_and_height():
    # reference: the IAU body-fixed -> J2000 rotation (rocketsim.bodies.orientation,
    # itself checked against the IAU WG 2015 report's matrices) of a body-fixed point
    import math
    from rocketsim.bodies.orientation import body_to_j2000
    from rocketsim.dynamics.central import planetocentric
    jd = 2461371.5
    to_frame_axes = soi.frame_rotation("mars", jd).T @ body_to_j2000("mars", jd)
    for lat, lon in ((0.3, 0.0), (-1.2, 45.0), (0.0, -120.0)):
        radius = 3.5e6
        fixed = radius * np.array([math.cos(math.radians(lon)) * math.cos(lat),
                                   math.sin(math.radians(lon)) * math.cos(lat), math.sin(lat)])
        got_lat, got_lon, height = planetocentric(to_frame_axes @ fixed, "mars", jd)
        assert abs(got_lat - lat) < 1e-12 and abs(math.degrees(got_lon) - lon) < 1e-9
        a, b = soi.CENTRAL["mars"][1], soi.CENTRAL["mars"][3]
        surface = a * b / math.hypot(b * math.cos(lat), a * math.sin(lat))
        assert abs(height - (radius - surface)) < 1e-6


def test_about_the_moon_a_sleeping_body_follows_the_awake_path_to_the_bit(write, scenario):
    # Sleep rails about the Moon and Mars fly the awake field's arithmetic, so they must be
    # bit-identical to awake (docs/physics.md#sleep-rails). The same body in a
    # 100 km lunar orbit flies 200 s once asleep (sleep rails, the full field held per 5 s)
    # and once stepping its program every step (awake RK4 of the derivative, the field
    # held by the step); the two must agree to the last bit
    finals = []
    for program, asleep in (("def main(fc):\n    fc.sleep(1e9)\n", True),
                            ("def main(fc):\n    while True:\n        fc.step()\n", False)):
        path = scenario(program, duration="200 s")
        write("vehicle.yaml", "name: spinner\nrigid_body:\n  mass: 10 kg\n  inertia: [0.15, 0.12, 0.12]\n")
        write("mission.yaml", f"""\
            epoch: {EPOCH}
            start:
              orbit: {{body: moon, altitude: 100 km, inclination: 80 deg, raan: 30 deg}}
            duration: 200 s
            initial_rates: [0.0, 0.0, 0.0]
            """)
        world = build_world(load(path))
        body = world.bodies[0]
        railed = []
        world.on_progress = lambda t: railed.append(world.schedule.on_rails(body))
        world.run()
        assert body.central == "moon" and body.t == 200.0
        assert all(railed) if asleep else not any(railed)
        finals.append(body.y[:6].copy())
    np.testing.assert_array_equal(finals[0], finals[1])
