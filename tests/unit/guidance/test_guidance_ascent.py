"""Ascent insertion guidance (ascent, peg, target_orbit) against independent references.

* The thrust integrals L, J, S, Q, P, H against their definitions, the moments of the
  thrust acceleration ``a(t) = ve / (tau - t)`` of one constant-thrust phase or of two
  (a throttle-down), by scipy's adaptive quadrature; the phases of a burn against the
  rocket equation.
* Closed-loop Powered Explicit Guidance against the reference integrator: an upper stage
  (Falcon 9-class second stage at staging) flown by scipy's DOP853 at 1e-10 under
  inverse-square gravity, the guidance solved every second from the state and its law
  followed exactly between; cut off when the orbital energy reaches the target's. It
  must end on the target radius, flight-path angle, speed and plane -- also when it
  starts 2 deg out of a target plane of fixed node, aims at an elliptical orbit, loses a
  fifth of its thrust halfway (the engines "whatever they do": the guidance reads the
  acceleration each cycle), or flies its last 150 m/s at 39 % thrust as planned (then the
  law must hardly turn when the throttle steps down: the plan held it).
* Optimality: the linear-tangent law is the minimum-propellant steering in a uniform
  gravity field (Bryson & Ho, *Applied Optimal Control*, 1975, sec. 2.7); over a round
  Earth PEG's burn must cost no more than the best burn scipy's SLSQP finds over a
  richer family (the pitch above the local horizontal a cubic in time, four
  coefficients and the burn time free), integrated by fixed-step RK4 on the same planar
  equations: within 0.05 % of the burn time.
* The target: an insertion state for a target in Kozai mean elements has those mean
  elements (rocketsim.frames.mean_elements, itself checked against Kozai's and
  Brouwer's closed forms in tests/unit/frames/test_mean_elements.py) at every argument of latitude
  (the points chosen away from the vertex: the mean orbit's osculating inclination there
  is below its mean one, so no point of it reaches the mean inclination's latitude);
  the plane through a point has the inclination and holds the point; the launch
  azimuth reaches the inclination (the plane's heading at the pad, ``sin(b) = cos(i) /
  cos(lat)``, Vallado 4th ed. eq. 6-19, with the ground's eastward speed taken off).
"""

import math

import numpy as np
import pytest
from scipy.integrate import quad, solve_ivp
from scipy.optimize import minimize

from rocketsim import fly
from rocketsim.api.flying import load as load_scenario
from rocketsim.constants import DEG, EARTH_MU, EARTH_OMEGA, EARTH_RADIUS_EQ, G0
from rocketsim.frames.mean_elements import mean_elements_of_state
from rocketsim.guidance.ascent import launch_azimuth
from rocketsim.guidance.peg import burn_phases, cycle, settle, start, thrust_integrals, unit
from rocketsim.guidance.target_orbit import Orbit, plane_normal, plane_through
from tests.conftest import ROOT

# a Falcon 9-class second stage just after staging (vehicles/falcon9-block5.yaml, 10 t payload)
THRUST, ISP = 934e3, 348.0                   # N, s
MASS = 121.5e3                               # kg, fairing still on
EXHAUST = ISP * G0
R0 = EARTH_RADIUS_EQ + 75e3                  # m
SPEED0, CLIMB0 = 2400.0, 20.0 * DEG          # m/s inertial, flight-path angle
TARGET = EARTH_RADIUS_EQ + 200e3             # m
FINAL = 150.0                                # m/s flown at the lowest throttle (the Insertion's default)


@pytest.mark.parametrize("phases", [[(380.0, 420.0, EXHAUST)],
                                    [(300.0, 420.0, EXHAUST), (25.0, (420.0 - 300.0) / 0.39, EXHAUST)]])
