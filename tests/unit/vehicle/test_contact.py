"""Ground contact (docs/physics.md#ground-contact): a lander dropped onto its legs on
the WGS84 ground.

References: energy (the rotating-frame Jacobi energy of a body on a turning
Earth can only fall when the ground's forces are springs, dampers and
friction); the static deflection of a spring ``m gamma / (n k)`` with
``gamma`` Somigliana's normal gravity (WGS84, NIMA TR8350.2 eq. 4-1: the
surface's effective gravity, gravity plus centrifugal, normal to the
ellipsoid); free fall ``v = sqrt(v0^2 + 2 gamma h)``; and the stability limit
of classical RK4 (|lambda h| about 2.8; e.g. Hairer & Wanner, Solving ODEs II,
fig. IV.2.1).
"""

import math

import numpy as np
import pytest

from rocketsim.constants import EARTH_J2, EARTH_MU, EARTH_OMEGA, EARTH_RADIUS_EQ
from rocketsim.dynamics.rk4 import rk4_step, step
from rocketsim.frames.geodetic import enu_basis, geodetic_to_ecef
from rocketsim.frames.quaternion import quat_from_matrix
from rocketsim.sim.vehicle_checks import VehicleChecks
from rocketsim.sim.world import World
from rocketsim.vehicle.contact import contact_heights, footprint, tip_over_angle
from rocketsim.vehicle.build import build
from tests.aero_vehicles import corotating, earth_params, shipped

LAT, LON = math.radians(28.5), math.radians(-80.6)
K_LEG = 8.5e7                      # N/m, vehicles/lander.yaml
N_LEGS = 4


def somigliana(lat):
    """Normal gravity on the WGS84 ellipsoid (m/s^2), Somigliana (NIMA TR8350.2 eq. 4-1)."""
    s2 = math.sin(lat) ** 2
    return 9.7803253359 * (1 + 0.00193185265241 * s2) / math.sqrt(1 - 0.00669437999013 * s2)


@pytest.fixture(scope="module")
def lander():
    model = build(shipped("lander.yaml"))
    mass, x_cm = model.mass_properties(model.state([0, 0, 0], [0, 0, 0]))[:2]
    enu = enu_basis(LAT, LON)
    up = enu[2]
    axes = np.column_stack((up, enu[0], np.cross(up, enu[0])))        # body x up
    # the feet are 1.2 m below the base: the centre of mass 2 m + 1.2 m + x_cm up
    r = np.array(geodetic_to_ecef(LAT, LON, 2.0 + 1.2 + x_cm))
    y = model.state(r, corotating(r) - 2.0 * up, q=quat_from_matrix(axes),
                    w=axes.T @ np.array([0.0, 0.0, EARTH_OMEGA]))
    return model, y, mass, up


def jacobi_energy(model, y, p, mass):
    """Energy in the frame turning with the ground: relative kinetic energy, gravity (point mass
    + J2) and centrifugal potential, and the legs' springs (J)."""
    r = y[0:3]
    v = y[3:6] - corotating(r)
    rn = np.linalg.norm(r)
    s = r[2] / rn
    potential = (-EARTH_MU / rn + EARTH_MU * EARTH_J2 * EARTH_RADIUS_EQ ** 2 * (3 * s * s - 1) / (2 * rn ** 3)
                 - 0.5 * EARTH_OMEGA ** 2 * (r[0] ** 2 + r[1] ** 2))
    h = contact_heights(y, p, model)[:N_LEGS]
    return 0.5 * mass * v @ v + mass * potential + 0.5 * K_LEG * np.sum(np.minimum(h, 0.0) ** 2)


