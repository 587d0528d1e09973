"""The return's guidance library (rocketsim.guidance) against independent references.

* Apollo's quadratic guidance (Klumpp 1974): its command is the start of the one
  quadratic acceleration profile that meets the target's position, velocity and
  acceleration at the time to go, found here by solving the boundary conditions as
  a linear system; re-solved every step on a double integrator it lands on the
  target at rest (the law's defining property).
* The vertical profile: re-solved every step on a falling point mass it reaches the
  ground at the touch speed (uniform-deceleration kinematics).
* Boost-back targeting: on a flat-Earth vacuum projectile, whose landing point is
  analytic, the velocity to gain found is the analytic one; the state at a burn's
  end matches scipy's DOP853 integrating the burn to second order in its length.
* The landing-point predictor: through air with a wind and the body's drag, it
  matches DOP853 on the same rotating-frame equations; with the landing burn it
  stops the fall at the ground.
* The learnt drag area converges on the scale of the readings; one Newton step of
  the descent's lean solves a linear miss exactly.
"""

import math

import numpy as np
from scipy.integrate import solve_ivp

from rocketsim.atmosphere.table import make_table
from rocketsim.bodies.gravity import point_mass_j2
from rocketsim.constants import (DEG, EARTH_J2, EARTH_MU, EARTH_OMEGA, EARTH_RADIUS_EQ,
                                 EARTH_RADIUS_POLAR)
from rocketsim.frames.geodetic import enu_basis, geodetic_to_ecef
from rocketsim.guidance import boostback, descent, powered_descent
from rocketsim.guidance.drag import DragArea
from rocketsim.guidance.landing_point import LandingPoint, entry_burn, landing_burn
from rocketsim.vehicle.contact import point_height

LAT, LON = 28.5 * DEG, -80.5 * DEG


def test_the_quadratic_command_starts_the_profile_that_meets_the_boundary_conditions():
    """a(t) = c0 + c1 t + c2 t^2 with r(T) = 0, v(T) = 0, a(T) = a_T solved as a linear
    system: the law's command is c0."""
    r0, v0, a_t, big_t = np.array((120.0, -40.0)), np.array((-8.0, 3.0)), np.array((0.5, -0.2)), 14.0
    # r(T) = r0 + v0 T + c0 T^2/2 + c1 T^3/6 + c2 T^4/12; v(T) = v0 + c0 T + c1 T^2/2 + c2 T^3/3
    system = np.array(((big_t ** 2 / 2, big_t ** 3 / 6, big_t ** 4 / 12),
                       (big_t, big_t ** 2 / 2, big_t ** 3 / 3),
                       (1.0, big_t, big_t ** 2)))
    for k in range(2):
        c = np.linalg.solve(system, (-r0[k] - v0[k] * big_t, -v0[k], a_t[k]))
        assert math.isclose(powered_descent.quadratic_acceleration(r0, v0, big_t, a_t)[k], c[0],
                            rel_tol=1e-12)


def test_the_quadratic_law_re_solved_every_step_lands_on_the_target_at_rest():
    r, v, big_t, dt = np.array((300.0, -150.0)), np.array((-20.0, 12.0)), 20.0, 1e-3
    t = 0.0
    while t < big_t - 0.05:
        a = powered_descent.quadratic_acceleration(r, v, big_t - t)
        r, v, t = r + v * dt + 0.5 * a * dt * dt, v + a * dt, t + dt
    assert np.linalg.norm(r) < 0.01 and np.linalg.norm(v) < 0.01     # m, m/s of 300 m, 23 m/s


def test_the_vertical_profile_re_solved_every_step_touches_down_at_the_touch_speed():
    plan = powered_descent.Plan(touch_speed=1.0)
    h, fall, g, dt = 2500.0, 230.0, 9.81, 1e-3
    planned = powered_descent.profile_acceleration(h, fall, g, plan)
    assert math.isclose(planned - g, (fall ** 2 - 1.0) / (2 * h))    # v^2 - v_td^2 = 2 a h
    while h > 0.0:
        a = powered_descent.profile_acceleration(h, fall, g, plan)
        fall -= (a - g) * dt
        h -= fall * dt
    assert abs(fall - 1.0) < 0.05                                     # m/s at the ground


