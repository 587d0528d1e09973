"""Aerodynamics (docs/physics.md#aerodynamics): axial tables, normal force, static
stability, pitch damping, grid fins and reaction control, each against an independent
reference quoted below."""

import math

import numpy as np
import pytest

from rocketsim.atmosphere.day import standard_table
from rocketsim.constants import EARTH_RADIUS_EQ, G0
from rocketsim.dynamics.derivative import derivative
from rocketsim.dynamics.rk4 import step
from rocketsim.layout import P_SPIN, Q, W
from rocketsim.frames.quaternion import quat_rotate
from rocketsim.vehicle.aero import (A_AREA, A_ETA, A_NOSE_X, A_TAIL_AREA, A_TAIL_X, FIN_X, HANDOVER, NOSE_FIRST_CA,
                                    NOSE_FIRST_MACH, TAIL_FIRST_CA, TAIL_FIRST_MACH,
                                    axial_coefficient, body_aero)
from rocketsim.vehicle.grid_fins import (GC_CMD, GRID_CD, GRID_CN_ALPHA, GRID_MACH, G_MAX, G_RATE,
                                         command, deflection, grid_fin_forces)
from rocketsim.vehicle.build import build
from rocketsim.vehicle.rcs import rcs_forces
from tests.aero_vehicles import (SLENDER, SOUNDING, corotating, earth_params, pitch_quaternion,
                                 shipped, spec)

NF = np.column_stack((NOSE_FIRST_MACH, NOSE_FIRST_CA))
TF = np.column_stack((TAIL_FIRST_MACH, TAIL_FIRST_CA))


# --- axial force --------------------------------------------------------------

def test_axial_tables_hold_the_physics_models_points():
    # docs/physics.md#axial-force: nose first 0.30 subsonic, 0.62 at
    # Mach 1.15, 0.25 hypersonic; tail first 0.85 rising to 1.45 at Mach 2.
    for mach, ca in ((0.0, 0.30), (0.5, 0.30), (1.15, 0.62), (8.0, 0.25), (20.0, 0.25)):
        assert axial_coefficient(mach, 1.0, 0.0, NF, TF) == ca
    for mach, ca in ((0.0, 0.85), (0.3, 0.85), (2.0, 1.45), (6.0, 1.45)):
        assert axial_coefficient(mach, -1.0, 0.0, NF, TF) == ca
    machs = np.linspace(0.0, 10.0, 2001)
    nose = np.array([axial_coefficient(m, 1.0, 0.0, NF, TF) for m in machs])
    tail = np.array([axial_coefficient(m, -1.0, 0.0, NF, TF) for m in machs])
    peak = machs <= 1.15
    assert np.all(np.diff(nose[peak]) >= 0.0) and np.all(np.diff(nose[~peak]) <= 0.0)
    assert np.all(np.diff(tail) >= 0.0)


@pytest.mark.parametrize("mach", [0.3, 0.95, 1.15, 2.0, 5.0])
def test_axial_force_hands_over_monotonically_and_continuously_through_90_degrees(mach):
    # The axial force per q S is -cos(alpha) C_A: it must run from -C_A(nose first) at 0
    # to +C_A(tail first) at 180 deg without a jump and without turning back.
    alphas = np.radians(np.linspace(0.0, 180.0, 18001))
    force = np.array([-math.cos(a) * axial_coefficient(mach, math.cos(a), 0.0, NF, TF) for a in alphas])
    assert force[0] == -axial_coefficient(mach, 1.0, 0.0, NF, TF)
    assert force[-1] == axial_coefficient(mach, -1.0, 0.0, NF, TF)
    assert np.all(np.diff(force) > 0.0)
    # continuous: no step larger than the slope bound (|d/dalpha| <= C_A,max (1 + 3/(2 sin 10deg)))
    bound = 1.45 * (1.0 + 1.5 / HANDOVER) * (alphas[1] - alphas[0])
    assert np.max(np.diff(force)) < bound


