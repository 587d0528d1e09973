"""Sine and cosine together, inlined, for the series' inner loops.

The ephemeris kernels evaluate a few hundred sines and cosines per instant;
the C library's ``sin`` and ``cos`` are opaque calls that cost ~20 ns each
and stop the compiler from vectorising the loop. :func:`sincos` is plain
arithmetic the compiler can inline and vectorise:

1. reduction: ``k = round(x / (pi/2))``, ``r = x - k pi/2`` with pi/2 split
   in three parts (Cody & Waite 1980): the first two have 33 significant
   bits, so ``k * part`` is exact for ``|k| < 2**20`` (``|x|`` up to 1.6e6),
   and ``|r| <= pi/4``;
2. the Taylor series of ``sin r`` to ``r^15`` and of ``cos r`` to ``r^16``:
   on ``|r| <= pi/4`` the first omitted terms are below 5e-17 and 3e-18;
3. the quadrant ``k mod 4`` swaps and negates the pair.

Agreement with the C library is within a few units in the last place for
``|x| < 1e5`` (checked in ``tests/test_ephemeris_sincos.py``).
"""

from __future__ import annotations

import math

from rocketsim._jit import njit

TWO_OVER_PI = 2.0 / math.pi
# pi/2 = PIO2_1 + PIO2_2 + PIO2_3 (PIO2_1, PIO2_2: 31 and 32 significant bits)
PIO2_1 = 1.5707963267341256
PIO2_2 = 6.077100506303966e-11
PIO2_3 = 2.0222662487959506e-21   # pi/2 - PIO2_1 - PIO2_2, rounded

# Taylor coefficients (-1)^n / (2n+1)! and (-1)^n / (2n)!, n = 1..7 / 1..8
_S = tuple((-1.0) ** n / math.factorial(2 * n + 1) for n in range(1, 8))
_C = tuple((-1.0) ** n / math.factorial(2 * n) for n in range(1, 9))
S1, S2, S3, S4, S5, S6, S7 = _S
C1, C2, C3, C4, C5, C6, C7, C8 = _C


@njit(inline="always")
def sincos(x):
    """``(sin x, cos x)`` for a float ``x`` in radians, ``|x| < 1.6e6``."""
    k = math.floor(x * TWO_OVER_PI + 0.5)
    r = ((x - k * PIO2_1) - k * PIO2_2) - k * PIO2_3
    z = r * r
    s = r + r * z * (S1 + z * (S2 + z * (S3 + z * (S4 + z * (S5 + z * (S6 + z * S7))))))
    c = 1.0 + z * (C1 + z * (C2 + z * (C3 + z * (C4 + z * (C5 + z * (C6 + z * (C7 + z * C8)))))))
    # quadrant k mod 4 in floating point (vectorises where int conversion does not)
    q = k - 4.0 * math.floor(k * 0.25)
    odd = q == 1.0 or q == 3.0                 # quadrants 1, 3: swap the pair
    sign_s = 1.0 if q < 2.0 else -1.0          # quadrants 2, 3: sin < 0
    sign_c = 1.0 if q == 0.0 or q == 3.0 else -1.0   # quadrants 1, 2: cos < 0
    return sign_s * (c if odd else s), sign_c * (s if odd else c)