def test_below_the_gate_the_drift_falls_linearly_to_nothing_at_the_contact():
    """Below the gate the wanted push is ``-v / t_go``, ``t_go`` the vertical profile's time
    to the contact: flown exactly (a point mass in still airless space, no autopilot lag)
    ``v / t_go`` is a constant, so the drift falls linearly with the time left, like the
    fall, down to the last ``terminal_time`` ``tau``, over which ``-v / tau`` takes it
    down by ``1/e``: ``v0 (tau / t_go0) / e`` is left at the contact (a time constant alone,
    ``-v / 2.5 s``, would leave ``v0 exp(-t_go0 / 2.5 s)``: 0.7 m/s of 2 m/s here)."""
    plan = powered_descent.Plan(lag=0.0)
    g, mass, thrust, dt = 9.81, 26e3, 845e3, 1e-3
    h = plan.gate_height - 0.01
    fall = powered_descent.gate_speed(200.0, 60.0, plan)       # on a profile lit at 200 m, 60 m/s
    v = np.array((2.0, -0.5))
    slowing = (fall ** 2 - plan.touch_speed ** 2) / (2.0 * h)
    start = powered_descent.contact_time(h, fall, slowing, plan)
    t = 0.0
    while h > 0.0:
        direction, throttle = powered_descent.command(np.zeros(2), (*v, -fall), h, mass, thrust, g, 0.0,
                                                      (*v, -fall), plan)
        a = throttle * thrust / mass * direction
        if t + 0.5 < start and int(t / dt) % 500 == 0:          # linear in the time left
            assert np.allclose(v, np.array((2.0, -0.5)) * (1.0 - t / start), atol=0.02)
        v, fall, h, t = v + a[:2] * dt, fall - (a[2] - g) * dt, h - fall * dt, t + dt
    print(f"\ndrift at the contact {np.linalg.norm(v):.3f} m/s of 2.06 m/s at the gate, "
          f"{t:.2f} s from it (profile: {start:.2f} s)")
    left = math.hypot(2.0, -0.5) * plan.terminal_time / start / math.e
    assert math.isclose(np.linalg.norm(v), left, rel_tol=0.1) and abs(fall - plan.touch_speed) < 0.05


def test_the_command_in_still_thin_air_leans_the_thrust_along_the_wanted_push():
    """Out of the air the thrust alone pushes sideways: the lean's tangent is the wanted
    horizontal acceleration over the vertical one (from the command's own law)."""
    plan = powered_descent.Plan()
    offset, velocity = np.array((40.0, 0.0, 0.0)), np.array((0.0, 0.0, -60.0))
    direction, throttle = powered_descent.command(offset, velocity, 1500.0, 30e3, 914e3, 9.81, 0.0,
                                                  velocity, plan)
    up = powered_descent.profile_acceleration(1500.0, 60.0, 9.81, plan)
    fall = 60.0
    slowing = up - 9.81
    time_to_go = max((fall - powered_descent.gate_speed(1500.0, fall, plan)) / slowing, plan.min_time_to_go)
    wanted = powered_descent.quadratic_acceleration(offset[:2], velocity[:2], time_to_go)
    assert wanted[0] < 0.0                                            # back towards the pad
    assert math.isclose(direction[0] / direction[2], wanted[0] / up, rel_tol=1e-9)
    assert math.isclose(throttle, 30e3 * math.hypot(wanted[0], up) / 914e3, rel_tol=1e-9)


def flat_landing(r, v, g=9.81):
    """Where a vacuum projectile from height r[2] with velocity v lands on a flat ground."""
    t = (v[2] + math.sqrt(v[2] ** 2 + 2 * g * r[2])) / g
    return r[:2] + v[:2] * t, t


def test_the_velocity_to_gain_is_the_analytic_one_on_a_flat_vacuum_projectile():
    r, v, target = np.array((0.0, 0.0, 80e3)), np.array((1500.0, 100.0, 900.0)), np.array((-20e3, 5e3))
    axes = np.array(((1.0, 0.0, 0.0), (0.0, 1.0, 0.0)))        # the horizontal plane: the fall time holds
    # the miss is linear in the horizontal velocity: Newton is exact once its steps are no
    # longer cut to MAX_PASS_STEP (1580 m/s to gain here: four passes)
    to_gain = boostback.velocity_to_gain(lambda trial: flat_landing(r, trial)[0] - target, v, axes,
                                         passes=4)
    _, t_fall = flat_landing(r, v)
    required = target / t_fall                                  # the analytic horizontal velocity
    assert np.allclose(v[:2] + to_gain[:2], required, atol=1e-6) and to_gain[2] == 0.0