def test_plume_shields_the_base_when_flying_tail_first_under_thrust():
    # exp(-C_T), fitted to the trend in Korzun, Cruz & Braun (2008) sec. 4: C_A falls
    # steeply with C_T and is nearly gone (a few percent) above C_T ~ 3.
    bare = axial_coefficient(1.5, -1.0, 0.0, NF, TF)
    shielded = [axial_coefficient(1.5, -1.0, c, NF, TF) / bare for c in (0.5, 1.0, 3.0, 6.0)]
    assert shielded == pytest.approx([math.exp(-0.5), math.exp(-1.0), math.exp(-3.0), math.exp(-6.0)])
    assert shielded[2] < 0.06
    # thrust pushing along the flight (nose first) shields nothing
    assert axial_coefficient(1.5, 1.0, 3.0, NF, TF) == axial_coefficient(1.5, 1.0, 0.0, NF, TF)


# --- normal force -------------------------------------------------------------

def _slender_coefficients(alpha_deg, mach=0.3):
    a = build(spec(SLENDER)).arrays.aero
    sound, rho = 340.294, 1.225
    speed = mach * sound
    al = math.radians(alpha_deg)
    f = body_aero(speed * math.cos(al), 0.0, speed * math.sin(al), 0.0, 0.0, 0.0, rho, sound, 0.0,
                    5.0, a.ref, a.seg, a.fin, a.ca_nf, a.ca_tf)
    return -f[2] / (0.5 * rho * speed ** 2 * a.ref[A_AREA]), a


@pytest.mark.parametrize("alpha_deg", [0.5, 2.0, 5.0, 10.0])
def test_normal_force_of_a_slender_cylinder_with_nose_matches_jorgensen(alpha_deg):
    # L. H. Jorgensen, NASA TR R-474 (1977), eq. (1): for a body of base area A_b,
    # planform area A_p, reference area A_r,
    #   C_N = (A_b/A_r) sin(2a) cos(a/2) + eta C_dc (A_p/A_r) sin^2 a
    # (slender-body theory at the nose: C_N_alpha = 2 per radian; crossflow behind).
    # eta = 0.70 for fineness ratio 20 (his fig. 3), C_dc = 1.2 at a crossflow Mach
    # below 0.4 (his fig. 4). The 10 m x 0.5 m body has a 2 m cone nose.
    cn, a = _slender_coefficients(alpha_deg)
    al = math.radians(alpha_deg)
    area = math.pi * 0.25 ** 2
    planform = 0.5 * 8.0 + 0.5 * 0.5 * 2.0
    assert a.ref[A_ETA] == pytest.approx(0.70)
    expected = math.sin(2 * al) * math.cos(al / 2) + 0.70 * 1.2 * planform / area * math.sin(al) ** 2
    assert cn == pytest.approx(expected, rel=0.05)


def test_normal_force_slope_at_zero_is_two_per_radian():
    # Slender-body theory (Munk 1924; Jorgensen eq. 1 as alpha -> 0): C_N_alpha = 2 A_b/A_r.
    cn, _ = _slender_coefficients(0.05)
    assert cn / math.radians(0.05) == pytest.approx(2.0, rel=0.05)


def test_nose_lift_acts_at_the_slender_body_centre_of_pressure():
    # Slender-body theory puts a cone's lift 2/3 of its length from the tip, a tangent
    # ogive's at 0.467 L (Barrowman 1967, table of nose centres of pressure: 0.666 L cone,
    # 0.466 L ogive).
    cone = build(spec(SLENDER)).arrays.aero.ref
    assert 10.0 - cone[A_NOSE_X] == pytest.approx(2.0 * 2.0 / 3.0, rel=1e-3)
    ogive = build(spec(SOUNDING)).arrays.aero.ref
    assert 6.0 - ogive[A_NOSE_X] == pytest.approx(0.466 * 1.0, rel=0.01)