@pytest.mark.parametrize("h", [0.02, 0.1])
def test_lander_dropped_from_2_m_at_2_m_s_settles_on_its_legs(lander, h):
    # at 20 ms the seed's four 5 ms sub-steps; a larger headless step (0.1 s) keeps
    # sub-steps of 5 ms at most near the ground, and the drop settles the same way
    model, y, mass, up = lander
    p = earth_params()
    assert contact_heights(y, p, model)[:N_LEGS] == pytest.approx(2.0, abs=1e-4)
    energies = [jacobi_energy(model, y, p, mass)]
    for k in range(round(3.0 / h)):                        # 3 s (sub-stepped near the ground)
        y = step(y, h * k, h, p, model.arrays)
        energies.append(jacobi_energy(model, y, p, mass))
    # energy never increases (float64 resolution of ~1e12 J: 1 mJ), and the drop's
    # kinetic and potential energy has gone into the dampers
    assert np.max(np.diff(energies)) < 1e-3
    assert energies[0] - energies[-1] == pytest.approx(0.5 * mass * (2.0 ** 2 + 2 * somigliana(LAT) * 2.0),
                                                       rel=0.01)
    # at rest, each leg compressed by its share of the weight (1 mm tolerance required;
    # it holds to 1e-7 m)
    deflection = -contact_heights(y, p, model)[:N_LEGS]
    static = mass * somigliana(LAT) / (N_LEGS * K_LEG)
    assert np.max(np.abs(deflection - static)) < 1e-3
    assert deflection == pytest.approx(static, rel=1e-3)
    assert np.linalg.norm(y[3:6] - corotating(y[0:3])) < 1e-4


def test_the_same_drop_at_20_ms_without_sub_steps_is_unstable(lander):
    # lambda h of the legs' modes at 20 ms (vertical 150 rad/s -> 3.0, rocking 245 ->
    # 4.9) lies outside RK4's stability region: the contact pumps energy in.
    model, y, mass, up = lander
    p = earth_params()
    e0 = jacobi_energy(model, y, p, mass)
    peak = -math.inf
    for k in range(100):
        y = rk4_step(y, 0.02 * k, 0.02, p, model.arrays)
        peak = max(peak, jacobi_energy(model, y, p, mass))
    assert peak > e0 + 1e6                  # megajoules from nowhere: the lander is thrown off


class _World:
    telemetry = None
    end_flight = World.end_flight       # the event, then the body's flight ends

    def __init__(self):
        self.events = []

    def event(self, body, name, figures):
        self.events.append((name, figures))


class _Body:
    def __init__(self, model, y, p):
        self.vehicle, self.y, self.p, self.t, self.flying = model, y, p, 0.0, True
        self.mu, self.central = EARTH_MU, "earth"
        from rocketsim.atmosphere.day import standard_table
        table = standard_table()
        self.atmosphere = lambda: table

    @property
    def position(self):
        return self.y[0:3]

    @property
    def attitude(self):
        return self.y[6:10]

    def view(self):
        from rocketsim.flight.readings import StateView
        return StateView(self.t, self.y[0:3].copy(), self.y[3:6].copy(), self.y[6:10].copy(),
                         self.y[10:13].copy(), self.atmosphere, self.mu)


def test_touchdown_event_reports_speed_tilt_and_distance_to_the_pad(lander):
    model, y, mass, up = lander
    p = earth_params()
    pad = np.array(geodetic_to_ecef(LAT, LON, 0.0)) + 3.0 * enu_basis(LAT, LON)[0]   # 3 m east
    checks = VehicleChecks(pad_ecef=pad)
    body, world = _Body(model, y, p), _World()
    for k in range(60):
        checks.after_step(world, body, 0.02)
        body.y = step(body.y, 0.02 * k, 0.02, p, model.arrays)
        body.t = 0.02 * (k + 1)
    names = [name for name, _ in world.events]
    assert names == ["touchdown"]
    figures = world.events[0][1]
    # free fall over the last 2 m: sqrt(2^2 + 2 gamma 2); the air (tail-first C_A 0.85 on
    # the 4.2 m base, ~250 N against 148 kN of weight) takes about 0.2 % off
    assert figures["vertical_speed_m_s"] == pytest.approx(-math.sqrt(4.0 + 4.0 * somigliana(LAT)), rel=4e-3)
    assert figures["horizontal_speed_m_s"] < 1e-3          # Coriolis over the fall: 2 omega v t ~ 4e-4
    assert figures["tilt_deg"] < 1e-6
    assert figures["distance_to_target_m"] == pytest.approx(3.0, abs=1e-3)


