"""The autopilot steers a burning vehicle's nose onto the commanded direction."""

import math

import numpy as np
import pytest

from rocketsim.flight.steering import attitude_error
from rocketsim.scenario.load import load
from rocketsim.api.telemetry_flight import fly_to_file as fly

VEHICLE = """\
name: kick stage
stages:
  - name: stage
    length: 4 m
    diameter: 1.5 m
    structure_mass: 300 kg
    tanks:
      - {name: fuel, propellant: MMH, density: 880 kg/m3, radius: 0.6 m, length: 1.4 m,
         position: 1.2 m, wall_mass: 20 kg, propellant_mass: 1300 kg}
    engines:
      - name: engine
        position: 0.3 m
        mass: 60 kg
        thrust_vacuum: 20 kN
        isp_vacuum: 320 s
        exit_area: 0.3 m2
        throttle: [0.5, 1.0]
        throttle_rate: 1.0
        gimbal_range: 5 deg
        gimbal_rate: 20 deg/s
        ignition_delay: 0.2 s
        spool_up: 0.5 s
        tail_off: 0.25 s
        restarts: 1
"""

PROGRAM = """
import math
import numpy as np
def main(fc):
    fc.ignite()
    fc.throttle(1.0)
    nose = fc.prograde
    target = math.cos(0.35) * nose + math.sin(0.35) * fc.radial    # 20 deg up from prograde
    fc.point_at(target)
    fc.sleep(25.0)
    fc.event("settled", target=[float(x) for x in target], rates=[float(x) for x in fc.body_rates])
"""


def _burn(write, tmp_path, program: str):
    """``(telemetry path, summary)`` of the kick stage flying ``program`` for 26 s from a
    400 km orbit."""
    write("vehicle.yaml", VEHICLE)
    write("program.py", program)
    path = write("scenario.yaml", """\
        name: burn
        vehicle: vehicle.yaml
        program: program.py
        mission:
          epoch: 2026-11-26T12:00:00Z
          start: {orbit: {altitude: 400 km, inclination: 28.5 deg}}
          duration: 26 s
        """)
    out = tmp_path / "run.mcap"
    return out, fly(load(path), out)


def test_the_nose_settles_on_a_new_direction_during_a_burn(write, tmp_path):
    """Reference: the commanded direction itself. A 20 deg turn with the damped
    response (omega_n = 1 rad/s, zeta = 0.9) settles within a few seconds; after
    25 s the nose is within 0.1 deg of the target and the body rates are small."""
    out, summary = _burn(write, tmp_path, PROGRAM)
    settled = {e["name"]: e for e in summary["bodies"]["kick_stage"]["events"]}["settled"]
    from rocketsim.telemetry.reader import messages
    from rocketsim.frames.quaternion import quat_to_matrix
    last = [m for _, _, m in messages(out, ["/kick_stage/state"]) if m["t"] <= 25.0 + 1e-9][-1]
    axes = quat_to_matrix(np.array(last["attitude"]))
    error = np.linalg.norm(attitude_error(axes, np.array(settled["target"])))
    print(f"\nnose error after 25 s: {math.degrees(error):.2e} deg, pitch/yaw rates {settled['rates'][1:]}")
    assert math.degrees(error) < 0.1
    assert np.max(np.abs(settled["rates"][1:])) < 1e-3


def test_attitude_error_is_the_rotation_onto_the_target():
    """Analytic: a nose along x and a target in the x-y plane at angle a need a
    rotation of a about +z; a target in the x-z plane needs a rotation about -y."""
    a = 0.3
    assert np.allclose(attitude_error(np.eye(3), np.array([math.cos(a), math.sin(a), 0.0])), [0, 0, a])
    assert np.allclose(attitude_error(np.eye(3), np.array([math.cos(a), 0.0, math.sin(a)])), [0, -a, 0])
    assert np.allclose(attitude_error(np.eye(3), np.array([1.0, 0.0, 0.0])), 0.0)


