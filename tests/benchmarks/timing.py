"""The one timing helper of the benchmarks (they print figures, never assert them)."""

import math
import time


def best_of(repeats, function):
    """``(seconds, result)``: the fastest of ``repeats`` calls of ``function()``."""
    best, result = math.inf, None
    for _ in range(repeats):
        start = time.perf_counter()
        result = function()
        best = min(best, time.perf_counter() - start)
    return best, result