def fly_drop(write, speed: float, duration: float, target: str = "", east: float = 0.0) -> dict:
    """The lander dropped by World from a scenario at ``speed`` (m/s, down) and ``east``
    (m/s) with its feet 2 m above the ellipsoid (the site's height; the ground is the
    WGS84 ellipsoid, ``ground_height: 0 m``); ``target`` a mission ``target:`` entry.
    Its summary."""
    from rocketsim.scenario.load import load
    from rocketsim.sim.build import build_world
    from tests.aero_vehicles import ROOT
    model = build(shipped("lander.yaml"))
    x_cm = model.mass_properties(model.state([0, 0, 0], [0, 0, 0]))[1]
    write("site.yaml", f"name: flat\nlatitude: 28.5 deg\nlongitude: -80.6 deg\nheight: {2.0 + 1.2 + x_cm} m\n"
                       "ground_height: 0 m\n")
    write("mission.yaml", "epoch: 2026-11-26T12:00:00Z\nstart:\n  site:\n"
                          f"    velocity: [{east!r} m/s, 0 m/s, {-speed!r} m/s]\nduration: {duration!r} s\n{target}")
    path = write("drop.yaml", f"name: drop\nvehicle: {ROOT / 'vehicles' / 'lander.yaml'}\nsite: site.yaml\n"
                              "mission: mission.yaml\n")
    (body,) = build_world(load(path)).run()["bodies"].values()
    return body


def test_the_world_reports_touchdown_and_the_lander_rests(write):
    model = build(shipped("lander.yaml"))
    x_cm = model.mass_properties(model.state([0, 0, 0], [0, 0, 0]))[1]
    body = fly_drop(write, 2.0, 2.0)
    events = {e["name"]: e for e in body["events"]}
    assert "touchdown" in events and "impact" not in events and "breakup" not in events
    assert events["touchdown"]["vertical_speed_m_s"] == pytest.approx(-math.sqrt(4.0 + 4.0 * somigliana(LAT)),
                                                                      rel=4e-3)
    # the pad is the site, straight below the start (Coriolis moves it by millimetres)
    assert events["touchdown"]["distance_to_target_m"] < 0.01
    assert body["final"]["altitude_m"] == pytest.approx(1.2 + x_cm - mass_static(model, x_cm), abs=2e-3)


def test_the_lander_touching_down_sliding_east_slides_and_stays_up(write):
    """At 10 m/s east the lander's feet drag (friction 0.6) but its footprint is wide:
    friction's moment about the leading feet stays under gravity's (0.6 < tan 40 deg =
    0.85, the tilt past which it would fall), so it slides to a stop upright: one
    touchdown, no tip-over, the flight flown to its end."""
    body = fly_drop(write, 2.0, 4.0, east=10.0)
    assert [e["name"] for e in body["events"]] == ["touchdown"]
    assert body["final"]["time_s"] == pytest.approx(4.0)
    assert body["events"][0]["horizontal_speed_m_s"] == pytest.approx(10.0, abs=0.1)


def mass_static(model, x_cm):
    """Static compression of the legs (m) under the lander's weight."""
    mass = model.mass_properties(model.state([0, 0, 0], [0, 0, 0]))[0]
    return mass * somigliana(LAT) / (N_LEGS * K_LEG)


