"""The guidance-rate helper: a program paced by ``Approach`` acts in the step its limit is crossed.

References are analytic: a reading moving at a constant rate, and one accelerating
towards its limit (a falling body's height, ``h(t) = h0 - g t^2 / 2``), sampled
only where ``next_update`` lets the program wake (multiples of the 20 ms step).
The first wake-up at or past the limit must be the first 20 ms step past the
exact crossing time, the wake-ups far from the limit the longest period, and the
per-step wake-ups only those within two of the shortest period of the crossing.
"""

from __future__ import annotations

import math

import pytest

from rocketsim.guidance.rate import Approach

STEP = 0.02     # s, the flight's step


def _paced(reading, approach: Approach, until: float) -> tuple[float, list[float]]:
    """Wake where ``approach`` says, reading ``reading(t)``, from t = 0; returns the
    time of the first wake-up at which the limit is no longer ahead, and the sleeps."""
    k, sleeps = 0, []
    while k * STEP < until:
        t = k * STEP
        if not approach.ahead(reading(t), t):
            return t, sleeps
        wait = approach.next_update()
        sleeps.append(wait)
        k += max(1, math.ceil(wait / STEP - 1e-9))
    raise AssertionError("the limit was never reached")


@pytest.mark.parametrize("rate", [3.0, 250.0, 7000.0])
def test_a_steady_reading_is_caught_in_the_step_it_crosses(rate):
    limit = 10_000.0
    crossing = limit / rate                         # exact, s
    woke, sleeps = _paced(lambda t: rate * t, Approach(limit, rising=True, periods=(1.0, 0.1)), 2 * crossing)
    assert woke == pytest.approx(math.ceil(crossing / STEP - 1e-9) * STEP, abs=1e-9)
    if crossing > 3.0:                              # far from the limit it sleeps the longest period
        assert sleeps[1] == 1.0
    assert sleeps.count(0.0) <= 2 * 0.1 / STEP + 2   # every step only within two shortest periods


def test_a_falling_height_accelerating_to_its_limit_is_caught():
    g, h0, floor = 9.80665, 8_000.0, 1_000.0        # h = h0 - g t^2 / 2 reaches the floor at
    crossing = math.sqrt(2.0 * (h0 - floor) / g)    # 37.78 s, faster every second
    woke, sleeps = _paced(lambda t: h0 - 0.5 * g * t * t, Approach(floor, periods=(0.5, 0.1)), 60.0)
    assert woke == pytest.approx(math.ceil(crossing / STEP - 1e-9) * STEP, abs=1e-9)
    assert sleeps.count(0.5) > 40 and sleeps[-1] == 0.0


def test_past_the_limit_the_next_update_is_the_next_step():
    approach = Approach(5.0)
    assert not approach.ahead(4.0, 0.0)
    assert approach.next_update() == 0.0
