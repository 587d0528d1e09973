"""Where a coast leads: the field integrated ahead of the flight, for flight programs.

A program that targets a periapsis or an encounter asks what its coast will
do, with or without an impulsive change of velocity now. :func:`coast`
integrates position and velocity through the n-body field
(:func:`rocketsim.dynamics.nbody.field`, the other bodies evaluated at each
instant, as on cruise rails) with Dormand-Prince 8(5,3) under error control
(scipy's ``DOP853``), in the frame and about the central body of the field
``fp``; it stops early at the next periapsis when asked. A prediction is a
separate computation: it never changes the flight.
"""

from __future__ import annotations

import numpy as np

from rocketsim.dynamics.nbody import field


def coast(r, v, t0: float, seconds: float, p, fp, *, periapsis: bool = False,
          rtol: float = 1e-10, atol: float = 1e-3):
    """``(t, r, v)`` after coasting from ``r`` (m), ``v`` (m/s) at mission time ``t0`` (s).

    Integrates ``seconds`` (s) ahead in the field ``fp`` about the central body
    of the parameters ``p`` (frame axes); with ``periapsis`` it stops at the
    next periapsis (the radial velocity turning from negative to positive)
    if that comes first. ``atol`` is in metres and m/s.
    """
    from scipy.integrate import solve_ivp   # here: a flight that predicts nothing never loads it
    p = np.asarray(p, dtype=float)
    fp = np.asarray(fp, dtype=float)

    def rhs(t, y):
        return np.concatenate((y[3:], field(y[:3], t, fp, p, held=False)))

    def closest(t, y):
        return float(y[:3] @ y[3:])
    closest.terminal = True
    closest.direction = 1.0

    y0 = np.concatenate((np.asarray(r, dtype=float), np.asarray(v, dtype=float)))
    solution = solve_ivp(rhs, (t0, t0 + seconds), y0, method="DOP853", rtol=rtol, atol=atol,
                         events=closest if periapsis else None)
    if not solution.success:
        raise RuntimeError(f"coast prediction failed: {solution.message}")
    if periapsis and len(solution.t_events[0]):
        return float(solution.t_events[0][0]), solution.y_events[0][0][:3], solution.y_events[0][0][3:]
    return float(solution.t[-1]), solution.y[:3, -1], solution.y[3:, -1]