@pytest.mark.parametrize("tilt_deg, tips", [(14.0, False), (23.0, True)])
def test_a_booster_standing_tilted_on_its_legs_rights_itself_or_tips_over(tilt_deg, tips):
    # Statics: a body on a ring of feet tips over when its centre of mass passes over the
    # edge between two feet, at atan(r cos(45 deg) / height of the centre of mass above
    # the feet): 18.2 deg for the nearly empty shipped booster (legs on an 8.5 m ring, 1 m
    # below the base). Below it the legs bring it back; beyond it it falls onto its side.
    from rocketsim.dynamics.rk4 import advance
    from rocketsim.frames.quaternion import quat_rotate
    model = build(shipped("falcon9-block5.yaml"), last=0)
    p = earth_params()
    prop = np.array([500.0, 1000.0])
    x_cm = model.mass_properties(model.state([0, 0, 0], [0, 0, 0], propellant=prop))[1]
    critical = math.degrees(math.atan(8.5 * math.cos(math.pi / 4) / (x_cm + 1.0)))
    assert (tilt_deg > critical) == tips
    assert math.degrees(tip_over_angle(footprint(model.arrays.aero.contact), x_cm)) == pytest.approx(critical,
                                                                                        rel=1e-12)
    enu = enu_basis(LAT, LON)
    up, north = enu[2], enu[1]
    tilt = math.radians(tilt_deg)
    bx = math.cos(tilt) * up + math.sin(tilt) * north
    bz = -math.sin(tilt) * up + math.cos(tilt) * north
    axes = np.column_stack((bx, np.cross(bz, bx), bz))
    q, w = quat_from_matrix(axes), axes.T @ np.array([0.0, 0.0, EARTH_OMEGA])
    r = np.array(geodetic_to_ecef(LAT, LON, 30.0))
    lowest = contact_heights(model.state(r, corotating(r), q=q, w=w, propellant=prop), p, model).min()
    r = r - (lowest - 5e-4) * up                           # the downhill feet just touching
    y = model.state(r, corotating(r), q=q, w=w, propellant=prop)
    # the checks watch it as after a touchdown: past the critical tilt it is reported
    # tipping over (its centre of mass beyond the feet) and stops; the dynamics fly on
    checks, body, world = VehicleChecks(), _Body(model, y, p), _World()
    checks.landed, checks.touched_down = True, True
    tilts = []
    for k in range(400):                                   # 8 s
        y, _ = advance(y, k, 0.02, 1, p, model.arrays)
        body.y, body.t = y, 0.02 * (k + 1)
        checks.after_step(world, body, 0.02)
        tilts.append(math.degrees(math.acos(quat_rotate(y[6:10], np.array([1.0, 0.0, 0.0])) @ up)))
    if tips:
        assert max(tilts) > 80.0
        ((name, figures),) = world.events
        assert name == "tip-over" and not body.flying
        assert figures["tilt_deg"] == pytest.approx(tilt_deg, abs=0.1)    # at once: it starts past it
    else:
        assert max(tilts) < tilt_deg and tilts[-1] < 8.0
        assert world.events == [] and body.flying


def test_a_compiled_run_hands_a_landed_body_to_python_short_of_tipping_over():
    """The compiled runs' checks are quiet for a landed body standing upright and not
    for one tilted past the watch (the cosine of the tip-over angle less the margin),
    so the Python side sees the step where it starts to fall."""
    from rocketsim.stepping import quiet
    watch = np.full(quiet.N_WATCH, math.inf)
    watch[quiet.WATCH_SHIELD], watch[quiet.WATCH_CLEARANCE] = 0.0, 1.0
    watch[quiet.WATCH_TIP] = math.cos(math.radians(20.0))
    figures = (0.0, 288.0, 0.0, 0.0, 0.0, 0.0, -0.01)       # no air, no loads, the feet on the ground
    carry = np.array((math.nan, 1.0, 0.0, 0.0))
    r = np.array(geodetic_to_ecef(LAT, LON, 20.0))
    up = r / np.linalg.norm(r)
    side = np.cross(up, [0.0, 0.0, 1.0])
    side /= np.linalg.norm(side)
    for tilt_deg, still in ((19.0, True), (21.0, False)):
        t = math.radians(tilt_deg)
        bx = math.cos(t) * up + math.sin(t) * side
        bz = np.cross(bx, np.cross(up, bx))
        bz /= np.linalg.norm(bz)
        y = np.zeros(13)
        y[0:3], y[6:10] = r, quat_from_matrix(np.column_stack((bx, np.cross(bz, bx), bz)))
        assert quiet.checks_quiet(y, 0.02, figures, carry, watch)[0] is still
    watch[quiet.WATCH_TIP] = -math.inf                            # before a touchdown: never
    assert quiet.checks_quiet(y, 0.02, figures, carry, watch)[0]