def test_the_thrust_integrals_are_the_moments_of_the_thrust_acceleration(phases):
    """A burn most of a stage long; then one ending at 39 % thrust (the Merlin Vacuum's lowest)."""
    starts = np.cumsum([0.0] + [duration for duration, _, _ in phases])
    end = starts[-1]

    def a(t):
        k = min(np.searchsorted(starts, t, side="right") - 1, len(phases) - 1)
        _, tau, exhaust = phases[k]
        return exhaust / (tau - (t - starts[k]))

    def integral(f):
        return sum(quad(f, starts[k], starts[k + 1], epsabs=0, epsrel=1e-13)[0] for k in range(len(phases)))

    moment = [integral(lambda t, n=n: t ** n * a(t)) for n in range(3)]
    double = [integral(lambda s, n=n: (end - s) * s ** n * a(s)) for n in range(3)]
    L, J, S, Q, P, H = thrust_integrals(phases)
    np.testing.assert_allclose([L, J, H], moment, rtol=1e-10)
    np.testing.assert_allclose([S, Q, P], double, rtol=1e-9)


def test_the_burn_phases_gain_the_speed_asked_for():
    """The rocket equation: each phase's ``-ve ln(1 - b / tau)`` adds up to the speed, the
    last phase's to ``final_speed``; the low phase's tau is the mass then over its flow."""
    phases = burn_phases(5000.0, 420.0, EXHAUST, 150.0, 0.39)
    gains = [-exhaust * math.log1p(-duration / tau) for duration, tau, exhaust in phases]
    assert sum(gains) == pytest.approx(5000.0, rel=1e-12) and gains[1] == pytest.approx(150.0, rel=1e-12)
    assert phases[1][1] == pytest.approx((420.0 - phases[0][0]) / 0.39, rel=1e-12)
    assert burn_phases(100.0, 420.0, EXHAUST, 150.0, 0.39) == [(420.0 * -math.expm1(-100.0 / EXHAUST),
                                                                  420.0, EXHAUST)]


def initial_state(out_of_plane_deg=0.0, inclination=51.6 * DEG):
    """Position and velocity at staging over the equator heading north-east in the plane of
    ``inclination`` through the point (node at x), the velocity turned out of it by
    ``out_of_plane_deg``."""
    r = np.array([R0, 0.0, 0.0])
    normal = plane_normal(inclination, 0.0)
    along = np.cross(normal, r / R0)
    turn = out_of_plane_deg * DEG
    horizontal = math.cos(turn) * along + math.sin(turn) * normal
    return r, SPEED0 * (math.sin(CLIMB0) * r / R0 + math.cos(CLIMB0) * horizontal)


def fly_closed_loop(orbit, r, v, thrust_at=lambda t: THRUST, period=1.0, lowest=None):
    """The burn flown by DOP853 with PEG solved every ``period`` s from the state (the
    accelerometer's thrust acceleration, the engine's exhaust velocity), cut off when the
    energy reaches the last target's; with ``lowest``, the last FINAL m/s planned at that
    throttle and flown there from the planned switch on (a step down). Returns (state at
    cut-off, last solution, time, the turn of the law at the switch, rad)."""
    t, y = 0.0, np.concatenate([r, v, [MASS]])
    solution, throttle, turn = None, 1.0, None

    def rhs(time, s, law, throttle):
        d = math.sqrt(s[0] ** 2 + s[1] ** 2 + s[2] ** 2)
        thrust = thrust_at(time) * throttle
        push = thrust / s[6] * law.direction(time)
        return np.concatenate([s[3:6], -EARTH_MU * s[:3] / d ** 3 + push, [-thrust / EXHAUST]])

    while True:
        if lowest is not None and throttle == 1.0 and solution is not None and solution.switch is not None \
                and t >= solution.switch - 1e-9:
            throttle = lowest
            planned = solution.direction(t)
            solution = settle(solution, t, y[:3], y[3:6], thrust_at(t) * throttle / y[6], EXHAUST, orbit)
            turn = math.acos(min(1.0, planned @ solution.direction(t)))
        final = (FINAL, lowest) if lowest is not None and throttle == 1.0 else (0.0, 1.0)
        acceleration = thrust_at(t) * throttle / y[6]
        if solution is None:
            solution = start(t, y[:3], y[3:6], acceleration, EXHAUST, orbit, final)
        elif solution.tgo - (t - solution.t) > 2.0:          # frozen in the last 2 s
            solution = cycle(solution, t, y[:3], y[3:6], acceleration, EXHAUST, orbit, False, final)
        wanted = 0.5 * solution.target.speed ** 2 - EARTH_MU / solution.target.radius

        def short(time, s, law, throttle):
            return 0.5 * (s[3:6] @ s[3:6]) - EARTH_MU / np.linalg.norm(s[:3]) - wanted
        short.terminal = True
        until = t + period
        if throttle == 1.0 and solution.switch is not None and lowest is not None:
            until = min(until, max(solution.switch, t + 1e-3))
        flown = solve_ivp(rhs, (t, until), y, method="DOP853", rtol=1e-10, atol=1e-6,
                          events=short, args=(solution, throttle))
        t, y = flown.t[-1], flown.y[:, -1]
        if flown.status == 1:
            return y, solution, t, turn