def test_grid_fin_gain_reverses_tail_first_and_matches_the_fin_model_in_axial_flow():
    """Analytic reference, the grid-fin model (rocketsim/vehicle/grid_fins.py) in a flow
    along the body axis: a pitch deflection delta turns the fins on the arms at 0 and
    180 deg by +-delta, each meets the flow at a = -delta (nose first; +delta tail first,
    the |V.c| of the model) and pushes -q A C_N_alpha(M) a n with n_z = cos(delta), so
    the pitch moment per radian measured with the autopilot's probe is
    ``-+ 2 d q A C_N_alpha(M) cos(probe)`` (d the fins' station above the centre of
    mass); the fins at 90 and 270 deg and the drag give no pitch moment."""
    from tests.aero_vehicles import shipped
    from rocketsim.flight.steering import FIN_PROBE, fin_gains
    from rocketsim.vehicle.grid_fins import GRID_CN_ALPHA, GRID_MACH, G_AREA, G_X
    from rocketsim.vehicle.aero import interp
    from rocketsim.vehicle.build import build

    model = build(shipped("falcon9-block5.yaml"), last=0)
    grid = model.arrays.aero.grid
    x_cm = model.mass_properties(model.tank_load)[1]
    rho, sound, speed = 0.4, 300.0, 250.0
    mach = speed / sound
    d = float(grid[0, G_X]) - x_cm
    expected = 2.0 * d * 0.5 * rho * speed ** 2 * float(grid[0, G_AREA]) * \
        interp(GRID_MACH, GRID_CN_ALPHA, mach) * math.cos(FIN_PROBE)
    nose_first = fin_gains(model.arrays.aero, speed, 0.0, 0.0, rho, sound, x_cm)
    tail_first = fin_gains(model.arrays.aero, -speed, 0.0, 0.0, rho, sound, x_cm)
    assert nose_first[0] == pytest.approx(-expected, rel=1e-9)
    assert tail_first[0] == pytest.approx(expected, rel=1e-9)
    # yaw pushes the fin station to +y: the moment about z is +d F_y, the opposite sign
    assert nose_first[1] == pytest.approx(expected, rel=1e-9)


def test_rotation_error_is_the_axis_times_the_angle():
    """Analytic (Rodrigues): the target axes turned by an angle a about a unit axis n
    (body axes: the current axes are the identity) need the rotation vector a n; the
    same for a turn beyond 90 deg."""
    from rocketsim.flight.steering import rotation_error
    for angle in (0.3, 2.5):
        n = np.array([1.0, -2.0, 0.5]) / math.sqrt(5.25)
        k = np.array([[0.0, -n[2], n[1]], [n[2], 0.0, -n[0]], [-n[1], n[0], 0.0]])
        turned = np.eye(3) + math.sin(angle) * k + (1.0 - math.cos(angle)) * (k @ k)
        assert np.allclose(rotation_error(np.eye(3), turned), angle * n, atol=1e-12)


def test_commanded_attitudes_in_local_axes():
    """Reference: the conventions of rocketsim/flight/readings.py, with east, north, up
    along ECI x, y, z. Pitch 30 deg, heading 90 deg puts the nose at cos 30 east +
    sin 30 up; level flight east with roll 0 has the belly (body z) down and body y =
    z x x = south; a roll of 90 deg turns body z about the nose to z_ref turned by
    +90 deg, x_nose cross z_ref = east x down = north."""
    from rocketsim.dynamics.rails import PITCH_HEADING, nose_target
    from rocketsim.flight.steering import target_axes
    enu = np.eye(3)
    code = np.array([PITCH_HEADING, 1.0, math.radians(30.0), math.radians(90.0), 0.0, math.nan])
    nose = nose_target(code, np.array([7e6, 0.0, 0.0]), np.array([0.0, 7e3, 0.0]), enu, np.zeros(3), 0.0)
    assert np.allclose(nose, [math.cos(math.radians(30.0)), 0.0, 0.5], atol=1e-15)
    east = np.array([1.0, 0.0, 0.0])
    found, level = target_axes(east, enu, 0.0)
    assert found and np.allclose(level, [[1, 0, 0], [0, -1, 0], [0, 0, -1]], atol=1e-15)
    found, rolled = target_axes(east, enu, math.pi / 2)
    assert found and np.allclose(rolled[:, 2], [0.0, 1.0, 0.0], atol=1e-15)
    found, _ = target_axes(np.array([0.0, 0.0, 1.0]), enu, 0.0)     # nose up: no reference
    assert not found