def test_touchdown_distance_is_measured_to_the_mission_target_pad(write):
    """The same drop with a target pad 10 m north of the site: the touchdown's
    distance to the pad is 10 m (a meridian arc of 10 m is 10/M rad of
    latitude, M = a(1 - e^2)/(1 - e^2 sin^2 lat)^1.5, WGS84)."""
    from rocketsim.constants import EARTH_E2, EARTH_RADIUS_EQ
    meridian = EARTH_RADIUS_EQ * (1 - EARTH_E2) / (1 - EARTH_E2 * math.sin(LAT) ** 2) ** 1.5
    pad_lat = math.degrees(LAT + 10.0 / meridian)
    body = fly_drop(write, 2.0, 1.0, f"target:\n  pad: {{latitude: {pad_lat!r} deg, longitude: -80.6 deg}}\n")
    touchdown = {e["name"]: e for e in body["events"]}["touchdown"]
    assert touchdown["distance_to_target_m"] == pytest.approx(10.0, abs=0.02)


def test_a_contact_far_faster_than_any_landing_is_an_impact_not_a_bounce(write):
    """Dropped at 30 m/s (three times CRASH_SPEED) the lander's first contact ends it:
    an impact with the speeds at the contact (free fall over the last 2 m,
    sqrt(30^2 + 2 gamma 2), as in the touchdown test), no touchdown, no bounce (the
    legs' springs would throw it back up)."""
    from rocketsim.sim.vehicle_checks import CRASH_SPEED
    assert 30.0 > 2.0 * CRASH_SPEED
    body = fly_drop(write, 30.0, 1.0)
    names = [e["name"] for e in body["events"]]
    assert names == ["impact"]
    impact = body["events"][0]
    expected = math.sqrt(30.0 ** 2 + 4.0 * somigliana(LAT))
    assert impact["vertical_speed_m_s"] == pytest.approx(-expected, rel=4e-3)
    assert impact["surface_speed_m_s"] == pytest.approx(expected, rel=4e-3)
    assert impact["time_s"] == pytest.approx((expected - 30.0) / somigliana(LAT), abs=0.021)
    assert body["final"]["time_s"] == impact["time_s"]          # it flies no further


def test_about_mars_the_touchdown_speeds_are_over_ground_turning_at_mars_rate():
    """About Mars the ground turns at Mars's rate (IAU WGCCRE 2015: the prime meridian
    turns 350.89198226 deg/day about the pole, the frame's z), not Earth's 360.9856
    deg/day (about 6.9 m/s apart on Mars's equator): a body riding the equator's
    ground while sinking at 5 m/s has a vertical speed of -5 m/s and no horizontal
    speed over the ground."""
    from rocketsim.sim.vehicle_checks import ground_motion
    rate = math.radians(350.89198226) / 86400.0
    angle = 0.7
    radial = np.array([math.cos(angle), math.sin(angle), 0.0])
    r = 3396.19e3 * radial
    y = np.zeros(13)
    y[0:3], y[3:6] = r, rate * np.array([-r[1], r[0], 0.0]) - 5.0 * radial
    up, surface = ground_motion("mars", 100.0, y)
    assert np.allclose(up, radial, atol=1e-15)
    assert surface @ up == pytest.approx(-5.0, abs=1e-9)
    assert np.linalg.norm(surface - (surface @ up) * up) < 1e-6
