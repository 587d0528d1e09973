"""Reaction control in vacuum: the autopilot turns and holds a coasting body with its
RCS thrusters (rocketsim.flight.autopilot), and without them leaves it alone.

The test vehicle is a 1.2 t spacecraft, 4 m long, coasting in a 700 km orbit
(above the air), with twelve 200 N thrusters in couples: four for pitch, four for
yaw (1.5 m either side of the middle) and four for roll (1 m off the axis).
"""

import math

import numpy as np
from scipy.integrate import solve_ivp

from rocketsim.flight.autopilot import rcs_command, rcs_torques
from rocketsim.flight.steering import OMEGA_N, RATE_LIMIT, ZETA
from rocketsim.frames.quaternion import quat_to_matrix
from rocketsim.scenario.load import load
from rocketsim.api.telemetry_flight import fly_to_file as fly
from rocketsim.telemetry.reader import messages

THRUST = 200.0     # N, each thruster


def _thruster(position, y, z, direction):
    return (f"    - {{stage: bus, tank: hydrazine, position: {position} m, y: {y} m, z: {z} m, "
            f"direction: {list(direction)}, thrust: {THRUST} N, isp: 220 s}}\n")


VEHICLE = """\
name: craft
stages:
  - name: bus
    length: 4 m
    diameter: 2 m
    structure_mass: 900 kg
    tanks:
      - {name: hydrazine, propellant: N2H4, density: 1010 kg/m3, radius: 0.5 m, length: 1.0 m,
         position: 1.5 m, wall_mass: 20 kg, propellant_mass: 250 kg}
    engines:
      - name: engine
        position: 0.2 m
        mass: 30 kg
        thrust_vacuum: 4 kN
        isp_vacuum: 310 s
        exit_area: 0.1 m2
        throttle: [1.0, 1.0]
        throttle_rate: 1.0
        gimbal_range: 3 deg
        gimbal_rate: 5 deg/s
        ignition_delay: 0.2 s
        spool_up: 0.3 s
        tail_off: 0.2 s
        restarts: 2
aero:
  rcs:
""" + "".join(_thruster(x, 0, 0, (0, 0, s)) for x, s in ((3.5, 1), (0.5, -1), (3.5, -1), (0.5, 1))) \
    + "".join(_thruster(x, 0, 0, (0, s, 0)) for x, s in ((3.5, 1), (0.5, -1), (3.5, -1), (0.5, 1))) \
    + "".join(_thruster(2.0, y, 0, (0, 0, s)) for y, s in ((1, 1), (-1, -1), (1, -1), (-1, 1)))


def _fly(write, tmp_path, program, seconds, rates=(0.0, 0.0, 0.0), vacuum=False, vehicle=VEHICLE):
    """Fly ``program`` on the craft (or ``vehicle``, a vehicle file's text); ``vacuum``: as
    a spacecraft without aerodynamics (``aero: {aerodynamics: false}``, the RCS alone in
    the derivative)."""
    write("vehicle.yaml", vehicle.replace("aero:\n", "aero:\n  aerodynamics: false\n") if vacuum else vehicle)
    write("program.py", program)
    path = write("scenario.yaml", f"""\
        name: rcs
        vehicle: vehicle.yaml
        program: program.py
        mission:
          epoch: 2026-11-26T12:00:00Z
          start: {{orbit: {{altitude: 700 km, inclination: 28.5 deg}}}}
          duration: {seconds} s
          initial_rates: {list(rates)}
        """)
    out = tmp_path / "run.mcap"
    summary = fly(load(path), out)
    events = {e["name"]: e for e in summary["bodies"]["craft"]["events"]}
    states = [m for _, _, m in messages(out, ["/craft/state"])]
    return events, states


SLEW = """
import numpy as np
from rocketsim.frames.quaternion import quat_to_matrix
def main(fc):
    body = fc._craft                 # the test reads the model's mass properties
    _, x_cm, ixx, iyy, izz = body.vehicle.mass_properties(body.y)
    fc.rcs(True)
    m = quat_to_matrix(fc.attitude)
    fc.point_at(m[:, 2])            # the body z axis: a 90 deg turn about body y
    fc.event("target", nose=[float(c) for c in m[:, 0]], target=[float(c) for c in m[:, 2]],
             x_cm=float(x_cm), iyy=float(iyy))
    fc.sleep(20.0)
"""


def _law_response(times, angle):
    """Reference: the autopilot law's own planar response (module docstring of
    rocketsim.flight.autopilot), theta'' = 2 zeta omega_n (clip(omega_n/(2 zeta) e,
    RATE_LIMIT) - theta'), e = angle - theta, integrated by scipy's DOP853 from rest."""
    k = 2.0 * ZETA * OMEGA_N

    def rhs(_, s):
        wanted = float(np.clip(OMEGA_N / (2.0 * ZETA) * (angle - s[0]), -RATE_LIMIT, RATE_LIMIT))
        return [s[1], k * (wanted - s[1])]

    sol = solve_ivp(rhs, (0.0, times[-1]), [0.0, 0.0], method="DOP853", t_eval=times, rtol=1e-10,
                    atol=1e-12, max_step=0.01)
    return sol.y[0]


