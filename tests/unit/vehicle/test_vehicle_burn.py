"""Powered flight through the RK4 stages (docs/physics.md#integrator): the rocket
equation, fourth-order convergence against the Dormand-Prince reference, and a tank
running dry inside a step."""

import math

import numpy as np
import pytest

from rocketsim.constants import (EARTH_J2, EARTH_MU, EARTH_RADIUS_EQ, EARTH_RADIUS_POLAR, G0,
                                 UNUSABLE_PROPELLANT)
from rocketsim.dynamics.reference import integrate_reference
from rocketsim.dynamics.rk4 import advance
from rocketsim.layout import V, make_params
from rocketsim.vehicle.engines import C_G, C_G0, S_DRY, S_DRY_AT, ignite
from rocketsim.vehicle.build import build
from tests.vehicle_specs import single_stage, spec

ISP, THRUST, LOAD = 300.0, 100e3, 6000.0
MDOT = THRUST / (G0 * ISP)
HIGH = EARTH_RADIUS_EQ + 1_000e3          # above the 600 km top of the air: vacuum


def no_gravity():
    return make_params(1.0, (1.0, 1.0, 1.0), 0.0, EARTH_RADIUS_EQ, 0.0, EARTH_RADIUS_POLAR)


def earth():
    return make_params(1.0, (1.0, 1.0, 1.0), EARTH_MU, EARTH_RADIUS_EQ, EARTH_J2, EARTH_RADIUS_POLAR)


def lit(model, y, spooled=False):
    a = model.arrays
    for e in range(model.n_engines):
        assert ignite(y, a.eng, a.cmd, a.stage, e, a.first_clock)
        if spooled:
            y[a.first_clock + e] = 10.0            # long past the dead time and the spool-up
    return y


@pytest.mark.parametrize("h", [0.02, 0.1])
def test_vertical_burn_in_vacuum_matches_the_rocket_equation(h):
    """Tsiolkovsky: dv = Isp g0 ln(m0 / m1) with m1 = m0 - 99 % of the load (within
    0.007 %, the seed description's audit figure). It holds through the spool-up (thrust
    and flow scale together)."""
    m = build(spec(single_stage()))
    y = lit(m, m.state([HIGH, 0.0, 0.0], [0.0, 0.0, 0.0]))
    m0 = m.mass_properties(y)[0]
    y1, _ = advance(y, 0, h, int(200 / h), no_gravity(), m.arrays)
    m1 = m0 - (1 - UNUSABLE_PROPELLANT) * LOAD
    expected = ISP * G0 * math.log(m0 / m1)
    dv = np.linalg.norm(y1[V:V + 3])
    assert m.arrays.stage[0, S_DRY] == 1.0
    assert abs(dv - expected) / expected < 7e-5
    assert abs(dv - expected) / expected < 1e-10          # what it actually does


def test_tank_running_dry_inside_a_step_stops_the_thrust_at_that_instant():
    """Burned mass = usable propellant to 1e-9; the cut-off time is the analytic one:
    dead time + half the spool-up (linear ramp) + usable / mdot; nothing pushes after."""
    m = build(spec(single_stage()))
    y = lit(m, m.state([HIGH, 0.0, 0.0], [0.0, 0.0, 0.0]))
    usable = (1 - UNUSABLE_PROPELLANT) * LOAD
    t_dry = 0.3 + 0.5 * 1.0 + usable / MDOT
    h = 0.1
    k = int(t_dry / h)
    assert 0.05 < t_dry / h - k < 0.95                     # the cut-off falls inside a step
    y1, _ = advance(y, 0, h, k + 1, no_gravity(), m.arrays)
    burned = LOAD - y1[m.tanks].sum()
    assert abs(burned - usable) / usable < 1e-9
    assert abs(m.arrays.stage[0, S_DRY_AT] - t_dry) / t_dry < 1e-9
    y2, _ = advance(y1, k + 1, h, 10, no_gravity(), m.arrays)
    assert np.array_equal(y2[V:V + 3], y1[V:V + 3])       # dry: no thrust, no flow
    assert np.array_equal(y2[m.tanks], y1[m.tanks])


