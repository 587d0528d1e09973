"""The cross products of rocketsim.frames.vectors against numpy's.

``cross`` (for Python callers) and ``compiled_cross`` (for kernels) must be
``np.cross`` bit for bit (the guidance, the steering and the rails that call them are
checked for identical flights), on vectors spanning many decades and of either sign;
``cross`` takes any sequence of three numbers.
"""

import numpy as np

from rocketsim.frames.vectors import compiled_cross, cross


def test_the_cross_product_is_numpys_bit_for_bit():
    rng = np.random.default_rng(7)
    for _ in range(2000):
        a = rng.normal(size=3) * 10.0 ** rng.uniform(-6, 8, size=3)
        b = rng.normal(size=3) * 10.0 ** rng.uniform(-6, 8, size=3)
        assert cross(a, b).tobytes() == np.cross(a, b).tobytes()
        assert compiled_cross(a, b).tobytes() == np.cross(a, b).tobytes()


def test_the_axes_follow_the_right_hand_rule_from_any_sequence():
    assert cross((1, 0, 0), [0.0, 1.0, 0.0]).tolist() == [0.0, 0.0, 1.0]
    assert cross(np.array((0.0, 0.0, 2.0)), (1.0, 0.0, 0.0)).tolist() == [0.0, 2.0, 0.0]
