"""Sine and cosine together, inlined, for the series' inner loops.

The ephemeris kernels evaluate a few hundred sines and cosines per instant;
the C library's ``sin`` and ``cos`` are opaque calls that stop the compiler from vectorising the loop. :func:`sincos` is plain
arithmetic the compiler can inline and vectorise:

1. reduction: ``k = round(x / (pi/2))``, ``r = x - k pi/2`` with pi/2 split
   in three parts (Cody & Waite 1980): the first two have 33 significant
   bits, so ``k * part`` is exact for ``|k| < 2**20`` (``|x|`` up to 1.6e6),
   and ``|r| <= pi/4``;
2. the Taylor series of ``sin r`` to ``r^15`` and of ``cos r`` to ``r^16``:
   on ``|r| <= pi/4`` the first omitted terms are below 5e-17 and 3e-18;
3. the quadrant ``k mod 4`` swaps and negates the pair.

Agreement with the C library is within a few units in the last place for
``|x| < 1e5`` (checked in ``tests/unit/ephemeris/test_ephemeris_sincos.py``).
"""

from __future__ import annotations

import math

import numpy as np

from rocketsim.jit import njit

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


# --- Building many phases from a few ------------------------------------------
# The series' frequencies are integer combinations of a few mean motions, so
# most phases are the sum of two others: sin/cos of a sum then costs four
# products instead of a reduction and two polynomials.

def sum_recipe(keys: np.ndarray, tolerance: float, order: np.ndarray | None = None):
    """Plan to get ``sin``/``cos`` of every ``keys[i] * x`` from a few sincos.

    ``keys``: the phases' multipliers (frequencies, or integer rows encoded
    as numbers); ``order``: the order to visit them (default ascending).
    Each key equal (within ``tolerance``) to the sum of two keys visited
    before it is *derived* from that pair (the pair of least depth, so error
    chains stay short); the others are *direct*. Returns int64 arrays
    ``(direct, derived, pair_a, pair_b)``: ``derived[k] = pair_a[k] +
    pair_b[k]``, listed in an order where both parts come first.
    """
    keys = np.asarray(keys, dtype=np.float64)
    order = np.argsort(keys, kind="stable") if order is None else np.asarray(order)
    depth = np.zeros(len(keys), dtype=np.int64)
    seen: list[int] = []
    direct, derived, pair_a, pair_b = [], [], [], []
    for i in order:
        best = None
        if len(seen) > 1:
            done = np.array(seen)
            values = keys[done]
            sort = np.argsort(values)
            sorted_values = values[sort]
            want = keys[i] - values
            at = np.clip(np.searchsorted(sorted_values, want), 1, len(done) - 1)
            for shift in (-1, 0):
                j = at + shift
                hit = np.abs(sorted_values[j] - want) <= tolerance
                for a, b in zip(done[hit], done[sort[j[hit]]]):
                    cost = max(depth[a], depth[b])
                    if best is None or cost < best[0]:
                        best = (cost, a, b)
        if best is None:
            direct.append(i)
        else:
            depth[i] = best[0] + 1
            derived.append(i)
            pair_a.append(best[1])
            pair_b.append(best[2])
        seen.append(i)
    # by depth, so that consecutive derivations do not wait for each other
    by_depth = np.argsort(depth[np.array(derived, dtype=np.int64)], kind="stable")
    derived, pair_a, pair_b = (np.array(x, dtype=np.int64)[by_depth]
                               for x in (derived, pair_a, pair_b))
    return np.array(direct, dtype=np.int64), derived, pair_a, pair_b


@njit
def expand(phase, direct, derived, pair_a, pair_b, sin_out, cos_out):
    """Fill ``sin_out``/``cos_out`` with sin/cos of ``phase`` by a
    :func:`sum_recipe` plan: sincos for the direct ones, angle addition
    ``sin(a + b) = sin a cos b + cos a sin b`` (and cos) for the rest.
    ``phase`` need only be right at the direct indices."""
    for k in range(direct.shape[0]):
        i = direct[k]
        s, c = sincos(phase[i])
        sin_out[i] = s
        cos_out[i] = c
    for k in range(derived.shape[0]):
        i = derived[k]
        a = pair_a[k]
        b = pair_b[k]
        sin_out[i] = sin_out[a] * cos_out[b] + cos_out[a] * sin_out[b]
        cos_out[i] = cos_out[a] * cos_out[b] - sin_out[a] * sin_out[b]