def misses(y, solution):
    """(radius m, flight-path speed m/s, speed m/s, out-of-plane speed m/s) off the target."""
    r, v = y[:3], y[3:6]
    target = solution.target
    distance, speed = np.linalg.norm(r), np.linalg.norm(v)
    return (distance - target.radius, (r @ v) / distance - speed * math.sin(target.flight_path),
            speed - target.speed, float(target.normal @ v))


@pytest.mark.parametrize("case", ["circular", "out of plane", "elliptical", "thrust drop", "throttle-down"])
def test_peg_flown_by_the_reference_integrator_ends_on_the_target(case):
    r, v = initial_state(2.0 if case == "out of plane" else 0.0)
    apoapsis = EARTH_RADIUS_EQ + 400e3 if case == "elliptical" else TARGET
    # the plane of node 0 (through the start): a start out of it turns into it
    orbit = Orbit(TARGET, apoapsis, 51.6 * DEG, raan=0.0 if case == "out of plane" else None)
    thrust_at = (lambda t: THRUST * (0.8 if t > 180.0 else 1.0)) if case == "thrust drop" else (lambda t: THRUST)
    y, solution, t, turn = fly_closed_loop(orbit, r, v, thrust_at, lowest=0.39 if case == "throttle-down" else None)
    radius, climb, speed, across = misses(y, solution)
    print(f"\n{case}: cut-off at {t:.2f} s, misses {radius:.2e} m, {climb:.2e} m/s climb, "
          f"{speed:.2e} m/s, {across:.2e} m/s out of plane")
    assert abs(radius) < 5.0 and abs(climb) < 0.02 and abs(speed) < 0.02 and abs(across) < 0.02
    assert abs(solution.t + solution.tgo - t) < 0.5        # where the last solution said it would end
    if case == "throttle-down":                             # planned: the law hardly turns at the switch
        print(f"the law turned {math.degrees(turn):.4f} deg at the throttle-down")
        assert math.degrees(turn) < 0.05
    h = np.cross(y[:3], y[3:6])
    assert math.degrees(math.acos(h[2] / np.linalg.norm(h))) == pytest.approx(51.6, abs=2e-4)


def planar_burn(coefficients, burn_time, steps=400):
    """(radius, radial speed, horizontal speed) at the end of a planar burn flown with the
    pitch above the local horizontal a polynomial in ``t / burn_time``: fixed-step RK4 on
    the equations of motion in polar coordinates."""
    def rates(t, s):
        r, vr, vh, m = s
        x = t / burn_time
        pitch = coefficients[0] + x * (coefficients[1] + x * (coefficients[2] + x * coefficients[3]))
        a = THRUST / m
        return np.array([vr, a * math.sin(pitch) - EARTH_MU / r ** 2 + vh * vh / r,
                         a * math.cos(pitch) - vr * vh / r, -THRUST / EXHAUST])
    h = burn_time / steps
    s = np.array([R0, SPEED0 * math.sin(CLIMB0), SPEED0 * math.cos(CLIMB0), MASS])
    for k in range(steps):
        t = k * h
        k1 = rates(t, s)
        k2 = rates(t + h / 2, s + h / 2 * k1)
        k3 = rates(t + h / 2, s + h / 2 * k2)
        k4 = rates(t + h, s + h * k3)
        s = s + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
    return s[:3]