def test_a_boattail_lifts_against_the_nose_as_barrowmans_conical_transition():
    # Barrowman (1967), conical transitions: C_N_alpha = 2 ((d_2/d)^2 - (d_1/d)^2) per radian
    # on the reference section, at x_1 + L/3 (1 + (1 - d_1/d_2) / (1 - (d_1/d_2)^2)) from its
    # fore end (d_1 there, d_2 at its aft end). Notre Dame 2020's boattail: 203 mm to 155 mm
    # over 127 mm: -0.8340 per radian, 60.66 mm aft of its fore end. At 0.5 deg nose first
    # the body's normal force and pitching moment change by that slope at that station.
    body = {"name": "tail", "stages": [{"name": "r", "length": "2.65 m", "diameter": "0.203 m",
                                        "structure_mass": "19 kg"}],
            "aero": {"nose": {"length": "0.61 m", "shape": "ogive"}, "segments": 40}}
    tailed = dict(body, aero=dict(body["aero"], boattail={"stage": "r", "length": "0.127 m",
                                                          "diameter": "0.155 m"}))
    d1, d2, length = 0.203, 0.155, 0.127
    slope = 2 * ((d2 / d1) ** 2 - 1)
    station = length - length / 3 * (1 + (1 - d1 / d2) / (1 - (d1 / d2) ** 2))     # above the base
    ref = build(spec(tailed)).arrays.aero.ref
    assert 2 * ref[A_TAIL_AREA] / ref[A_AREA] == pytest.approx(slope, rel=1e-12)
    assert ref[A_TAIL_X] == pytest.approx(station, rel=1e-6)
    forces = []
    for vehicle in (body, tailed):
        a = build(spec(vehicle)).arrays.aero
        speed, al = 100.0, math.radians(0.5)
        forces.append(body_aero(speed * math.cos(al), 0.0, speed * math.sin(al), 0.0, 0.0, 0.0,
                                1.225, 340.0, 0.0, 1.2, a.ref, a.seg, a.fin, a.ca_nf, a.ca_tf))
    q_s_alpha = 0.5 * 1.225 * 100.0 ** 2 * ref[A_AREA] * math.sin(al) * math.cos(al)
    normal = -(forces[1][2] - forces[0][2]) / q_s_alpha          # the boattail's own, plus its
    assert normal == pytest.approx(slope, rel=0.02)               # narrower crossflow segment
    arm = (forces[1][4] - forces[0][4]) / (forces[1][2] - forces[0][2])
    assert 1.2 - arm == pytest.approx(station, abs=0.005)


# --- static stability --------------------------------------------------------

def _angle_of_attack(model, y):
    v_air = y[3:6] - corotating(y[0:3]) - model.arrays.aero.wind
    axis = quat_rotate(y[Q:Q + 4], np.array([1.0, 0.0, 0.0]))
    return math.acos(axis @ v_air / np.linalg.norm(v_air))


def test_a_finned_sounding_rocket_weathercocks_into_the_wind():
    # A statically stable rocket turns its nose into the relative wind (Barrowman's
    # centre of pressure behind the centre of mass). Rising at 150 m/s through a
    # 15 m/s wind blowing towards ECI +y (east at this point), the nose must turn
    # towards -y, where the wind comes from, and settle near the relative wind.
    model = build(spec(SOUNDING))
    a = model.arrays
    a.aero.wind[:] = (0.0, 15.0, 0.0)            # held (the test's day has no table wind)
    r = np.array([EARTH_RADIUS_EQ + 1000.0, 0.0, 0.0])
    y = model.state(r, corotating(r) + np.array([150.0, 0.0, 0.0]))
    x_cm = model.mass_properties(y)[1]
    assert a.aero.fin[0, FIN_X] < x_cm         # the fins' centre of pressure is aft
    p = earth_params()
    alpha0 = _angle_of_attack(model, y)
    for k in range(100):                          # 2 s
        y = step(y, 0.02 * k, 0.02, p, a)
    axis = quat_rotate(y[Q:Q + 4], np.array([1.0, 0.0, 0.0]))
    assert axis[1] < -0.5 * math.sin(alpha0)      # turned towards the wind's source
    assert _angle_of_attack(model, y) < 0.5 * alpha0


def _booster_tail_first(with_grid_fins):
    vehicle = shipped("falcon9-block5.yaml")
    if not with_grid_fins:
        vehicle = vehicle.model_copy(update={"aero": vehicle.aero.model_copy(update={"grid_fins": []})})
    model = build(vehicle, last=0)
    r = np.array([EARTH_RADIUS_EQ + 8000.0, 0.0, 0.0])
    # falling tail first at 250 m/s, nose up (body x along ECI +x), pitched 3 degrees
    y = model.state(r, corotating(r) + np.array([-250.0, 0.0, 0.0]), q=pitch_quaternion(math.radians(3.0)),
                    propellant=np.zeros(model.n_tanks) + 1.0)
    return model, y


