"""Reaction control: fixed thrusters with positions, directions, thrust and Isp, compiled.

Each thruster pushes ``f T d`` (N, body axes; ``d`` its unit thrust direction,
``f`` its command, a fraction 0-1 held for the step by the autopilot) at its
position ``(x, y, z)`` (m; x a station above the base), so it adds a torque
``(r - r_cm) x F`` about the centre of mass, and draws ``f T / (g0 Isp)``
(kg/s) from its tank while that tank holds propellant.

The tank is one of the vehicle's (a state entry): a thruster names it by
stage and tank in the vehicle file. A thruster whose tank is empty pushes
nothing.
"""

from __future__ import annotations

from rocketsim.jit import njit
from rocketsim.vehicle.aero import NO_LOAD, with_force

# columns of AeroArrays.rcs
R_X, R_Y, R_Z, R_DX, R_DY, R_DZ, R_THRUST, R_MDOT, R_TANK = 0, 1, 2, 3, 4, 5, 6, 7, 8
N_RCS = 9


@njit(borrows=True)
def rcs_forces(y, dy, x_cm, rcs, rcs_cmd):
    """Force (N, body) and moment (N m about the centre of mass) of the firing
    thrusters; subtracts their propellant flow from ``dy`` (kg/s)."""
    load = NO_LOAD
    for i in range(rcs.shape[0]):
        f = rcs_cmd[i]
        if f <= 0.0:
            continue
        tank = int(rcs[i, R_TANK])
        if y[tank] <= 0.0:
            continue
        push = f * rcs[i, R_THRUST]
        gx = push * rcs[i, R_DX]
        gy = push * rcs[i, R_DY]
        gz = push * rcs[i, R_DZ]
        d = rcs[i, R_X] - x_cm
        ry = rcs[i, R_Y]
        rz = rcs[i, R_Z]
        load = with_force(load, d, ry, rz, gx, gy, gz)
        dy[tank] -= f * rcs[i, R_MDOT]
    return load
