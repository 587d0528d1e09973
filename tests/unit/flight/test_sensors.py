"""Sensor errors against their own specification (docs/physics.md#sensors).

The reference is the first-order Gauss-Markov process itself: a stationary
process of standard deviation sigma_b whose autocorrelation at lag L is
exp(-L/tau) (e.g. Brown & Hwang, *Introduction to Random Signals and Applied
Kalman Filtering*, 4th ed., sec. 2.9). Over a hold of 2 000 correlation
times the estimates of sigma and tau have a relative standard error of about
2-3 %, so a 10 % tolerance is a 4-sigma bound: it fails a wrong
sigma or tau, not the sampling.
"""

import math

import numpy as np
import pytest

from rocketsim.flight.sensors import ERRORS, LEVELS, ErrorStream, Sensors

DT = 0.02


def hold(name, seed=11, level="realistic", tau_multiple=2000):
    spec = ERRORS[name]
    stream = ErrorStream(seed, name, spec, DT, LEVELS[level])
    n = int(tau_multiple * spec.tau / DT)
    return spec, stream.series(n)


@pytest.mark.parametrize("name", ["position.x", "position.z", "velocity.y", "attitude.x",
                                  "dynamic_pressure", "angle_of_attack", "propellant"])
def test_bias_sigma_correlation_time_and_white_noise_match_the_table(name):
    spec, rows = hold(name)
    bias, white = rows[0], rows[1]
    assert bias.std() == pytest.approx(spec.bias, rel=0.10)
    assert white.std() == pytest.approx(spec.white, rel=0.10)
    lag = int(round(spec.tau / DT))
    rho = np.corrcoef(bias[:-lag], bias[lag:])[0, 1]          # should be exp(-1)
    assert -spec.tau / math.log(rho) == pytest.approx(spec.tau, rel=0.10)
    # white noise is white: no correlation from one step to the next
    assert abs(np.corrcoef(white[:-1], white[1:])[0, 1]) < 0.01


def test_hard_triples_every_error_and_truth_has_none():
    _, realistic = hold("velocity.x", tau_multiple=10)
    _, hard = hold("velocity.x", level="hard", tau_multiple=10)
    _, truth = hold("velocity.x", level="truth", tau_multiple=10)
    assert np.allclose(hard, 3 * realistic, rtol=1e-12, atol=1e-14)
    assert not truth.any()


def test_radar_altitude_is_two_tenths_of_a_percent_plus_five_centimetres():
    stream = ErrorStream(3, "radar_altitude", ERRORS["radar_altitude"], DT, 1.0)
    readings = np.array([stream.measure(1000.0) for _ in range(20000)])
    assert (readings - 1000.0).std() == pytest.approx(math.hypot(0.002 * 1000.0, 0.05), rel=0.05)


def test_streams_are_seeded_and_independent_of_each_other():
    a = Sensors(5, "booster", "realistic", DT)
    b = Sensors(5, "booster", "realistic", DT)
    c = Sensors(6, "booster", "realistic", DT)
    first = [a.scalar("mach", 2.0) for _ in range(10)]
    assert first == [b.scalar("mach", 2.0) for _ in range(10)]
    assert first != [c.scalar("mach", 2.0) for _ in range(10)]
    # reading another sensor in between does not change this one's numbers
    d = Sensors(5, "booster", "realistic", DT)
    interleaved = []
    for _ in range(10):
        d.vector("position", (1.0, 2.0, 3.0))
        interleaved.append(d.scalar("mach", 2.0))
    assert interleaved == first
    # nor does the body's name of another body
    assert Sensors(5, "stage2", "realistic", DT).scalar("mach", 2.0) != first[0]
