"""A part that nobody steers falls with a tumbling body's drag (docs/physics.md#tumbling-bodies).

References: the terminal speed ``sqrt(2 m g / (rho C_D A))`` where drag balances
weight, with the local gravity of a point mass plus J2 over the pole,
``g = mu / r^2 (1 - 3 J2 (a / r)^2)`` (Vallado, Fundamentals of Astrodynamics,
4th ed., eq. 8-20 with ``P2(1) = 1``) and the density of the U.S. Standard
Atmosphere 1976 (its own formulas, :func:`rocketsim.atmosphere.ussa1976.us_standard_1976`);
scipy's DOP853 on the same drag ODE at tight tolerance; and the decay of a circular
orbit per revolution from Gauss's variational equation for a tangential drag.
"""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from rocketsim.atmosphere.day import standard_table
from rocketsim.atmosphere.ussa1976 import us_standard_1976
from rocketsim.constants import EARTH_J2, EARTH_MU, EARTH_RADIUS_EQ, EARTH_RADIUS_POLAR
from rocketsim.dynamics.free_body import advance_free
from rocketsim.dynamics.nbody import make_field
from rocketsim.layout import make_params, make_state
from rocketsim.vehicle.tumbling import FREE_MOLECULAR_CD, continuum_cd, cylinder_area, tumbling_cd

MASS, RADIUS, LENGTH = 100.0, 1.0, 2.0          # a light drum: terminal speed ~30 m/s low down
AREA = cylinder_area(RADIUS, LENGTH)
H = 0.02


def _drop(height, seconds):
    """Drop the drum from rest at ``height`` (m) over the North Pole (where the air
    turning with the Earth is at rest in the inertial frame, so the fall is straight
    down); its states at every second and the pole's radius."""
    air = standard_table().arrays()
    p = make_params(MASS, (1.0, 2.0, 2.0), EARTH_MU, EARTH_RADIUS_EQ, EARTH_J2, EARTH_RADIUS_POLAR)
    fp = make_field("earth", 0.0, bodies=())
    y = make_state([0.0, 0.0, EARTH_RADIUS_POLAR + height], [0.0, 0.0, 0.0], [1.0, 0.0, 0.0, 0.0],
                   (0.1, 0.2, -0.05))
    states = [y]
    per_second = round(1.0 / H)
    for k in range(seconds):
        y, taken = advance_free(y, k * per_second, H, per_second, p, fp, air, AREA / MASS, LENGTH)
        states.append(y)
        if taken < per_second:
            break
    return np.array(states)


def test_a_dropped_drum_falls_at_the_analytic_terminal_speed():
    """From 10 km the drum reaches its terminal speed within a minute; at 6, 4 and
    2 km its speed is ``sqrt(2 m g / (rho C_D A))`` at the local density (USSA 1976)
    and gravity within 1 % (the speed lags the terminal speed falling into denser
    air by ``v_t^2 / (4 g H_rho)``, ~0.3 % here)."""
    states = _drop(10e3, 400)
    heights = states[:, 2] - EARTH_RADIUS_POLAR
    speeds = -states[:, 5]
    assert states[-1, 2] - EARTH_RADIUS_POLAR < 0.0            # it reached the ground
    for target in (6e3, 4e3, 2e3):
        k = int(np.argmax(heights < target))
        h, v = heights[k], speeds[k]
        air = us_standard_1976(np.array([h]))
        rho = float(air.density[0])
        r = EARTH_RADIUS_POLAR + h
        g = EARTH_MU / r ** 2 * (1.0 - 3.0 * EARTH_J2 * (EARTH_RADIUS_EQ / r) ** 2)
        cd = continuum_cd(v / float(air.speed_of_sound[0]))
        terminal = math.sqrt(2.0 * MASS * g / (rho * cd * AREA))
        assert v == pytest.approx(terminal, rel=0.01)
        assert 25.0 < v < 40.0


