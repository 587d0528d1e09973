"""Where and when a body that went below the ground in its last step crossed it.

A step ends wherever it ends: a body falling at 1.2 km/s with a 0.1 s step is up
to 120 m below the ground when the world sees it there. Its impact is recorded
at the crossing instead, found on the arc back from that first state below the
ground under the central body's gravity (point mass and J2,
:func:`rocketsim.bodies.gravity.gravity`)::

    r(tau) = r + v tau + g tau^2 / 2,   v(tau) = v + g tau,   -h <= tau <= 0

at the ``tau`` where the height along the radius
(:func:`rocketsim.dynamics.derivative.radial_height`, the world's impact test) is
the ground's, by bisection to a nanosecond. The other forces of the last step
(drag, thrust) are left out of the arc: their acceleration ``a`` moves the crossing
by at most ``a tau^2 / 2``, 5 cm for an ``a`` of one standard gravity over a 0.1 s
step, 2 mm at 20 ms; in vacuum the arc is the flown path to a fraction of a
millimetre. The attitude and rates are those at the end of the step.
"""

from __future__ import annotations

import numpy as np

from rocketsim.bodies.gravity import gravity
from rocketsim.dynamics.derivative import radial_height
from rocketsim.layout import P_J2, P_MU, P_RADIUS, R, V

BISECTIONS = 60           # halvings of the step: far below a nanosecond


def back_to_ground(y: np.ndarray, p: np.ndarray, ground: float, h: float) -> tuple[float, np.ndarray]:
    """``(tau, state)``: the state ``y`` (parameters ``p``), below the height ``ground``
    (m above the central body's ellipsoid) at the end of a step of ``h`` seconds,
    carried back ``tau`` seconds (``-h <= tau <= 0``) to the crossing (see the module)."""
    r, v = y[R:R + 3], y[V:V + 3]
    g = gravity(r, p[P_MU], p[P_RADIUS], p[P_J2])
    state = y.copy()

    def below(tau: float) -> bool:
        state[R:R + 3] = r + v * tau + 0.5 * g * tau * tau
        return radial_height(state, p) < ground

    early, late = -h, 0.0            # above (or the step's start) .. below
    for _ in range(BISECTIONS):
        middle = 0.5 * (early + late)
        if below(middle):
            late = middle
        else:
            early = middle
    tau = early if not below(early) else late
    below(tau)
    state[V:V + 3] = v + g * tau
    return tau, state