@pytest.mark.parametrize("fins", [False, True])
def test_orbital_first_stage_tail_first_is_unstable_bare_and_stable_with_grid_fins(fins):
    # Static stability: the pitching moment at a small angle of attack must turn the
    # trailing end downstream (restoring) for a stable body. Tail first, the base
    # leads; its slender-body lift acts ahead of the centre of mass and the bare
    # booster diverges; grid fins at the top (the trailing end) restore it.
    model, y = _booster_tail_first(fins)
    p = earth_params()
    dy = np.zeros_like(y)
    derivative(0.0, y, p, dy, model.arrays)
    alpha0 = math.pi - _angle_of_attack(model, y)          # from the leading (tail) end
    # the body is turned +3 deg about y; restoring means turning back: omega_y' < 0
    assert (dy[W + 1] < 0.0) == fins
    for k in range(150):                                     # 3 s
        y = step(y, 0.02 * k, 0.02, p, model.arrays)
    alpha = math.pi - _angle_of_attack(model, y)
    if fins:
        assert alpha < alpha0
    else:
        assert alpha > 3.0 * alpha0


# --- rotation-induced crossflow ----------------------------------------------

@pytest.mark.parametrize("rate", [0.4, -1.5])
def test_a_body_pitching_in_still_air_feels_the_analytic_damping_moment(rate):
    # A cylinder of diameter D turning at omega about a point d1 from its base and d2
    # from its top, in still air: each element sees a crossflow omega x, so
    #   M = -1/2 rho eta C_dc D omega |omega| (d1^4 + d2^4) / 4
    # (integrate x |x| x dx; eta, C_dc as above: crossflow Mach < 0.4 everywhere).
    data = {**SLENDER, "aero": {"segments": 200}}
    a = build(spec(data)).arrays.aero
    rho, sound, x_cm = 1.225, 340.294, 4.0
    f = body_aero(0.0, 0.0, 0.0, 0.0, rate, 0.0, rho, sound, 0.0, x_cm, a.ref, a.seg, a.fin,
                    a.ca_nf, a.ca_tf)
    eta = a.ref[A_ETA]
    expected = -0.5 * rho * eta * 1.2 * 0.5 * rate * abs(rate) * (4.0 ** 4 + 6.0 ** 4) / 4.0
    assert f[4] == pytest.approx(expected, rel=1e-4)
    assert f[0] == 0.0 and f[5] == 0.0 and math.copysign(1.0, f[4]) == -math.copysign(1.0, rate)
    # the default 20 segments (midpoint rule) are within 0.5 %
    a20 = build(spec({**SLENDER, "aero": {}})).arrays.aero
    f20 = body_aero(0.0, 0.0, 0.0, 0.0, rate, 0.0, rho, sound, 0.0, x_cm, a20.ref, a20.seg, a20.fin,
                      a20.ca_nf, a20.ca_tf)
    assert f20[4] == pytest.approx(expected, rel=5e-3)


# --- grid fins ------------------------------------------------------------------

def _grid():
    model = build(shipped("falcon9-block5.yaml"), last=0)
    a = model.arrays.aero
    return a.grid.copy(), np.zeros_like(a.grid_cmd)


def test_grid_fins_roll_command_gives_a_pure_roll_moment_and_drag_on_all_four():
    grid, cmd = _grid()
    rho, sound, speed = 0.4, 300.0, 450.0                 # Mach 1.5
    q = 0.5 * rho * speed ** 2
    f0 = grid_fin_forces(0.0, speed, 0.0, 0.0, 0.0, 0.0, 0.0, rho, sound, 20.0, grid, cmd)
    # undeflected: four times one fin's drag q A C_D(M), nothing else (symmetry)
    assert f0[0] == pytest.approx(-4 * q * 2.0 * np.interp(1.5, GRID_MACH, GRID_CD), rel=1e-12)
    assert max(abs(c) for c in f0[1:]) < 1e-6 * abs(f0[0])
    command(grid, cmd, 0.0, 0.0, 0.0, math.radians(5.0))
    f = grid_fin_forces(10.0, speed, 0.0, 0.0, 0.0, 0.0, 0.0, rho, sound, 20.0, grid, cmd)
    assert abs(f[3]) > 1e3 and max(abs(f[1]), abs(f[2]), abs(f[4]), abs(f[5])) < 1e-6 * abs(f[3])
    # a fin turned by delta in a flow along x: normal force q A C_N_alpha delta at radius r,
    # cos(delta) of it tangential (Washington & Miller's linear range; thin-fin geometry)
    delta = math.radians(5.0)
    cna = np.interp(1.5, GRID_MACH, GRID_CN_ALPHA)
    assert f[3] == pytest.approx(4 * q * 2.0 * cna * delta * math.cos(delta) * 2.6, rel=1e-9)