def test_the_state_at_a_burns_end_matches_the_reference_integrator_to_second_order():
    r = np.array(geodetic_to_ecef(LAT, LON, 70e3))
    v = np.array((800.0, -1200.0, 900.0))
    errors = []
    for size in (400.0, 200.0, 100.0):
        dv = size * np.array((-0.8, 0.6, 0.0))
        rb, vb, tb = boostback.after_burn(r, v, dv, 25.0, EARTH_MU)
        along = dv / size

        def rhs(t, s):
            g = -EARTH_MU * s[:3] / np.linalg.norm(s[:3]) ** 3
            return np.concatenate((s[3:], g + 25.0 * along))
        sol = solve_ivp(rhs, (0.0, tb), np.concatenate((r, v)), method="DOP853", rtol=1e-11, atol=1e-6)
        errors.append(np.linalg.norm(rb - sol.y[:3, -1]))
    assert errors[0] < 20.0                    # m after a 16 s burn (gravity held at its start)
    assert 6.0 < errors[0] / errors[1] < 10.0  # the position's error is third order in the burn's time


def test_the_cutoff_waits_for_the_part_along_the_thrust():
    thrust = np.array((1.0, 0.0, 0.0))
    # half a 0.1 s step and a 0.25 s tail-off at 30 m/s^2: 5.25 m/s along the thrust
    assert not boostback.cutoff_due(np.array((5.3, 40.0, 0.0)), thrust, 30.0, 0.1, 0.25)
    assert boostback.cutoff_due(np.array((5.2, 40.0, 0.0)), thrust, 30.0, 0.1, 0.25)


def reference_fall(r, v, mass, table, area):
    """Where the stage lands: DOP853 on the rotating-frame equations, drag through ``table``
    (density and wind against height) with the drag area ``area`` (m^2)."""
    heights = table.heights

    def rhs(t, s):
        x, y, z = s[:3]
        vel = s[3:]
        gx, gy, gz = point_mass_j2(x, y, z, EARTH_MU, EARTH_RADIUS_EQ, EARTH_J2)
        w = np.array((0.0, 0.0, EARTH_OMEGA))
        h = point_height(x, y, z, EARTH_RADIUS_EQ, EARTH_RADIUS_POLAR)
        up = s[:3] / np.linalg.norm(s[:3])
        east = np.cross((0.0, 0.0, 1.0), up)
        east /= np.linalg.norm(east)
        north = np.cross(up, east)
        rho = np.interp(h, heights, table.density)
        wind = np.interp(h, heights, table.wind_east) * east + np.interp(h, heights, table.wind_north) * north
        air = vel - wind
        acc = (np.array((gx, gy, gz)) - 2.0 * np.cross(w, vel) - np.cross(w, np.cross(w, s[:3]))
               - 0.5 * rho * np.linalg.norm(air) * area / mass * air)
        return np.concatenate((vel, acc))

    def ground(t, s):
        return point_height(s[0], s[1], s[2], EARTH_RADIUS_EQ, EARTH_RADIUS_POLAR)
    ground.terminal, ground.direction = True, -1
    sol = solve_ivp(rhs, (0.0, 1e4), np.concatenate((r, v)), method="DOP853", rtol=1e-10, atol=1e-6,
                    events=ground, max_step=2.0)
    return sol.y_events[0][0][:3]


def windy_day():
    """An isothermal day (scale height 7.2 km) with a jet of 50 m/s from the west at 12 km."""
    h = np.arange(0.0, 100e3 + 1.0, 50.0)
    density = 1.225 * np.exp(-h / 7200.0)
    jet = 50.0 * np.exp(-((h - 12e3) / 4e3) ** 2)
    return make_table(0.0, 50.0, density, density * 287.05 * 250.0, np.full(h.size, 250.0),
                      np.full(h.size, 317.0), np.full(h.size, 1.6e-5), jet, -0.3 * jet)


def starting_state(height, speed, elevation_deg, heading_deg):
    east, north, up = enu_basis(LAT, LON)
    el, hd = elevation_deg * DEG, heading_deg * DEG
    d = math.cos(el) * (math.sin(hd) * east + math.cos(hd) * north) + math.sin(el) * up
    return np.array(geodetic_to_ecef(LAT, LON, height)), speed * d


