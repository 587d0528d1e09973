"""The engines' dynamic-pressure throttle law (``fc.limit_q``, docs/fc.md): the throttle
last commanded times ``(end - q) / (end - start)`` clipped to 0..1, commanded at the
start of every step in compiled code (rocketsim.vehicle.engines.hold_q_law, called by
rocketsim.dynamics.rk4.step).

The reference is the law's own formula: on the arrays for chosen pressures, and in
the shipped Falcon 9 ascent (which throttles back above 33 kPa, to zero at
49.5 kPa) against the telemetry's dynamic pressure and throttle. That the compiled
runs and the one-step loop fly the law alike, bit for bit, is tests/unit/stepping/test_runs.py's
mission comparison (its ascent flies through the law and waits on its stage's
propellant).
"""

import math

import numpy as np
import pytest

import rocketsim
from rocketsim.vehicle.engines import (C_ON, C_Q_START, C_TAU, command_throttle, hold_q_law, set_q_law,
                                       shutdown)
from tests.conftest import ROOT
from tests.unit.vehicle.test_vehicle_engines import lit_model


def test_the_law_scales_the_last_throttle_between_its_bounds_and_the_engine_clips_it():
    """The test engine's range is 0.5-1: base 0.9; at and below start (30 kPa) the base
    itself, a quarter of the way (35 kPa) 0.9 * 0.75, past the point where the product
    falls under 0.5 the bottom of the range; removing the law commands the base again."""
    m, y = lit_model()
    a = m.arrays
    command_throttle(a.eng, a.cmd, 0, 0.0, 0.9)
    set_q_law(a.eng, a.cmd, [0], 0.0, 30e3, 50e3)
    for t, q, tau in [(1.0, 20e3, 0.9), (2.0, 30e3, 0.9), (3.0, 35e3, 0.9 * 0.75), (4.0, 45e3, 0.5),
                      (5.0, 80e3, 0.5), (6.0, 25e3, 0.9)]:
        hold_q_law(a.eng, a.cmd, t, q)
        assert a.cmd[0, C_TAU] == pytest.approx(tau, rel=1e-15), q
    hold_q_law(a.eng, a.cmd, 7.0, 40e3)
    set_q_law(a.eng, a.cmd, [0], 8.0, math.nan, math.nan)
    assert math.isnan(a.cmd[0, C_Q_START]) and a.cmd[0, C_TAU] == 0.9


def test_an_engine_that_is_off_keeps_its_command():
    m, y = lit_model()
    a = m.arrays
    set_q_law(a.eng, a.cmd, [0], 0.0, 30e3, 50e3)
    assert shutdown(y, a.eng, a.cmd, 0, a.first_clock) and a.cmd[0, C_ON] == 0.0
    before = a.cmd.copy()
    hold_q_law(a.eng, a.cmd, 1.0, 45e3)
    np.testing.assert_array_equal(a.cmd, before)


def test_the_falcon9_ascent_throttles_back_through_max_q_by_the_law():
    """The shipped ascent's first 100 s (a 0.05 s step: the suite's budget): where the
    dynamic pressure passes 33 kPa the flown throttle is the law's ``1 - 2 (q - 33 kPa)
    / 33 kPa`` (clipped to the Merlins' 0.4-1) to within 0.005 (the law reads q at the
    step's start and the radial height, the telemetry at the sample and the geodetic
    height), and it does throttle back (below 0.95 at max-Q)."""
    run = rocketsim.fly(ROOT / "scenarios" / "falcon9-leo.yaml", duration=100.0, step=0.05)
    table = run.bodies["falcon9-block5"].table()
    climb = table[(table.index > 20.0) & (table.index < 100.0)]
    q, flown = climb["dynamic_pressure_Pa"], climb["throttle"]
    law = np.clip(1.0 - 2.0 * (q - 33e3) / 33e3, 0.4, 1.0)
    assert (flown - law).abs().max() < 0.005
    assert flown.min() < 0.95 and q.max() > 33.5e3


@pytest.mark.parametrize("args, message", [
    ((33e3,), "needs an end"),
    ((40e3, 30e3), "end must be above start"),
    ((-1.0, 30e3), "start must be within 0"),
    ((1.0, math.inf), "end must be a finite number"),
    ((None, 30e3), "takes no end"),
])
def test_fc_limit_q_refuses_a_law_it_cannot_fly(args, message):
    from rocketsim.flight.fc import FlightComputer

    fc = FlightComputer.__new__(FlightComputer)
    with pytest.raises(ValueError, match=message):
        fc.limit_q(*args)
