"""The compiled conditions of fc.wait_until (rocketsim.flight.conditions) against the readings.

A compiled run (rocketsim.stepping.runs) tests a program's condition at every
step: each kind of condition is checked against the reading it stands for (the
flight computer's, in Python), on states drawn at random about Earth, at the
threshold itself, one ulp either side and far away: the same boolean.
"""

import math
from pathlib import Path

import numpy as np
import pytest

from rocketsim.constants import EARTH_J2, EARTH_MU, EARTH_RADIUS_EQ, EARTH_RADIUS_POLAR
from rocketsim.flight.conditions import ABOVE, BELOW, holds
from rocketsim.flight.readings import StateView
from rocketsim.layout import make_params
from rocketsim.scenario.load import load

MISSION = Path(__file__).resolve().parents[3] / "scenarios" / "falcon9-leo.yaml"


def _earth_states(count, seed=7):
    """States about Earth: from below the ground to 700 km, climbing and falling."""
    rng = np.random.default_rng(seed)
    for _ in range(count):
        direction = rng.normal(size=3)
        r = direction / np.linalg.norm(direction) * (EARTH_RADIUS_EQ + rng.uniform(-30e3, 700e3))
        v = rng.normal(size=3) * rng.choice((10.0, 300.0, 3000.0))
        q = rng.normal(size=4)
        y = np.concatenate((r, v, q / np.linalg.norm(q), np.zeros(3)))
        yield rng.uniform(0.0, 5000.0), y


def test_a_compiled_condition_reads_what_the_readings_read():
    # the same boolean from the same numbers: thresholds at the readings themselves
    # (ties), a hair either side, and far away
    p = make_params(1.0, (1.0, 1.0, 1.0), EARTH_MU, EARTH_RADIUS_EQ, EARTH_J2, EARTH_RADIUS_POLAR)
    checked = 0
    for t, y in _earth_states(400):
        view = StateView.of_state(t, y, None, EARTH_MU, p)
        readings = (view.geodetic[2], view.vertical_speed)
        for index, value in enumerate(readings):
            for threshold in (value, np.nextafter(value, math.inf), np.nextafter(value, -math.inf), value + 1e3):
                for op, truth in ((BELOW, value < threshold), (ABOVE, value > threshold)):
                    code = np.array(((op, float(index), threshold),))
                    assert holds(code, t, y, p) == truth
                    checked += 1
        # combinations, postfix: (altitude below) and (climb below), or both ways
        a, c = readings
        code = np.array(((BELOW, 0.0, a + 1.0), (BELOW, 1.0, c), (3.0, 0.0, 0.0)))
        assert holds(code, t, y, p) == (a < a + 1.0 and c < c)
        code = np.array(((BELOW, 0.0, a - 1.0), (ABOVE, 1.0, c - 1.0), (4.0, 0.0, 0.0)))
        assert holds(code, t, y, p) == (a < a - 1.0 or c > c - 1.0)
    assert checked == 400 * 2 * 4 * 2


def test_a_compiled_propellant_condition_reads_the_stage_s_tanks_as_python_sums_them():
    """The Falcon 9's second stage (its tanks after the booster's): its condition reads the
    sum of its own tanks' slots in the order of ``fc.propellant``, to the bit, at the sum
    itself (ties) and a hair either side, over random loads."""
    from rocketsim.flight import conditions
    from rocketsim.vehicle.build import build

    vehicle = build(load(MISSION).scenario.vehicle)
    rng = np.random.default_rng(11)
    p = make_params(1.0, (1.0, 1.0, 1.0), EARTH_MU, EARTH_RADIUS_EQ, EARTH_J2, EARTH_RADIUS_POLAR)
    fc = _Readings()
    for t, body in _earth_states(50):
        y = vehicle.state(body[:3], body[3:6])
        y[vehicle.tanks] = rng.uniform(0.0, 1e5, vehicle.n_tanks) * rng.choice((1e-3, 1.0), vehicle.n_tanks)
        fc.propellant = dict(zip(vehicle.tank_names, y[vehicle.tanks].tolist()))
        total = sum(fc.propellant[name] for name in vehicle.tank_names if name.startswith("second stage/"))
        for threshold in (total, np.nextafter(total, math.inf), np.nextafter(total, -math.inf)):
            for op in (BELOW, ABOVE):
                condition = conditions.compare_propellant(fc, vehicle, 1, threshold, op)
                assert holds(condition.code, t, y, p) == condition() == (
                    total < threshold if op == BELOW else total > threshold)
    mine = [i for i, name in enumerate(vehicle.tank_names) if name.startswith("second stage/")]
    assert mine[0] > 0 and condition.code[0, 3:5].tolist() == [vehicle.tanks.start + mine[0], len(mine)]