def test_peg_burns_no_longer_than_the_best_cubic_pitch_program():
    orbit = Orbit(TARGET, TARGET, 51.6 * DEG, raan=0.0)
    r, v = initial_state()
    _, _, t_peg, _ = fly_closed_loop(orbit, r, v)
    circular = math.sqrt(EARTH_MU / TARGET)

    def constraints(x):
        radius, climb, horizontal = planar_burn(x[:4], x[4])
        return [(radius - TARGET) / 1e3, climb, horizontal - circular]

    guess = np.array([0.3, -0.5, 0.0, 0.0, t_peg + 5.0])
    best = minimize(lambda x: x[4], guess, method="SLSQP", constraints={"type": "eq", "fun": constraints},
                    options={"ftol": 1e-10, "maxiter": 200})
    print(f"\nburn time: PEG {t_peg:.3f} s, best cubic pitch program {best.x[4]:.3f} s")
    assert best.success and np.max(np.abs(constraints(best.x))) < 1e-3
    assert t_peg < best.x[4] * (1.0 + 5e-4)


@pytest.mark.parametrize("u_deg", [0.0, 40.0, 75.0, 150.0, 233.0])
def test_a_mean_target_state_has_the_mean_elements_asked_for(u_deg):
    orbit = Orbit(TARGET, TARGET, 51.6 * DEG, mean=True)
    normal = plane_normal(51.6 * DEG, 1.0)
    line = np.array([math.cos(1.0), math.sin(1.0), 0.0])
    point = TARGET * (math.cos(u_deg * DEG) * line + math.sin(u_deg * DEG) * np.cross(normal, line))
    target = orbit.at(point, np.cross(normal, point))
    up = unit(point - (point @ target.normal) * target.normal)
    r = target.radius * up
    v = target.speed * (math.sin(target.flight_path) * up + math.cos(target.flight_path) * np.cross(target.normal, up))
    mean = mean_elements_of_state(r, v)
    assert abs(mean.a - TARGET) < 20.0 and mean.e * mean.a < 20.0        # m
    assert math.degrees(mean.i) == pytest.approx(51.6, abs=1e-4)
    assert abs(point @ target.normal) < 1e-6 * TARGET                  # the free node: through the point


@pytest.mark.parametrize("along, climb", [(0.25, 0.0), (-0.25, 0.0), (0.0, 0.2), (0.15, 0.21)])
def test_a_cut_off_velocity_error_splits_the_mean_apsides_as_two_body_theory_says(along, climb):
    """The state the guidance aims for on the mean 200 km circle at 51.6 deg (40 deg past
    the node), with ``along`` m/s too much speed and ``climb`` m/s upwards, read as the
    campaign reads it (``Orbit.reached``: mean elements). Reference: a circular orbit
    perturbed by ``dv`` along the track and ``dv_r`` up, to first order (vis-viva and the
    eccentricity vector, ``e cos nu = h^2 / (mu r) - 1``, ``e sin nu = h v_r / mu``):
    ``da = 2 a dv / v``, ``a e = a sqrt((2 dv)^2 + dv_r^2) / v``, the periapsis moved by
    ``da - a e``, the apoapsis by ``da + a e``. A speed error alone moves one apsis by
    ``4 a dv / v`` (3.4 km per m/s) and leaves the other: the cut-off's half a step's gain
    at the Falcon 9-class second stage's lowest throttle (0.20 m/s) is 0.7 km of apsis."""
    orbit = Orbit(TARGET, TARGET, 51.6 * DEG, mean=True)
    normal = plane_normal(51.6 * DEG, 0.0)
    point = TARGET * (math.cos(40.0 * DEG) * np.array([1.0, 0.0, 0.0])
                      + math.sin(40.0 * DEG) * np.cross(normal, [1.0, 0.0, 0.0]))
    target = orbit.at(point, np.cross(normal, point))
    up = unit(point)
    ahead = np.cross(target.normal, up)
    r = target.radius * up
    v = target.speed * (math.sin(target.flight_path) * up + math.cos(target.flight_path) * ahead)
    periapsis, apoapsis, _ = orbit.reached(r, v + along * unit(v) + climb * up)
    speed = math.sqrt(EARTH_MU / TARGET)
    da = 2.0 * TARGET * along / speed
    ae = TARGET * math.hypot(2.0 * along, climb) / speed
    # within the aimed-at state's own distance from the mean circle (metres: the test above)
    assert periapsis - TARGET == pytest.approx(da - ae, abs=10.0)      # m
    assert apoapsis - TARGET == pytest.approx(da + ae, abs=10.0)