def test_rcs_slews_90_degrees_like_the_law_and_settles(write, tmp_path):
    """A 90 deg turn in a coast with only the RCS. References: (1) the law's analytic
    planar response (rate-limited damped second order, integrated by DOP853): the
    angle turned stays within 0.5 deg of it at every 0.1 s sample (the autopilot holds
    its command for each 20 ms step, a lag of about one step); (2) the bang-bang bound:
    the thrusters' largest torque about y is T (3.5 - 0.5) m from the pitch couple plus
    2 T |2 - x_cm| from the roll thrusters pushing alike, and no turn of 89 deg is faster
    than 2 sqrt(theta I_yy / tau_max) (half the way at full torque, half braking)."""
    events, states = _fly(write, tmp_path, SLEW, 20.0)
    target_event = events["target"]
    nose0 = np.array(target_event["nose"])
    target = np.array(target_event["target"])
    t0 = target_event["time_s"]
    times, turned, residual = [], [], []
    for m in states:
        if m["t"] < t0:
            continue
        nose = quat_to_matrix(np.array(m["attitude"]))[:, 0]
        times.append(m["t"] - t0)
        turned.append(math.atan2(float(np.linalg.norm(np.cross(nose0, nose))), float(nose0 @ nose)))
        residual.append(math.acos(float(np.clip(nose @ target, -1.0, 1.0))))
    times, turned = np.array(times), np.array(turned)
    reference = _law_response(times, math.pi / 2)
    gap = np.degrees(np.abs(turned - reference))
    ninety = times[np.argmax(turned >= math.radians(89.0))]
    tau_max = THRUST * (3.0 + 2.0 * abs(2.0 - target_event["x_cm"]))
    fastest = 2.0 * math.sqrt(math.radians(89.0) * target_event["iyy"] / tau_max)
    print(f"\nlargest gap from the law's response {gap.max():.3f} deg; error after {times[-1]:.1f} s "
          f"{math.degrees(residual[-1]):.4f} deg; 89 deg reached in {ninety:.2f} s "
          f"(bang-bang bound {fastest:.2f} s)")
    assert gap.max() < 0.5
    assert math.degrees(residual[-1]) < 0.05               # settled
    assert np.max(np.abs(states[-1]["body_rates"])) < 1e-3
    assert ninety > fastest


ROLL = """
import math
def main(fc):
    fc.rcs(True)
    fc.point(math.radians(5.0), math.radians(90.0), roll=math.radians(30.0))
    fc.sleep(45.0)
    fc.event("held", pitch=fc.pitch, heading=fc.heading, roll=fc.roll)
"""


def test_a_commanded_roll_is_held(write, tmp_path):
    """Reference: the command itself. The craft flown as a vacuum spacecraft
    (no aerodynamics, the RCS alone). fc.point(5 deg, 90 deg, roll=30 deg) from the
    start attitude; after 45 s (a turn of up to 180 deg at the 8.6 deg/s rate limit,
    then settling) fc.roll, fc.pitch and fc.heading read the command within 0.15 deg.
    The local horizon turns at the orbit's rate n = 1.05e-3 rad/s, which the law
    (alpha = omega_n^2 e - 2 zeta omega_n w) follows with a steady lag of
    e = 2 zeta n / omega_n = 0.11 deg; the tolerance is that lag plus a margin."""
    events, _ = _fly(write, tmp_path, ROLL, 46.0, vacuum=True)
    held = events["held"]
    print(f"\nheld: pitch {math.degrees(held['pitch']):.4f} heading {math.degrees(held['heading']):.4f} "
          f"roll {math.degrees(held['roll']):.4f} deg")
    assert abs(math.degrees(held["roll"]) - 30.0) < 0.15
    assert abs(math.degrees(held["pitch"]) - 5.0) < 0.15
    assert abs(math.degrees(held["heading"]) - 90.0) < 0.15


FREE = """
def main(fc):
    body = fc._craft
    _, _, ixx, iyy, izz = body.vehicle.mass_properties(body.y)
    fc.event("inertia", moments=[float(ixx), float(iyy), float(izz)])
    fc.point(0.0, 0.0)              # a command, but neither engines nor RCS to act on it
    fc.sleep(20.0)
"""


