"""Three-vectors: numpy's products without numpy's handling of shapes.

``np.cross`` of two 3-vectors moves and broadcasts axes before it multiplies, which
costs far more than the six products do; guidance re-solved every cycle from Python
calls it thousands of times a flight. :func:`cross` (from Python) and
:func:`compiled_cross` (in compiled code) take the same products in the same order
(``a1 b2 - a2 b1``, ``a2 b0 - a0 b2``, ``a0 b1 - a1 b0``), so their results are
``np.cross``'s bit for bit.
"""

from __future__ import annotations

import numpy as np

from rocketsim.jit import njit


def cross(a, b) -> np.ndarray:
    """``a x b`` of two 3-vectors (any sequences of three numbers), a float array."""
    (ax, ay, az), (bx, by, bz) = np.asarray(a, dtype=float).tolist(), np.asarray(b, dtype=float).tolist()
    return np.array((ay * bz - az * by, az * bx - ax * bz, ax * by - ay * bx))


@njit
def compiled_cross(a, b):
    """``a x b`` of two 3-vectors (float arrays) in compiled code, a new array."""
    out = np.empty(3)
    out[0] = a[1] * b[2] - a[2] * b[1]
    out[1] = a[2] * b[0] - a[0] * b[2]
    out[2] = a[0] * b[1] - a[1] * b[0]
    return out