def test_the_plane_through_a_point_holds_it_at_the_inclination():
    point = np.array([2.0e6, 4.5e6, 3.1e6])
    for heading in (np.array([-1.0, 0.0, 0.6]), np.array([-1.0, 0.0, -0.6])):
        node = plane_through(point, heading, 51.6 * DEG)
        n = plane_normal(51.6 * DEG, node)
        assert abs(n @ point) < 1e-6 * np.linalg.norm(point)
        assert np.cross(n, point) @ heading > 0.0                       # moving the heading's way


@pytest.mark.parametrize("latitude_deg, inclination_deg", [(28.5, 51.6), (28.5, 28.5), (-39.3, 97.4)])
def test_the_launch_azimuth_reaches_the_inclination_at_orbital_speed(latitude_deg, inclination_deg):
    lat, inclination = latitude_deg * DEG, inclination_deg * DEG
    azimuth = launch_azimuth(lat, inclination, 200e3, 90.0 * DEG if inclination_deg < 90 else 180.0 * DEG)
    speed = math.sqrt(EARTH_MU / (EARTH_RADIUS_EQ + 200e3))
    ground = EARTH_OMEGA * EARTH_RADIUS_EQ * math.cos(lat)
    # over the ground at azimuth b_rot; inertial: that plus the ground's eastward speed
    # (east, north), whose speed is the orbital one when the ground speed is matched
    over_ground = np.array([math.sin(azimuth), math.cos(azimuth)])
    k = -ground * over_ground[0] + math.sqrt((ground * over_ground[0]) ** 2 - ground ** 2 + speed ** 2)
    east, north = k * over_ground + np.array([ground, 0.0])
    # the orbit's inclination from the inertial heading at the latitude: cos(i) = cos(lat) sin(b)
    heading = math.atan2(east, north)
    assert math.degrees(math.acos(math.cos(lat) * math.sin(heading))) == pytest.approx(inclination_deg, abs=1e-9)



def test_a_stage_short_of_propellant_ends_its_burn_ran_dry():
    """The Falcon 9-class ascent with 40 % of its second stage's load (a 0.1 s step, the
    booster's return left out, to keep it short): the stage runs dry before the target
    energy, the guidance says so (the program's log) and the vehicle is left suborbital."""
    loaded = load_scenario(ROOT / "scenarios" / "falcon9-leo.yaml",
                           {"programs": {}, "mission.duration": "600 s",
                            "vehicle.stages[second stage].tanks[LOX].propellant_mass": "30207 kg",
                            "vehicle.stages[second stage].tanks[RP-1].propellant_mass": "12793 kg"})
    run = fly(loaded, step=0.1)
    lines = [line["message"] for line in run.logs if "insertion" in line["message"]]
    assert len(lines) == 1 and lines[0].startswith("insertion (ran dry)"), lines
    assert run.bodies["falcon9-block5"].orbit is None          # no orbit: its periapsis is below the ground