def test_the_fall_matches_dop853_on_the_same_drag_ode():
    """The first 120 s of the fall from 10 km against scipy's DOP853 (rtol 1e-11) on
    ``r'' = g(r) - 1/2 rho |v| v C_D(M, Kn) A/m`` with the same air table and
    coefficient: heights within 3 mm, speeds within 1e-3 m/s. The flight model holds
    ``C_D`` for each 20 ms step (RK4 otherwise): an error first order in the step
    while the Mach number changes, 1.5 mm at most here (0.4 mm after 120 s; half
    that at 10 ms)."""
    table = standard_table()
    states = _drop(10e3, 120)

    def rhs(_, s):
        z, w = s
        rho, _, _, sound, _, _ = (float(a[0]) for a in table.at(z - EARTH_RADIUS_POLAR))
        g = EARTH_MU / z ** 2 * (1.0 - 3.0 * EARTH_J2 * (EARTH_RADIUS_EQ / z) ** 2)
        return [w, -g - 0.5 * rho * abs(w) * w * tumbling_cd(abs(w) / sound, rho, LENGTH) * AREA / MASS]

    ref = solve_ivp(rhs, (0.0, 120.0), [EARTH_RADIUS_POLAR + 10e3, 0.0], method="DOP853",
                    rtol=1e-11, atol=1e-9, t_eval=np.arange(121.0))
    assert np.max(np.abs(states[:, 2] - ref.y[0])) < 3e-3
    assert np.max(np.abs(states[:, 5] - ref.y[1])) < 1e-3
    assert np.all(np.abs(states[:, :2]) < 1e-6)                 # straight down over the pole


def test_tumbling_drag_coefficient_limits():
    """Newtonian limit: a convex body tumbling at random has ``C_D = C_p,max / 2`` on its
    mean area at hypersonic speed, 0.92 for the modified-Newtonian ``C_p,max = 1.839``
    (Anderson 2006, section 3.2); free molecular 2.2 (Vallado 2013, 8.6.2) where the
    mean free path (USSA 1976: 6.6328e-8 m x 1.225 / rho) is over ten body lengths;
    the bridging is monotonic between them."""
    assert continuum_cd(8.0) == pytest.approx(1.839 / 2, abs=0.005)
    assert tumbling_cd(8.0, 1e-10, 10.0) == FREE_MOLECULAR_CD           # mean free path ~810 m
    assert tumbling_cd(0.3, 1.0, 10.0) == continuum_cd(0.3)
    rhos = np.geomspace(1e-10, 1e-4, 60)
    cds = [tumbling_cd(8.0, rho, 10.0) for rho in rhos]
    assert np.all(np.diff(cds) <= 0.0) and cds[-1] == pytest.approx(continuum_cd(8.0))


def test_a_payload_in_a_200_km_orbit_decays_at_the_analytic_rate():
    """A deployed payload (10 t, a solid cylinder 4 m x 6 m: mean area 25.1 m^2) in a
    circular equatorial 200 km orbit, point-mass gravity only (J2 off, so the
    height stays put): free molecular there (mean free path ~310 m over 6 m:
    ``C_D`` 2.2). Over one revolution its semi-major axis drops by
    ``2 pi rho B a^2 (v_air / v)^2`` (Gauss's equation for a tangential
    deceleration ``1/2 rho v_air^2 B``, ``B = C_D A/m``, integrated over a circular
    orbit; ``v_air = v - omega_E r`` for the prograde equatorial orbit in the turning
    air), with the USSA 1976 density at the mean height: within 0.1 % (338.179 m
    against 338.184 m). That density is the standard's as printed: at 200 km the
    table the flight reads gives the 2.541e-10 kg/m^3 of its Table I (NOAA-S/T
    76-1562) within 0.2 %."""
    table = standard_table()
    area = cylinder_area(2.0, 6.0)
    a0 = EARTH_RADIUS_EQ + 200e3
    v0 = math.sqrt(EARTH_MU / a0)
    p = make_params(1e4, (2e4, 3.5e4, 3.5e4), EARTH_MU, EARTH_RADIUS_EQ, 0.0, EARTH_RADIUS_POLAR)
    y = make_state([a0, 0.0, 0.0], [0.0, v0, 0.0])
    period = 2 * math.pi * math.sqrt(a0 ** 3 / EARTH_MU)
    h = 0.1
    n = round(period / h)
    y, taken = advance_free(y, 0, h, n, p, make_field("earth", 0.0, bodies=()), table.arrays(),
                            area / 1e4, 6.0)
    r, v = np.linalg.norm(y[:3]), np.linalg.norm(y[3:6])
    a1 = 1.0 / (2.0 / r - v * v / EARTH_MU)
    rho = float(table.at(0.5 * (a0 + a1) - EARTH_RADIUS_EQ)[0][0])
    spin = 7.292115e-5                  # rad/s, WGS84
    expected = 2 * math.pi * rho * FREE_MOLECULAR_CD * area / 1e4 * a0 ** 2 * (1 - spin * a0 / v0) ** 2
    assert taken == n and tumbling_cd(7.8, rho, 6.0) == FREE_MOLECULAR_CD
    assert float(table.at(200e3)[0][0]) == pytest.approx(2.541e-10, rel=2e-3)
    assert a0 - a1 == pytest.approx(expected * n * h / period, rel=1e-3)


