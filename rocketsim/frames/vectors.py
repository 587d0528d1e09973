"""Three-vectors from Python: numpy's products without numpy's handling of shapes.

``np.cross`` of two 3-vectors moves and broadcasts axes before it multiplies, which
costs far more than the six products do; guidance re-solved every cycle from Python
calls it thousands of times a flight. :func:`cross` takes the same products in the
same order (``a1 b2 - a2 b1``, ``a2 b0 - a0 b2``, ``a0 b1 - a1 b0``), so its result is
``np.cross``'s bit for bit.
"""

from __future__ import annotations

import numpy as np


def cross(a, b) -> np.ndarray:
    """``a x b`` of two 3-vectors (any sequences of three numbers), a float array."""
    (ax, ay, az), (bx, by, bz) = np.asarray(a, dtype=float).tolist(), np.asarray(b, dtype=float).tolist()
    return np.array((ay * bz - az * by, az * bx - ax * bz, ax * by - ay * bx))
