"""Grid fins: lattice fins on arms round the body, deflected on all three axes, compiled.

docs/physics.md#grid-fins: grid fins on all three axes, with a normal-force
slope that dips as the lattice chokes near Mach 1, a stall limit, and a
Mach-dependent drag on all four fins. Each fin sits at station ``x`` on an arm at angle
``phi`` about the body x axis (arm direction ``(0, cos phi, sin phi)``, its
centre of pressure ``r`` from the axis) and turns about its arm by ``delta``.
With ``e_n = (0, -sin phi, cos phi)``, its chord and normal are::

    c = cos(delta) e_x + sin(delta) e_n,     n = -sin(delta) e_x + cos(delta) e_n

The local flow at the fin is the centre of mass's air-relative velocity plus
``omega x r_fin``; its angle to the lattice ``a = atan2(V.n, |V.c|)`` gives
the normal force ``-q A C_N_alpha(M) a n`` (``|a|`` capped at the stall
angle) and the drag ``-q A C_D(M) V/|V|``, with ``q = 1/2 rho |V|^2`` and
``A`` the fin's reference (frontal) area. Because ``|V.c|`` is used, a fin
works in either direction of flow: tail first (a landing booster) its
deflection sense reverses, as a real one's does.

Commands: ``pitch``, ``yaw`` and ``roll`` deflections (rad) map onto the fins
as ``delta = pitch cos(phi) - yaw sin(phi) + roll``: with the air coming from
the nose, positive pitch pushes the fin station towards body +z, positive yaw
towards +y, positive roll turns the body about +x. Each fin slews towards its
commanded deflection at a limited rate (``delta0`` at ``t0``, then at
``rate`` until it reaches the command), evaluated at every RK4 stage.

Tables: the shape of the normal-force slope and drag against Mach (a dip of
the slope and a peak of the drag between Mach 0.8 and 1.2 where the lattice
cells choke, recovery supersonic, ``1/beta`` fall-off above) follows W. D.
Washington & M. S. Miller, "Grid fins - a new concept for missile stability
and control", AIAA 93-0035 (1993), figs. for the lattice fins tested there;
the magnitudes (per radian, on the frontal area) are this project's estimates.
"""

from __future__ import annotations

import math

import numpy as np

from rocketsim.jit import njit
from rocketsim.vehicle.aero import NO_LOAD, interp, with_force

GRID_MACH = np.array([0.0, 0.6, 0.8, 0.95, 1.05, 1.2, 1.5, 2.0, 3.0, 5.0])
GRID_CN_ALPHA = np.array([2.9, 3.0, 3.1, 2.2, 1.8, 2.3, 2.4, 2.0, 1.4, 0.9])   # per rad
GRID_CD = np.array([0.60, 0.65, 0.80, 1.30, 1.50, 1.10, 0.90, 0.75, 0.60, 0.50])

# columns of AeroArrays.grid (G_COS_PHI, G_SIN_PHI: cos and sin of G_PHI, once at build)
G_X, G_PHI, G_R, G_AREA, G_MAX, G_RATE, G_STALL, G_COS_PHI, G_SIN_PHI = 0, 1, 2, 3, 4, 5, 6, 7, 8
N_GRID = 9
# columns of AeroArrays.grid_cmd
GC_DELTA0, GC_CMD, GC_T0 = 0, 1, 2
N_GRID_CMD = 3


@njit
def deflection(t, row, cmd_row):
    """Deflection (rad) of one fin at time ``t`` (s), slewing from ``delta0`` at ``t0``."""
    d0 = cmd_row[GC_DELTA0]
    target = cmd_row[GC_CMD]
    gap = target - d0
    if gap == 0.0:
        return target
    reach = row[G_RATE] * max(t - cmd_row[GC_T0], 0.0)
    if reach >= abs(gap):
        return target
    return d0 + math.copysign(reach, gap)


@njit(borrows=True)
def grid_fin_forces(t, u, v, w, wx, wy, wz, rho, sound, x_cm, grid, grid_cmd):
    """Force (N, body axes) and moment (N m about the centre of mass) of all grid fins.

    ``(u, v, w)`` the centre of mass's air-relative velocity in body axes
    (m/s), ``(wx, wy, wz)`` body rates (rad/s).
    """
    load = NO_LOAD
    for i in range(grid.shape[0]):
        row = grid[i]
        d = row[G_X] - x_cm
        cphi = row[G_COS_PHI]
        sphi = row[G_SIN_PHI]
        ry = row[G_R] * cphi
        rz = row[G_R] * sphi
        # flow at the fin: V + omega x r
        vx = u + wy * rz - wz * ry
        vy = v + wz * d - wx * rz
        vz = w + wx * ry - wy * d
        s2 = vx * vx + vy * vy + vz * vz
        if s2 == 0.0:
            continue
        s = math.sqrt(s2)
        delta = deflection(t, row, grid_cmd[i])
        cd = math.cos(delta)
        sd = math.sin(delta)
        # n = -sin(delta) e_x + cos(delta) e_n, c = cos(delta) e_x + sin(delta) e_n
        ny, nz = -cd * sphi, cd * cphi
        nx = -sd
        en_v = -sphi * vy + cphi * vz
        v_n = nx * vx + ny * vy + nz * vz
        v_c = cd * vx + sd * en_v
        a = math.atan2(v_n, abs(v_c))
        stall = row[G_STALL]
        if a > stall:
            a = stall
        elif a < -stall:
            a = -stall
        mach = s / sound
        qa = 0.5 * rho * s2 * row[G_AREA]
        normal = -qa * interp(GRID_MACH, GRID_CN_ALPHA, mach) * a
        drag = -qa * interp(GRID_MACH, GRID_CD, mach) / s
        gx = normal * nx + drag * vx
        gy = normal * ny + drag * vy
        gz = normal * nz + drag * vz
        load = with_force(load, d, ry, rz, gx, gy, gz)
    return load


@njit
def command(grid: np.ndarray, grid_cmd: np.ndarray, t: float, pitch: float, yaw: float,
            roll: float) -> None:
    """Command the fins (rad) at time ``t`` (s): each starts slewing from where it is now.

    Each fin's deflection is clipped to its range. Updates ``grid_cmd`` in place.
    """
    for i in range(grid.shape[0]):
        row = grid[i]
        now = deflection(t, row, grid_cmd[i])
        target = pitch * row[G_COS_PHI] - yaw * row[G_SIN_PHI] + roll
        grid_cmd[i, GC_DELTA0] = now
        grid_cmd[i, GC_CMD] = max(-row[G_MAX], min(row[G_MAX], target))
        grid_cmd[i, GC_T0] = t