def test_grid_fins_pitch_and_yaw_push_the_fin_station_and_stall_caps_the_force():
    grid, cmd = _grid()
    rho, sound, speed = 0.4, 300.0, 240.0                 # Mach 0.8
    command(grid, cmd, 0.0, math.radians(4.0), 0.0, 0.0)
    f = grid_fin_forces(10.0, speed, 0.0, 0.0, 0.0, 0.0, 0.0, rho, sound, 20.0, grid, cmd)
    assert f[2] > 0.0 and abs(f[1]) < 1e-6 * f[2] and f[4] < 0.0      # +z at x > x_cm: nose down
    command(grid, cmd, 0.0, 0.0, math.radians(4.0), 0.0)
    f = grid_fin_forces(10.0, speed, 0.0, 0.0, 0.0, 0.0, 0.0, rho, sound, 20.0, grid, cmd)
    assert f[1] > 0.0 and abs(f[2]) < 1e-6 * f[1]
    # beyond the stall angle (25 deg) the normal force stops growing
    lateral = []
    for deg in (20.0, 30.0, 40.0):
        al = math.radians(deg)
        cmd[:] = 0.0
        g = grid_fin_forces(0.0, speed * math.cos(al), 0.0, speed * math.sin(al), 0.0, 0.0, 0.0, rho,
                              sound, 20.0, grid, cmd)
        drag = 2 * 0.5 * rho * speed ** 2 * 2.0 * np.interp(0.8, GRID_MACH, GRID_CD) * math.sin(al)
        lateral.append(-g[2] - drag * 2)                   # the two normal-bearing fins' share
    assert lateral[0] < lateral[1] and lateral[2] == pytest.approx(lateral[1], rel=1e-9)


def test_grid_fin_normal_force_slope_dips_where_the_lattice_chokes():
    # Washington & Miller (1993): the slope falls between Mach 0.8 and 1.2 (choked
    # cells) and recovers supersonic.
    slope = lambda m: np.interp(m, GRID_MACH, GRID_CN_ALPHA)
    assert slope(1.05) < 0.7 * slope(0.8) and slope(1.05) < 0.8 * slope(1.5)


def test_grid_fins_slew_at_their_rate_limit():
    grid, cmd = _grid()
    rate = grid[0, G_RATE]
    command(grid, cmd, 1.0, math.radians(15.0), 0.0, 0.0)
    for t, expected in ((1.0, 0.0), (1.1, 0.1 * rate), (1.2, 0.2 * rate), (5.0, math.radians(15.0))):
        assert deflection(t, grid[0], cmd[0]) == pytest.approx(expected, abs=1e-15)
    # commanded past the limit: clipped to it
    command(grid, cmd, 5.0, math.radians(90.0), 0.0, 0.0)
    assert cmd[0, GC_CMD] == pytest.approx(grid[0, G_MAX])


# --- reaction control ---------------------------------------------------------

def test_rcs_thruster_torque_and_propellant_flow():
    data = {**SOUNDING, "aero": {**SOUNDING["aero"], "rcs": [
        {"stage": "rocket", "tank": "T", "position": "5 m", "y": "0.15 m", "z": "0 m",
         "direction": [0, 0, 1], "thrust": "400 N", "isp": "220 s"}]}}
    data["stages"] = [{**SOUNDING["stages"][0], "tanks": [{**SOUNDING["stages"][0]["tanks"][0],
                                                            "propellant_mass": "10 kg"}]}]
    model = build(spec(data))
    a = model.arrays.aero
    y = model.state([EARTH_RADIUS_EQ + 1e5, 0, 0], [0, 0, 0])
    x_cm = model.mass_properties(y)[1]
    dy = np.zeros_like(y)
    a.rcs_cmd[0] = 0.5
    f = rcs_forces(y, dy, x_cm, a.rcs, a.rcs_cmd)
    # F = 200 N along z at r = (5 - x_cm, 0.15, 0): M = r x F = (0.15 F, -(5 - x_cm) F, 0)
    assert f == pytest.approx((0.0, 0.0, 200.0, 0.15 * 200.0, -(5.0 - x_cm) * 200.0, 0.0), abs=1e-12)
    assert dy[model.tanks][0] == pytest.approx(-200.0 / (G0 * 220.0), rel=1e-14)
    y[model.tanks] = 0.0                                  # empty tank: nothing
    assert rcs_forces(y, np.zeros_like(y), x_cm, a.rcs, a.rcs_cmd) == (0.0,) * 6