def test_two_tanks_drain_in_proportion_and_run_dry_together():
    data = single_stage()
    tank = data["stages"][0]["tanks"][0]
    data["stages"][0]["tanks"] = [dict(tank, name="ox", length="3 m", position="1 m",
                                       propellant_mass="2400 kg"),
                                  dict(tank, name="fuel", length="3 m", position="4.5 m",
                                       propellant_mass="1200 kg")]
    m = build(spec(data))
    y = lit(m, m.state([HIGH, 0.0, 0.0], [0.0, 0.0, 0.0]))
    y1, _ = advance(y, 0, 0.1, 1200, no_gravity(), m.arrays)
    left = y1[m.tanks]
    assert left == pytest.approx([24.0, 12.0], rel=1e-9)   # 1 % of each: the mixture ratio held


def powered_segment(h, model, y0, duration):
    y, _ = advance(y0.copy(), 0, h, round(duration / h), earth(), model.arrays)
    return y


def test_powered_segment_converges_at_fourth_order_against_dop853():
    """A turning burn at 300 km (gimbal 0.2 deg: torque, rotation, J2 gravity, mass falling
    and inertia changing) for 10 s, against DOP853 at rtol 1e-13 on the same derivative:
    the position error falls about 16-fold per halving of the step (fourth order; the
    seed description's audit: 'the position error of a powered segment fell from 0.91 m').

    Steps 0.2, 0.1 and 0.05 s: their errors (~2e-5 to ~7e-8 m) stand well above the
    rounding floor of a position of 6.7e6 m (one ulp is 9.3e-10 m). At 0.025 s the error is
    ~2e-9 m, two ulps, where rounding, not the method, sets it: the order measured there
    swung from 4 to 5 with a change of the last bits of the derivative."""
    m = build(spec(single_stage()))
    a = m.arrays
    r0 = EARTH_RADIUS_EQ + 300e3
    y0 = lit(m, m.state([r0, 0.0, 0.0], [0.0, 7500.0, 0.0], w=(0.01, 0.0, 0.0)), spooled=True)
    g = math.radians(0.2)
    a.cmd[0, C_G0], a.cmd[0, C_G] = g, g               # held deflection: no slew kink
    ref = integrate_reference(y0, 0.0, 10.0, earth(), rtol=1e-13, atol=1e-9, veh=a)
    errors = []
    for h in (0.2, 0.1, 0.05):
        y = powered_segment(h, m, y0, 10.0)
        errors.append(np.linalg.norm(y[:3] - ref[:3]))
    turned = np.degrees(2 * math.acos(min(1.0, abs(ref[6]))))
    assert turned > 10.0                                   # it did turn
    assert errors[1] < 1e-3
    orders = [math.log2(errors[i] / errors[i + 1]) for i in range(2)]
    assert all(3.6 < order < 4.4 for order in orders), (errors, orders)


def test_burn_through_spool_up_still_converges_at_fourth_order():
    """From the ignition command, tumbling at 0.5 rad/s: the steps are split at the end of
    the dead time and of the spool-up, so those kinks do not spoil the order. Reference:
    the same integrator at a 64 times smaller step (Richardson's convergence test; the
    position is about 1e-8 m from rounding at that step, so only two steps are compared)."""
    m = build(spec(single_stage()))
    r0 = EARTH_RADIUS_EQ + 300e3
    y0 = lit(m, m.state([r0, 0.0, 0.0], [0.0, 7500.0, 0.0], w=(0.0, 0.5, 0.0)))
    fine = powered_segment(0.1 / 64, m, y0, 4.0)
    errors = [np.linalg.norm(powered_segment(h, m, y0, 4.0)[:3] - fine[:3]) for h in (0.1, 0.05)]
    assert 11.0 < errors[0] / errors[1] < 20.0, errors