def test_the_predicted_landing_point_matches_the_reference_integrator_through_wind():
    table = windy_day()
    r, v = starting_state(50e3, 700.0, -60.0, 250.0)
    area, mass = 18.0, 28e3
    mach = np.array((0.0, 10.0))
    predictor = LandingPoint(table, mach, np.full(2, area), np.zeros(2), 1.0, 0.0)
    point = predictor(r, v, mass).point
    expected = reference_fall(r, v, mass, table, area)
    calm = LandingPoint(make_table(0.0, 50.0, table.density, table.pressure, table.temperature,
                                   table.speed_of_sound, table.viscosity), mach, np.full(2, area),
                        np.zeros(2), 1.0, 0.0)(r, v, mass).point
    print(f"\nmiss against DOP853: {np.linalg.norm(point - expected):.2f} m; the wind moved the point "
          f"{np.linalg.norm(calm - expected):.0f} m")
    assert np.linalg.norm(calm - expected) > 200.0          # the wind matters here
    assert np.linalg.norm(point - expected) < 5.0           # m, over a 50 km fall


def test_the_predicted_landing_burn_stops_the_fall_at_the_ground():
    table = windy_day()
    r, v = starting_state(9e3, 280.0, -85.0, 250.0)
    mass, thrust, flow = 30e3, 845e3, 300.0
    mach = np.array((0.0, 10.0))
    predictor = LandingPoint(table, mach, np.full(2, 15.0), np.zeros(2), 1.0, 0.0)
    down = predictor(r, v, mass, landing=landing_burn(thrust, flow, 0.8, 1.0, 22e3, 8e3, 0.0))
    height = point_height(*down.point, EARTH_RADIUS_EQ, EARTH_RADIUS_POLAR)
    assert 0.0 <= height < 3.0                          # m: slowed to 1 m/s just above the ground
    assert down.ignition_mass > down.mass > 22e3        # lit, and the tanks held out
    # what it burnt is what the throttle it flew at draws: at least the hover's share
    burnt = down.ignition_mass - down.mass
    assert burnt > flow * (mass * 9.81 / thrust) * 10.0


def test_the_predicted_landing_burn_burns_what_the_rocket_equation_says_with_the_airs_push():
    """A vertical fall through airless ground with a constant pressure ``p`` (no drag):
    the landing burn lit at the throttle ``plan`` and flown at a constant deceleration
    ``a`` holds ``T / m = k = a + g``; an engine of vacuum thrust ``T_vac``, exit ``A_e``
    and full flow ``q`` draws ``u q`` at the throttle ``u = (m k + p A_e) / T_vac``
    (docs/physics.md#propulsion), so ``dm/dt = -(m k + L) / c`` (``c = T_vac / q``,
    ``L = p A_e``) and ``m + L / k`` decays as ``exp(-k t / c)``: burnt over the burn's
    ``t_b = (V - v_td) / a`` is ``(m0 + L / k) (1 - exp(-k t_b / c))``. Lit where
    ``m0 k + L = plan T_vac``, at the height ``H = (v0^2 + 2 g h0 - v_td^2) / 2k`` of the
    free fall from ``h0`` at ``v0``. Leaving out the pressure's push (a flow of
    ``F / (T_vac - L)`` of the full) gives 155 kg (3 %) less here."""
    h = np.arange(0.0, 20e3 + 1.0, 50.0)
    pressure = 101325.0
    table = make_table(0.0, 50.0, np.zeros(h.size), np.full(h.size, pressure), np.full(h.size, 288.0),
                       np.full(h.size, 340.0), np.full(h.size, 1.8e-5))
    h0, v0, m0 = 6e3, 250.0, 30e3
    vacuum, flow, area, plan, touch = 914e3, 300.0, 0.68, 0.8, 1.0
    r, v = starting_state(h0, v0, -90.0, 0.0)
    predictor = LandingPoint(table, np.array((0.0, 10.0)), np.zeros(2), np.zeros(2), 1.0, 0.0)
    down = predictor(r, v, m0, landing=landing_burn(vacuum, flow, plan, touch, 0.0, 8e3, area))
    g = EARTH_MU / float(np.linalg.norm(r)) ** 2
    loss = pressure * area
    k = (plan * vacuum - loss) / m0
    lit = (v0 ** 2 + 2.0 * g * h0 - touch ** 2) / (2.0 * k)
    speed = math.sqrt(v0 ** 2 + 2.0 * g * (h0 - lit))
    burn_time = (speed - touch) / (k - g)
    burnt = (m0 + loss / k) * (1.0 - math.exp(-k * burn_time / (vacuum / flow)))
    predicted = down.ignition_mass - down.mass
    print(f"\nlanding burn: predicted {predicted:.1f} kg, rocket equation {burnt:.1f} kg")
    assert down.ignition_mass == m0
    assert math.isclose(predicted, burnt, rel_tol=3e-3)


