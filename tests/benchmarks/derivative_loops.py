"""Compiled loops that call the derivative n times, for the per-call benchmarks.

Shared by the vehicle and aerodynamics benchmarks; the running sum keeps the
compiler from dropping the calls.
"""

import numba

from rocketsim.dynamics.derivative import derivative
from rocketsim.layout import V


@numba.njit
def powered_derivative_calls(n, y, p, dy, veh):
    """``n`` derivative calls of a staged vehicle (its arrays ``veh``)."""
    total = 0.0
    for i in range(n):
        derivative(1e-6 * i, y, p, dy, veh)
        total += dy[V]
    return total


@numba.njit
def coasting_derivative_calls(n, y, p, dy):
    """``n`` derivative calls of a coasting rigid body."""
    total = 0.0
    for i in range(n):
        derivative(1e-6 * i, y, p, dy)
        total += dy[V]
    return total
