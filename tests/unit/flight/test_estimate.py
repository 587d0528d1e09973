"""The navigation estimate in compiled code (rocketsim.flight.navigation.estimate) against the
sensors read axis by axis in Python.

A compiled run steers on the estimate and tests a program's condition on it
(rocketsim.stepping.runs); the flight computer reads it in Python. The reference
here is the estimate made from the error streams one quantity at a time
(:meth:`rocketsim.flight.sensors.Sensors.vector` and ``scalar``: each axis its
``truth + bias + white + floor``, a gauge's ``truth (1 + bias + white) + floor``),
the attitude turned by the measured tilt with numpy's norm and the quaternion
kernels: the same numbers to the bit, at random states and at steps either side
of the streams' block boundaries (the runs' errors span two blocks). The
compiled conditions then read on it what the readings read, at the thresholds
themselves and one ulp either side.
"""

import math
from pathlib import Path

import numpy as np

from rocketsim.constants import EARTH_J2, EARTH_MU, EARTH_RADIUS_EQ, EARTH_RADIUS_POLAR
from rocketsim.flight import conditions
from rocketsim.flight.conditions import ABOVE, BELOW, holds_on
from rocketsim.flight.navigation import estimate
from rocketsim.flight.readings import StateView
from rocketsim.flight.sensors import BLOCK, E_GAUGES, Sensors, gauged
from rocketsim.frames.quaternion import quat_from_axis_angle, quat_multiply
from rocketsim.layout import make_params
from rocketsim.scenario.load import load
from rocketsim.vehicle.build import build

MISSION = Path(__file__).resolve().parents[3] / "scenarios" / "falcon9-leo.yaml"
DT = 0.02
# steps of the streams' first blocks and either side of their boundaries
STEPS = (0, 1, 700, BLOCK - 2, BLOCK - 1, BLOCK, BLOCK + 1, 2 * BLOCK - 1, 2 * BLOCK, 3 * BLOCK + 5)


def _axis_by_axis(sensors, y, k):
    """The estimate as the flight computer made it one stream at a time."""
    tilt = sensors.vector("attitude", (0.0, 0.0, 0.0), k)
    angle = float(np.linalg.norm(tilt))
    q = y[6:10].copy() if angle == 0.0 else quat_multiply(y[6:10], quat_from_axis_angle(tilt / angle, angle))
    return (sensors.vector("position", y[0:3], k), sensors.vector("velocity", y[3:6], k), q,
            sensors.vector("rates", y[10:13], k))


def _states(vehicle, count, seed):
    rng = np.random.default_rng(seed)
    for _ in range(count):
        direction = rng.normal(size=3)
        r = direction / np.linalg.norm(direction) * (EARTH_RADIUS_EQ + rng.uniform(-1e3, 300e3))
        q = rng.normal(size=4)
        y = vehicle.state(r, rng.normal(size=3) * rng.choice((10.0, 3000.0)), q / np.linalg.norm(q),
                          rng.normal(size=3) * 0.1)
        y[vehicle.tanks] = rng.uniform(0.0, 2e5, vehicle.n_tanks)
        yield y


def test_the_compiled_estimate_is_the_sensors_read_axis_by_axis():
    vehicle = build(load(MISSION).scenario.vehicle)
    tanks = tuple(vehicle.tank_names)
    for level in ("realistic", "hard"):
        compiled = Sensors(4, "booster", level, DT)
        reference = Sensors(4, "booster", level, DT)
        checked = 0
        for k, y in zip(STEPS, _states(vehicle, len(STEPS), 3)):
            errors, first = compiled.run_errors(k, tanks)
            assert first <= k < first + 2 * BLOCK and errors.shape == (2 * BLOCK, E_GAUGES + len(tanks), 3)
            for got, want in zip(estimate(y, errors, k - first), _axis_by_axis(reference, y, k)):
                assert np.array_equal(got, want)
                checked += 1
            for c, name in enumerate(tanks):
                mass = float(y[vehicle.tanks.start + c])
                assert gauged(mass, errors, k - first, E_GAUGES + c) == reference.scalar(f"propellant/{name}", mass, k)
        assert checked == 4 * len(STEPS)
    # the errors are the sensors': the estimate is off the truth, by metres (hard: 3 sigma of 2 m)
    r = estimate(y, errors, k - first)[0]
    assert 0.1 < np.abs(r - y[0:3]).max() < 50.0


def test_a_truth_flight_s_errors_are_none():
    errors, _ = Sensors(4, "booster", "truth", DT).run_errors(10, ())
    assert errors.shape[0] == 0


def test_compiled_conditions_read_the_estimate_as_the_readings_read_it():
    """Height, climb, the nose's angle and a stage's propellant through its gauges, read
    on the estimate: the compiled test and the comparison of the Python readings (the
    view of the estimate made axis by axis, the gauges summed in ``fc.propellant``'s
    order) agree at the readings themselves and one ulp either side."""
    vehicle = build(load(MISSION).scenario.vehicle)
    tanks = tuple(vehicle.tank_names)
    p = make_params(1.0, (1.0, 1.0, 1.0), EARTH_MU, EARTH_RADIUS_EQ, EARTH_J2, EARTH_RADIUS_POLAR)
    compiled, reference = Sensors(9, "stack", "realistic", DT), Sensors(9, "stack", "realistic", DT)
    stage = [name for name in tanks if name.startswith("second stage/")]
    first_slot = vehicle.tanks.start + tanks.index(stage[0])
    towards = np.array([0.6, 0.0, 0.8])
    checked = 0
    for k, y in zip(STEPS, _states(vehicle, len(STEPS), 8)):
        t = k * DT
        errors, first = compiled.run_errors(k, tanks)
        j = k - first
        r, v, q, _ = _axis_by_axis(reference, y, k)
        view = StateView(t, r, v, q, np.zeros(3), None, EARTH_MU, p)
        gauges = [reference.scalar(f"propellant/{name}", float(m), k)
                  for name, m in zip(tanks, y[vehicle.tanks])]
        readings = {0.0: view.geodetic[2], 1.0: view.vertical_speed,
                    2.0: sum(m for name, m in zip(tanks, gauges) if name in stage),
                    4.0: -conditions.nose_dot(q, *towards)}
        for reading, value in readings.items():
            for threshold in (value, np.nextafter(value, math.inf), np.nextafter(value, -math.inf)):
                for op, truth in ((BELOW, value < threshold), (ABOVE, value > threshold)):
                    row = (op, reading, threshold, *((first_slot, len(stage), 0.0) if reading == 2.0
                                                     else tuple(towards) if reading == 4.0 else (0.0, 0.0, 0.0)))
                    assert holds_on(np.array((row,)), t, y, p, errors, j, vehicle.tanks.start) == truth
                    checked += 1
    assert checked == len(STEPS) * 4 * 3 * 2
