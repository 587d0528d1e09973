"""The reference integrator: Dormand-Prince with error control (scipy).

The flight never uses it; tests measure the fixed-step RK4 against it. It
integrates the very same derivative (:func:`rocketsim.dynamics.derivative`),
so a disagreement is the fixed-step method's error, not a model difference.
``method="DOP853"`` (8th order) serves tight tolerances; ``"RK45"`` is the
Dormand-Prince 5(4) pair.
"""

from __future__ import annotations

import numpy as np
from scipy.integrate import solve_ivp

from rocketsim.dynamics.derivative import derivative


def integrate_reference(y0, t0: float, t1: float, p, *, rtol: float = 1e-12, atol: float = 1e-12,
                        method: str = "DOP853", t_eval=None, veh=None):
    """Integrate the state ``y0`` from ``t0`` to ``t1`` (s) with error control.

    Returns the state at ``t1`` (or at each of ``t_eval``, shape (N, len(y0))).
    The quaternion is not renormalised along the way: a tight tolerance keeps
    its norm to the tolerance. ``veh``: a staged vehicle's arrays (see
    :func:`rocketsim.dynamics.derivative.derivative`); a stage running dry is
    not handled here, so integrate up to the cut-off at most.
    """
    p = np.asarray(p, dtype=float)

    def rhs(t, y):
        dy = np.empty_like(y)
        derivative(t, y, p, dy, veh)
        return dy

    solution = solve_ivp(rhs, (t0, t1), np.asarray(y0, dtype=float), method=method,
                         rtol=rtol, atol=atol, t_eval=t_eval)
    if not solution.success:
        raise RuntimeError(f"reference integration failed: {solution.message}")
    return solution.y[:, -1] if t_eval is None else solution.y.T