def test_compiled_time_and_nose_conditions_read_as_python_reads_them():
    """The mission time and the nose's angle to a direction (compared by its cosine:
    conditions.nose_dot) at random states and directions, at the thresholds themselves
    and one ulp either side: the compiled test and the Python one agree; 1e-4 rad away
    from the angle (the nose from the attitude matrix, quat_to_matrix's first column)
    the test is the angle's."""
    from rocketsim.flight import conditions
    from rocketsim.frames.quaternion import quat_to_matrix
    from rocketsim.layout import Q

    p = make_params(1.0, (1.0, 1.0, 1.0), EARTH_MU, EARTH_RADIUS_EQ, EARTH_J2, EARTH_RADIUS_POLAR)
    rng = np.random.default_rng(5)
    fc = _Readings()
    checked = 0
    for t, y in _earth_states(200):
        fc.attitude, fc.time = y[Q:Q + 4].copy(), t
        towards = rng.normal(size=3)
        towards /= np.linalg.norm(towards)
        angle = math.acos(max(-1.0, min(1.0, float(quat_to_matrix(y[Q:Q + 4])[:, 0] @ towards))))
        for op in (BELOW, ABOVE):
            for a in (angle, np.nextafter(angle, 0.0), np.nextafter(angle, 4.0)):
                condition = conditions.compare_nose(fc, towards, a, op)
                assert holds(condition.code, t, y, p) == condition()
                checked += 1
            for value in (t, np.nextafter(t, 0.0), np.nextafter(t, 1e9)):
                condition = conditions.compare(fc, "time", value, op)
                assert holds(condition.code, t, y, p) == condition() == (t < value if op == BELOW else t > value)
        if 1e-3 < angle < math.pi - 1e-3:
            for a in (angle - 1e-4, angle + 1e-4):
                assert conditions.compare_nose(fc, towards, a, BELOW)() == (angle < a)
    assert checked == 200 * 2 * 3


class _Readings:
    """What fc.below/above read, as the flight computer's readings (a stand-in)."""

    altitude, vertical_speed = 1000.0, -50.0


def test_conditions_are_called_as_the_lambdas_they_stand_for():
    from rocketsim.flight import conditions

    fc = _Readings()
    low = conditions.compare(fc, "altitude", 2000.0, BELOW)
    falling = conditions.compare(fc, "vertical_speed", -60.0, BELOW)
    assert low() is True and falling() is False
    assert (low & falling)() is False and (low | falling)() is True
    assert (low & falling).code.shape == (3, 6) and (low & falling).code[2, 0] == conditions.AND
    fc.vertical_speed = -70.0
    assert (low & falling)() is True
    with pytest.raises(TypeError, match="combines"):
        low & (lambda: True)


def test_fc_below_refuses_a_reading_it_cannot_test():
    from rocketsim.flight.fc import FlightComputer

    fc = FlightComputer.__new__(FlightComputer)
    with pytest.raises(ValueError, match=r"fc.below\(\): reading must be one of altitude, vertical_speed, propellant, time, nose_angle"):
        fc.below("speed", 10.0)
    with pytest.raises(ValueError, match=r"fc.above\(\): value must be a finite number"):
        fc.above("altitude", math.nan)
    with pytest.raises(ValueError, match=r"fc.below\(\): stage goes with the reading propellant only"):
        fc.below("altitude", 10.0, stage="booster")