def test_the_entry_burn_ends_where_the_landing_keeps_its_margin_and_the_point_moves_smoothly():
    """The entry burn's end airspeed, solved (descent.entry_end_speed), is the aim when
    the propellant allows it, else the speed at which the touchdown keeps exactly the
    margin; across the propellant at which one turns into the other the predicted
    landing point moves without a step (what the lean's Newton steps need)."""
    table = windy_day()
    r, v = starting_state(55e3, 1100.0, -70.0, 250.0)
    aero = (np.array((0.0, 1.0, 2.0, 10.0)), np.array((15.0, 23.0, 21.0, 21.0)), np.zeros(4))
    predictor = LandingPoint(table, *aero, 1.0, 0.0)
    dry, margin, aim = 22e3, 800.0, 650.0
    landing = landing_burn(914e3, 300.0, 0.8, 1.0, dry, 8e3, 0.68)

    def solved(propellant):
        def kept(speed):
            entry = entry_burn(math.inf, speed, 3 * 914e3, 900.0, dry)
            return predictor(r, v, dry + propellant, entry=entry, landing=landing).mass - dry - margin
        speed = descent.entry_end_speed(kept, aim, 1100.0)
        return speed, kept(speed), predictor(r, v, dry + propellant, entry=entry_burn(
            math.inf, speed, 3 * 914e3, 900.0, dry), landing=landing).point

    plenty, short = solved(20e3), solved(6e3)
    assert plenty[0] == aim and plenty[1] > 0.0
    assert short[0] > aim + 20.0 and abs(short[1]) < 5.0         # kg of the margin at the root
    points = np.array([solved(p)[2] for p in np.arange(5.5e3, 8.5e3, 250.0)])
    steps = np.linalg.norm(np.diff(points, axis=0), axis=1)
    print(f"\nend speed {short[0]:.1f} m/s with 6 t; the point's steps per 250 kg: {np.round(steps, 1)}")
    assert steps.max() < 3.0 * np.median(steps) + 1.0


def test_the_learnt_drag_area_converges_on_the_readings_scale():
    mach, area = np.array((0.0, 1.0, 2.0)), np.array((15.0, 23.0, 21.0))
    learnt = DragArea(mach, area, time_constant=3.0)
    for k in range(300):
        m, q, M = 30e3, 20e3, 0.5 + k * 0.004
        learnt.update(0.1 * k, m, 1.1 * q * np.interp(M, mach, area) / m, q, M)
    assert math.isclose(learnt.scale, 1.1, rel_tol=1e-9)
    learnt.update(31.0, 30e3, 50.0, 100.0, 1.0)            # too thin an air: ignored
    assert math.isclose(learnt.scale, 1.1, rel_tol=1e-9)


def test_one_newton_step_of_the_lean_solves_a_linear_miss():
    jacobian, bias = np.array(((900.0, 120.0), (-60.0, 700.0))), np.array((350.0, -420.0))
    lean, miss = descent.solve_lean(lambda trial: bias + jacobian @ trial, np.zeros(2), 5.0)
    assert np.allclose(miss, bias) and np.allclose(jacobian @ lean + bias, 0.0, atol=1e-9)
    capped, _ = descent.solve_lean(lambda trial: bias + jacobian @ trial, np.zeros(2), 0.1)
    assert math.isclose(np.linalg.norm(capped), 0.1) and np.allclose(capped / 0.1, lean / np.linalg.norm(lean))


def test_a_leaning_body_points_its_nose_away_from_the_push():
    back, push = np.array((0.0, 0.0, 1.0)), np.array((1.0, 0.0, 0.0))
    nose = descent.lean_attitude(back, push, 0.1)
    assert np.allclose(nose, (-math.sin(0.1), 0.0, math.cos(0.1)))


def test_the_throttle_gives_the_force_asked_of_an_engine_in_the_air():
    """An engine's thrust in the air is ``u T_vac - p A_e`` (docs/physics.md#propulsion):
    the throttle for a force, the pressure's loss counted, gives that force exactly."""
    vacuum, loss = 914e3, 101325.0 * 0.68
    for force in (400e3, 505e3, 800e3):
        u = powered_descent.throttle_for(force, vacuum - loss, loss)
        assert math.isclose(u * vacuum - loss, force, rel_tol=1e-12)
    assert math.isclose(powered_descent.throttle_for(vacuum - loss, vacuum - loss, loss), 1.0)