def _law_direction(r, v, pitch, cross):
    """The linear-tangent law's nose, as a program would write it with numpy: the pitch
    above the plane normal to the radius, ahead along the velocity, ``cross`` along r x v."""
    up = r / np.linalg.norm(r)
    horizontal = v - (v @ up) * up
    horizontal /= np.linalg.norm(horizontal)
    normal = np.cross(r, v) / np.linalg.norm(np.cross(r, v))
    nose = math.cos(pitch) * horizontal + math.sin(pitch) * up + cross * normal
    return nose / np.linalg.norm(nose)


def test_the_linear_tangent_nose_is_the_law_s_pitch_in_the_orbit_plane():
    """nose_target's linear-tangent kind against the law written with numpy, at random
    states: the same direction to 1e-14, and without a cross-track share the pitch
    above the plane normal to the radius is atan(a + b (t - t0)) itself."""
    from rocketsim.dynamics.rails import LINEAR_TANGENT, nose_target

    rng = np.random.default_rng(3)
    for _ in range(200):
        r = rng.normal(size=3) * 7e6
        v = rng.normal(size=3) * 5e3
        a, b, t0, t = rng.normal(), rng.normal() * 0.01, rng.uniform(0, 500), rng.uniform(0, 500)
        cross = rng.choice((0.0, rng.uniform(-0.3, 0.3)))
        code = np.array((LINEAR_TANGENT, t0, a, b, cross, math.nan))
        nose = nose_target(code, r, v, np.eye(3), np.zeros(3), t)
        pitch = math.atan(a + b * (t - t0))
        np.testing.assert_allclose(nose, _law_direction(r, v, pitch, cross), rtol=0, atol=1e-14)
        if cross == 0.0:
            assert math.asin(nose @ (r / np.linalg.norm(r))) == pytest.approx(pitch, rel=1e-12, abs=1e-14)


LAW_PROGRAM = """
def main(fc):
    fc.ignite()
    fc.throttle(1.0)
    fc.steer_linear_tangent(0.35, -0.001, cross=0.05)
    fc.sleep(25.0)
"""


def test_a_burn_follows_linear_tangent_steering(write, tmp_path):
    """The kick stage's nose under fc.steer_linear_tangent(0.35, -0.001, cross=0.05).
    Reference: the damped response's steady error on a target turning at a steady rate
    Omega, ``2 zeta Omega / omega_n`` (omega_n = 1 rad/s, zeta = 0.9; the error of
    ``alpha = omega_n^2 e - 2 zeta omega_n w`` on a ramp). The law's direction turns at
    about 0.12 deg/s (the law's 0.05 deg/s and the local horizontal's turn with the
    orbit, 0.065 deg/s), measured here from the samples at T+24 and T+25 s; at T+25 s
    the nose trails the law's direction by that error, within 0.05 deg."""
    out, _ = _burn(write, tmp_path, LAW_PROGRAM)
    from rocketsim.telemetry.reader import messages
    from rocketsim.frames.quaternion import quat_to_matrix

    def law(m):
        r, v = np.array(m["position"]), np.array(m["velocity"])
        return _law_direction(r, v, math.atan(0.35 - 0.001 * m["t"]), 0.05)

    states = [m for _, _, m in messages(out, ["/kick_stage/state"])]
    before, last = [[m for m in states if m["t"] <= t + 1e-9][-1] for t in (24.0, 25.0)]
    turn = math.acos(min(1.0, law(before) @ law(last))) / (last["t"] - before["t"])
    lag = math.degrees(2 * 0.9 * turn / 1.0)
    axes = quat_to_matrix(np.array(last["attitude"]))
    error = math.degrees(np.linalg.norm(attitude_error(axes, law(last))))
    print(f"\nnose error at T+{last['t']:g} s: {error:.3f} deg; the law turns {math.degrees(turn):.3f} deg/s, "
          f"a steady lag of {lag:.3f} deg")
    assert error == pytest.approx(lag, abs=0.05) and 0.1 < lag < 0.3