def test_rcs_is_felt_in_the_derivative():
    data = {**SOUNDING, "aero": {**SOUNDING["aero"], "rcs": [
        {"stage": "rocket", "tank": "T", "position": "5 m", "direction": [0, 1, 0], "thrust": "100 N",
         "isp": "220 s"}]}}
    data["stages"] = [{**SOUNDING["stages"][0], "tanks": [{**SOUNDING["stages"][0]["tanks"][0],
                                                            "propellant_mass": "10 kg"}]}]
    model = build(spec(data))
    y = model.state([EARTH_RADIUS_EQ + 7e5, 0, 0], [0, 7500.0, 0])   # above the air
    p = earth_params()
    dy0, dy1 = np.zeros_like(y), np.zeros_like(y)
    derivative(0.0, y, p, dy0, model.arrays)
    model.arrays.aero.rcs_cmd[0] = 1.0
    derivative(0.0, y, p, dy1, model.arrays)
    mass, x_cm, _, _, izz = model.mass_properties(y)
    assert dy1[4] - dy0[4] == pytest.approx(100.0 / mass, rel=1e-12)
    assert dy1[W + 2] - dy0[W + 2] == pytest.approx((5.0 - x_cm) * 100.0 / izz, rel=1e-12)


def test_standard_table_used_by_the_tests_is_the_us_1976():
    # guard for the figures above: sea-level density of US 1976 is 1.2250 kg/m^3
    assert standard_table().at(0.0)[0][0] == pytest.approx(1.2250, rel=1e-4)


def test_the_derivative_shields_the_base_with_the_engines_own_thrust():
    # Tail first with the centre engine burning (a landing burn): the axial aerodynamic force
    # the derivative applies is the bare tail-first one times exp(-C_T), C_T = T / (q S)
    # with T the engines' thrust at that instant (Korzun et al. trend; plume_shielding).
    from rocketsim.vehicle.engines import engine_forces, ignite
    from rocketsim.atmosphere.table import air_in
    from rocketsim.dynamics.derivative import body_air_velocity, radial_height
    model = build(shipped("falcon9-block5.yaml"), last=0)
    a = model.arrays
    r = np.array([EARTH_RADIUS_EQ + 8e3, 0.0, 0.0])
    y = model.state(r, corotating(r) + np.array([-450.0, 0.0, 0.0]), propellant=np.array([2e4, 4e4]))
    ignite(y, a.eng, a.cmd, a.stage, 0, a.first_clock)           # the centre engine
    y[model.clocks] = 10.0
    p = earth_params()
    no_fins = a._replace(aero=a.aero._replace(grid=a.aero.grid[:0], grid_cmd=a.aero.grid_cmd[:0]))
    bare = a._replace(aero=a.aero._replace(ref=a.aero.ref * 0.0))
    dy, dy0 = np.zeros_like(y), np.zeros_like(y)
    derivative(0.0, y, p, dy, no_fins)
    derivative(0.0, y, p, dy0, bare)
    mass, x_cm = model.mass_properties(y)[:2]
    aero_x = (dy[3] - dy0[3]) * mass                       # body x = ECI x here
    rho, p_a, _, sound = air_in(a.air, radial_height(y, p))[:4]
    thrust = engine_forces(0.0, y, np.zeros_like(y), a.first_tank, a.first_clock, a.eng, a.cmd, a.stage,
                             a.tank_share, p_a, x_cm)[0]
    u, v, w = body_air_velocity(y, a.aero.wind, p[P_SPIN])
    q = 0.5 * rho * (u * u + v * v + w * w)
    area = a.aero.ref[A_AREA]
    bare_axial = q * area * np.interp(abs(u) / sound, TAIL_FIRST_MACH, TAIL_FIRST_CA)
    assert thrust > 0.0 and u < 0.0 and 0.5 < thrust / (q * area) < 5.0
    assert aero_x == pytest.approx(bare_axial * math.exp(-thrust / (q * area)), rel=1e-9)
