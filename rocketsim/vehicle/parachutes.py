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

``v_air = v - omega x r - wind`` the centre of mass's velocity through the air
(so a body under a canopy drifts with the wind); a parachute another one
``releases`` is cut away when that one begins to inflate (its drag stops
there, as in simulators that fly one parachute at a time).

The body hangs from its canopies: each one's drag pulls along its shock cord,
which runs from the cord's attachment point on the body's axis (station
``CH_X``) towards the canopy trailing in the airflow, so each drag acts at its
attachment point along ``-v_air`` and has the moment ``(x_a - x_cm) e_x x F``
about the centre of mass (body axes). Hung above the centre of mass, the body
swings to hang under it, its axis along the airflow: a rocket attached at its
top falls tail first, at a small angle of attack. This is the payload's side
of the parachute-payload models, where the riser's tension acts on the rigid
payload at its attachment point (G. Guglieri, "Parachute-Payload System Flight
Dynamics and Trajectory Simulation", Int. J. Aerospace Eng. 2012, 182907),
with the canopy's side reduced to its drag: no cord stretch, no canopy motion
of its own, the cord along the airflow. The body's own aerodynamics still act,
and its rotation is damped towards the canopy's (taken as not turning): the
body rates decay as ``omega' = -f omega / tau`` with ``f`` the largest inflated
fraction and ``tau`` :data:`CANOPY_RATE_TIME` (the suspension lines and the
canopy's own drag resisting a turn; a simple model, not a two-body canopy and
payload). The instants the drag area has a kink (``t_d + t_lag``,
``t_d + t_lag + t_inf``) cut the step like an engine's (:func:`next_canopy_kink`).

``chute`` (parachutes x :data:`N_CHUTE`): the columns below.
"""

from __future__ import annotations

import math

from rocketsim.jit import njit
from rocketsim.frames.local import air_velocity_inertial, body_air_velocity
from rocketsim.vehicle.motors import sooner, within_step

CH_STAGE = 0        # index of the stage that carries it
CH_CDS = 1          # m^2, drag area when fully inflated
CH_LAG = 2          # s, from deployment to the start of inflation
CH_INFLATION = 3    # s, from the start of inflation to full drag area
CH_DEPLOYED = 4     # s, mission time of deployment (nan: packed)
CH_CUT_BY = 5       # row of the parachute whose opening cuts this one away (-1: none)
CH_X = 6            # m, station of its shock cord's attachment on the axis (above the lowest base)
N_CHUTE = 7
CANOPY_RATE_TIME = 1.0     # s, time constant of the damping of the body's rates under a canopy


@njit
def cut_away(t, chute, i):
    """True once parachute ``i`` has been cut away at mission time ``t`` (s): the parachute
    that releases it (``CH_CUT_BY``) has begun to inflate (its deployment plus its lag)."""
    j = int(chute[i, CH_CUT_BY])
    if j < 0 or math.isnan(chute[j, CH_DEPLOYED]):
        return False
    return t > chute[j, CH_DEPLOYED] + chute[j, CH_LAG]


@njit(borrows=True, inline="always")
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


@njit(borrows=True, inline="always")
def canopy_drag(t, y, rho, wind, spin, chute, x_cm):
    """``(fx, fy, fz, my, mz, f)``: the parachutes' drag (N, inertial axes) at mission time
    ``t`` (s) in air of density ``rho`` (kg/m^3) moving with the ground (``spin`` rad/s
    about the frame's z) plus ``wind`` (inertial, m/s); its moment (N m, body y and z; none
    about the axis) about the centre of mass at station ``x_cm`` (m), each drag acting at
    its shock cord's attachment; and the largest inflated fraction."""
    area = 0.0
    arm = 0.0           # sum of C_D S(t) (x_a - x_cm), m^3
    largest = 0.0
    for i in range(chute.shape[0]):
        f = inflated(t, chute, i)
        area += f * chute[i, CH_CDS]
        arm += f * chute[i, CH_CDS] * (chute[i, CH_X] - x_cm)
        largest = max(largest, f)
    if area == 0.0:
        return 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
    ax, ay, az = air_velocity_inertial(y, wind, spin)
    k = -0.5 * rho * math.sqrt(ax * ax + ay * ay + az * az)
    body = body_air_velocity(y, wind, spin)     # the airflow in body axes
    # (x_a - x_cm) e_x x F, F = k C_D S v_air (body axes), summed over the canopies
    return (k * area * ax, k * area * ay, k * area * az, -k * arm * body[2],
            k * arm * body[1], largest)


@njit(borrows=True, inline="always")
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