def _first_step_drag(y, p, fp, air, t=0.0):
    """The drag acceleration (m/s^2, frame axes) of the drum's first step from ``y``: its
    velocity change less that of the same step without drag area, over the step."""
    with_drag, _ = advance_free(y, 0, H, 1, p, fp, air, AREA / MASS, LENGTH)
    without, _ = advance_free(y, 0, H, 1, p, fp, air, 0.0, LENGTH)
    return (with_drag[3:6] - without[3:6]) / H


def test_a_drum_at_rest_over_the_ground_is_pushed_along_the_wind():
    """A uniform 20 m/s east wind at every height (the standard day otherwise), the drum
    1 km over the equator at rest over the turning ground: the air moves past it at 20 m/s
    east, so it is pushed east by 1/2 rho C_D A |w|^2 / m (USSA 1976 density; C_D of the
    tumbling body at that Mach), averaged over the step as the drum picks up the wind's
    speed."""
    table = standard_table()
    h0, dh, density, pressure, temperature, sound, east, north = table.arrays()
    air = (h0, dh, density, pressure, temperature, sound, np.full_like(east, 20.0), north)
    p = make_params(MASS, (1.0, 2.0, 2.0), EARTH_MU, EARTH_RADIUS_EQ, EARTH_J2, EARTH_RADIUS_POLAR)
    fp = make_field("earth", 0.0, bodies=())
    r = np.array([EARTH_RADIUS_EQ + 1e3, 0.0, 0.0])
    y = make_state(r, np.cross((0.0, 0.0, 7.2921159e-5), r), [1.0, 0.0, 0.0, 0.0])
    drag = _first_step_drag(y, p, fp, air)
    at = us_standard_1976(np.array([1e3]))
    rho, a = float(at.density[0]), float(at.speed_of_sound[0])
    start = 0.5 * rho * 20.0 ** 2 * tumbling_cd(20.0 / a, rho, LENGTH) * AREA / MASS
    # over the step the drum picks up speed along the wind: the air passes it at w - a t,
    # and the drag (as (w - a t)^2) averages start (1 - a h / w) to first order
    expected = start * (1.0 - start * H / 20.0)
    assert drag[1] == pytest.approx(expected, rel=1e-4)                 # east, at x on the equator
    # up (x here): the air it starts to fall through pushes back, 1/2 (drag / w) g h = 0.024
    assert drag[0] == pytest.approx(0.5 * expected / 20.0 * 9.8 * H, rel=0.05)
    assert drag[2] == 0.0


def test_a_drum_about_mars_is_slowed_by_mars_air():
    """The drum 30 km over Mars's equator moving 300 m/s east over the turning ground:
    decelerated by 1/2 rho C_D A v^2 / m in Mars's air, the NASA Glenn model above 7 km
    typed here (T = -23.4 - 0.00222 h deg C, p = 0.699 exp(-0.00009 h) kPa,
    rho = p / (0.1921 (T + 273.1))), to 2e-3 (the table's interpolation and the step)."""
    from rocketsim.dynamics.soi import central_params
    from rocketsim.dynamics.central import air_about
    mars_eq, omega = 3396.19e3, math.radians(350.891982443297) / 86400.0      # IAU 2015
    p = central_params(make_params(MASS, (1.0, 2.0, 2.0), EARTH_MU, EARTH_RADIUS_EQ, EARTH_J2,
                                   EARTH_RADIUS_POLAR), "mars")
    fp = make_field("mars", 2461006.0, bodies=())
    r = np.array([mars_eq + 30e3, 0.0, 0.0])
    y = make_state(r, np.cross((0.0, 0.0, omega), r) + [0.0, 300.0, 0.0], [1.0, 0.0, 0.0, 0.0])
    air = air_about("mars", None)
    drag = _first_step_drag(y, p, fp, air.arrays())
    h = 30e3
    rho = 0.699 * math.exp(-0.00009 * h) / (0.1921 * (-23.4 - 0.00222 * h + 273.1))
    sound = float(air.at(np.array([h]))[3][0])
    expected = 0.5 * rho * 300.0 ** 2 * tumbling_cd(300.0 / sound, rho, LENGTH) * AREA / MASS
    assert -drag[1] == pytest.approx(expected, rel=2e-3)
