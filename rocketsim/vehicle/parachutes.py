"""Parachutes: drag against the air-relative velocity, opening lag and inflation, compiled.

docs/physics.md#parachutes. A parachute deployed at mission time ``t_d``
(by its trigger or the program: ``CH_DEPLOYED``, nan before) pulls nothing
during its opening lag ``t_lag`` (the deployment bag and lines paying out),
then its drag area grows linearly from 0 to its full ``C_D S`` over the
inflation time ``t_inf`` and holds it (the simplest of the drag-area-against-time
filling laws; T. W. Knacke, *Parachute Recovery Systems Design Manual*,
NWC TP 6575, 1992, ch. 5, treats filling times and the shapes of the growth;
the linear one is this project's choice):

    C_D S(t) = C_D S min(1, max(0, (t - t_d - t_lag) / t_inf))
    F = -1/2 rho |v_air| v_air  sum C_D S(t)

applied at the centre of mass (a parachute another one ``releases`` is cut
away when that one begins to inflate: its drag stops there, as in
simulators that fly one parachute at a time), ``v_air = v - omega x r - wind`` the
centre of mass's velocity through the air (so a body under a canopy drifts
with the wind). Under a canopy the body's own aerodynamics still act, and its
rotation is damped towards the canopy's (taken as not turning): the body
rates decay as ``omega' = -f omega / tau`` with ``f`` the largest inflated
fraction and ``tau`` :data:`CANOPY_RATE_TIME` (the suspension lines hold the
body; a simple model, not a two-body canopy and payload). The instants the
drag area has a kink (``t_d + t_lag``, ``t_d + t_lag + t_inf``) cut the step like
an engine's (:func:`next_canopy_kink`).

``chute`` (parachutes x :data:`N_CHUTE`): the columns below.
"""

from __future__ import annotations

import math

from rocketsim._jit import njit
from rocketsim.layout import R, V
from rocketsim.vehicle.motors import sooner, within_step

CH_STAGE = 0        # index of the stage that carries it
CH_CDS = 1          # m^2, drag area when fully inflated
CH_LAG = 2          # s, from deployment to the start of inflation
CH_INFLATION = 3    # s, from the start of inflation to full drag area
CH_DEPLOYED = 4     # s, mission time of deployment (nan: packed)
CH_CUT_BY = 5       # row of the parachute whose opening cuts this one away (-1: none)
N_CHUTE = 6
CANOPY_RATE_TIME = 1.0     # s, time constant of the damping of the body's rates under a canopy


@njit
def cut_away(t, chute, i):
    """True once parachute ``i`` has been cut away at mission time ``t`` (s): the parachute
    that releases it (``CH_CUT_BY``) has begun to inflate (its deployment plus its lag)."""
    j = int(chute[i, CH_CUT_BY])
    if j < 0 or math.isnan(chute[j, CH_DEPLOYED]):
        return False
    return t > chute[j, CH_DEPLOYED] + chute[j, CH_LAG]


@njit
def inflated(t, chute, i):
    """Inflated fraction (0..1) of parachute ``i`` at mission time ``t`` (s); 0 once cut away."""
    deployed = chute[i, CH_DEPLOYED]
    if math.isnan(deployed) or cut_away(t, chute, i):
        return 0.0
    since = t - deployed - chute[i, CH_LAG]
    if since <= 0.0:
        return 0.0
    if since >= chute[i, CH_INFLATION]:
        return 1.0
    return since / chute[i, CH_INFLATION]


@njit
def canopy_drag(t, y, rho, wind, spin, chute):
    """``(fx, fy, fz, f)``: the parachutes' drag (N, inertial axes) at mission time ``t``
    (s) in air of density ``rho`` (kg/m^3) moving with the ground (``spin`` rad/s about
    the frame's z) plus ``wind`` (inertial, m/s), and the largest inflated fraction."""
    area = 0.0
    largest = 0.0
    for i in range(chute.shape[0]):
        f = inflated(t, chute, i)
        area += f * chute[i, CH_CDS]
        largest = max(largest, f)
    if area == 0.0:
        return 0.0, 0.0, 0.0, 0.0
    ax = y[V] + spin * y[R + 1] - wind[0]
    ay = y[V + 1] - spin * y[R] - wind[1]
    az = y[V + 2] - wind[2]
    k = -0.5 * rho * math.sqrt(ax * ax + ay * ay + az * az) * area
    return k * ax, k * ay, k * az, largest


@njit
def next_canopy_kink(t, h, chute):
    """Time (s) from ``t`` to the first start or end of a deployed parachute's inflation
    inside the step ``(t, t + h)``, or ``h``."""
    first = h
    floor = 1e-9 * h
    for i in range(chute.shape[0]):
        deployed = chute[i, CH_DEPLOYED]
        if math.isnan(deployed):
            continue
        a = deployed + chute[i, CH_LAG] - t
        first = sooner(a + chute[i, CH_INFLATION], sooner(a, first, floor), floor)
    return within_step(first, h, floor)


def deploy(chute, i: int, t: float) -> bool:
    """Deploy parachute ``i`` at mission time ``t`` (s); False if it is already out."""
    if not math.isnan(chute[i, CH_DEPLOYED]):
        return False
    chute[i, CH_DEPLOYED] = t
    return True