def test_engines_off_and_rcs_off_leave_the_angular_momentum_alone(write, tmp_path):
    """Reference: conservation of angular momentum (Euler's equations without torque).
    A tumbling craft (0.05, 0.03, -0.02) rad/s with an attitude command but RCS off and
    engines off: H = A I w (ECI) after 20 s equals the start's to 1e-9 relative
    (the RK4 step's error), while the body rates themselves change (the craft is
    not symmetric about the axis it spins on)."""
    events, states = _fly(write, tmp_path, FREE, 20.0, rates=(0.05, 0.03, -0.02))
    inertia = np.array(events["inertia"]["moments"])

    def momentum(m):
        return quat_to_matrix(np.array(m["attitude"])) @ (inertia * np.array(m["body_rates"]))

    first, last = momentum(states[0]), momentum(states[-1])
    change = np.linalg.norm(last - first) / np.linalg.norm(first)
    print(f"\nrelative change of H over {states[-1]['t'] - states[0]['t']:.1f} s: {change:.2e}")
    assert change < 1e-9
    assert np.linalg.norm(np.array(states[-1]["body_rates"]) - np.array(states[0]["body_rates"])) > 1e-3


def test_the_lander_quads_give_the_full_roll_torque_of_four_thrusters():
    """Reference: hand statics of vehicles/lander.yaml's quads (445 N thrusters,
    2.0 m off the axis, one tangential pair per quad): the largest roll torque
    either way is four thrusters at full thrust, 4 x 445 N x 2.0 m = 3 560 N m, with
    no pitch or yaw left over (the four quads' tangential pushes cancel off-axis).
    The file gives the quads' y and z to 5 digits (1.41421 m), so 1e-5 relative."""
    from rocketsim.vehicle.build import build
    from tests.aero_vehicles import shipped
    model = build(shipped("lander.yaml"))
    y = model.state(np.array([7e6, 0.0, 0.0]), np.zeros(3))
    torques = rcs_torques(model.arrays, y, model.mass_properties(y)[1])
    assert torques.shape == (3, 16)
    for sense in (1.0, -1.0):
        got = torques @ rcs_command(torques, np.array([sense * 1e6, 0.0, 0.0]))
        print(f"\nlargest roll torque {got[0]:.1f} N m, pitch/yaw left {got[1]:.2e} {got[2]:.2e}")
        assert abs(got[0] - sense * 4 * 445.0 * 2.0) < 1e-5 * 3560.0
        assert np.all(np.abs(got[1:]) < 1e-6 * 3560.0)


GN2_TANK = """\
      - {name: GN2, propellant: N2, density: 250 kg/m3, radius: 0.3 m, length: 0.5 m,
         position: 3.0 m, wall_mass: 10 kg, propellant_mass: 30 kg, feeds_engines: false}
"""

TANKS = """
from rocketsim.frames.quaternion import quat_to_matrix
def main(fc):
    fc.ignite()
    fc.sleep(3.0)
    fc.shutdown()
    fc.sleep(1.0)
    fc.event("burned", **{k.replace("/", "_"): v for k, v in fc.propellant.items()})
    fc.rcs(True)
    fc.point_at(quat_to_matrix(fc.attitude)[:, 2])
    fc.sleep(5.0)
    fc.event("turned", **{k.replace("/", "_"): v for k, v in fc.propellant.items()})
"""


def test_an_rcs_only_tank_feeds_the_thrusters_and_not_the_engine(write, tmp_path):
    """Reference: where each flow is drawn from (rocketsim.vehicle.engines and rcs: an
    engine from its stage's tanks, a thruster from the tank it names). The craft with a
    30 kg nitrogen bottle (``feeds_engines: false``) that all its thrusters use: a 3 s
    burn leaves the bottle untouched, to the bit, and drains the hydrazine; a turn on
    the thrusters with the engine off drains the bottle and leaves the hydrazine."""
    vehicle = VEHICLE.replace("tank: hydrazine", "tank: GN2").replace(
        "propellant_mass: 250 kg}\n", "propellant_mass: 250 kg}\n" + GN2_TANK)
    events, _ = _fly(write, tmp_path, TANKS, 10.0, vehicle=vehicle)
    burned, turned = events["burned"], events["turned"]
    print(f"\nafter the burn: hydrazine {burned['bus_hydrazine']:.3f} kg, GN2 {burned['bus_GN2']:.6f} kg; "
          f"after the turn: hydrazine {turned['bus_hydrazine']:.3f} kg, GN2 {turned['bus_GN2']:.6f} kg")
    assert burned["bus_GN2"] == 30.0
    assert burned["bus_hydrazine"] < 250.0 - 1.0          # ~3.9 kg at 4 kN, 310 s
    assert turned["bus_hydrazine"] == burned["bus_hydrazine"]
    assert turned["bus_GN2"] < 30.0 - 0.01                 # ~0.09 kg at 0.093 kg/s a thruster
