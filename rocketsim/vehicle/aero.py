"""Aerodynamic force and moment of a slender body of revolution, compiled.

docs/physics.md#aerodynamics. Body axes: x along the stack from its base to
the nose, y and z lateral; stations ``x`` are metres above the base.
Everything here works on the air-relative velocity of the centre of mass in
body axes ``(u, v, w)`` (m/s; ``u > 0`` nose first), the body rates
``omega`` (rad/s) and the station of the centre of mass ``x_cm``. Forces are
in newtons on body axes, moments in N m about the centre of mass.

Axial force. ``F_x = -1/2 rho |V| u S C_A(M)``: at zero angle of attack this
is ``-q S C_A`` (``q = 1/2 rho V^2``); it scales with ``cos(alpha)`` and so
passes through zero, continuously, as the flow turns through 90 degrees.
``C_A`` blends the nose-first and the tail-first tables, a smoothstep in
``cos(alpha)`` from 80 to 100 degrees. Flying tail first under thrust the
plume shields the base (see :func:`plume_shielding`).

Normal force, per body segment (docs/physics.md#normal-force)::

    dN = eta(M_c) C_dc(M_c) 1/2 rho V_c^2 D dx

along the local crossflow ``(v + omega_z d, w - omega_y d)``, ``d = x - x_cm``
(the body's own rotation adds ``omega x d``), opposing it, in both lateral
planes at once; ``V_c`` its size and ``M_c = V_c / a``. ``C_dc`` is the
two-dimensional crossflow drag of a circular cylinder against crossflow Mach
and ``eta`` Jorgensen's crossflow efficiency (the finite cylinder carries less
than the two-dimensional value): L. H. Jorgensen, "Prediction of static
aerodynamic characteristics for slender bodies alone and with lifting
surfaces to very high angles of attack", NASA TR R-474 (1977), eq. (1) and
figs. 3-4 (the tables below are read from those figures: eta 0.55-0.72 with
fineness ratio, 1 at supersonic crossflow; C_dc 1.2 subcritical, a peak near
crossflow Mach 1, towards the Newtonian 4/3 hypersonic). Reynolds-number
effects (the supercritical drop of C_dc) are not modelled.

Slender-body lift at the leading end (Munk; Jorgensen eq. (1) first term,
``C_N = sin 2alpha cos(alpha/2)`` on the nose's base area; this module keeps
``2 sin alpha cos alpha``, docs/physics.md#nose-lift)::

    F_lateral = -rho S_lead |u| (v_lead, w_lead)   (= q S 2 sin a cos a)

at the leading end's centre of pressure: nose first, the nose's base area at
``x_tip - V_nose / S_nose`` (slender-body theory: 2/3 of a cone's length from
its tip, 0.467 of a tangent ogive's); tail first, the base's area at the base.
The two are blended by the same weight as the axial tables. A conical boattail
adds the same form with its change of area, ``S_aft - S_fore`` (negative nose
first: it lifts against the nose; its sign turns tail first, where it widens
towards the flow), at its slender-body centre of pressure, Barrowman's
``x_fore + L/3 (1 + (1 - d_f/d_a) / (1 - (d_f/d_a)^2))`` from its fore end.
Planar fins (a sounding rocket's) add the same form scaled by their
normal-force slope.
"""

from __future__ import annotations

import math

import numpy as np

from rocketsim.jit import njit
from rocketsim.constants import DEG

# --- tables ----------------------------------------------------------------
# Axial coefficient, nose first: docs/physics.md#axial-force's points (0.30 subsonic,
# 0.62 at Mach 1.15, 0.25 hypersonic); the shape between them is this
# module's (monotone up to the peak and down after it).
NOSE_FIRST_MACH = np.array([0.0, 0.6, 0.8, 0.95, 1.15, 1.5, 2.0, 3.0, 5.0, 8.0])
NOSE_FIRST_CA = np.array([0.30, 0.30, 0.34, 0.48, 0.62, 0.55, 0.45, 0.34, 0.27, 0.25])
# Tail first: 0.85 subsonic rising to 1.45 at Mach 2 (docs/physics.md#axial-force), held above.
TAIL_FIRST_MACH = np.array([0.0, 0.5, 0.8, 1.0, 1.2, 1.5, 2.0])
TAIL_FIRST_CA = np.array([0.85, 0.85, 0.95, 1.12, 1.28, 1.38, 1.45])
# Jorgensen (1977) fig. 4: crossflow drag of a 2-D circular cylinder against crossflow Mach.
CROSSFLOW_MACH = np.array([0.0, 0.4, 0.6, 0.8, 0.9, 1.0, 1.2, 1.5, 2.0, 3.0, 5.0])
CROSSFLOW_CD = np.array([1.20, 1.20, 1.30, 1.55, 1.75, 1.85, 1.80, 1.65, 1.50, 1.38, 1.33])
# Jorgensen (1977) fig. 3: subsonic crossflow efficiency against fineness ratio L/D.
EFFICIENCY_FINENESS = np.array([1.0, 5.0, 10.0, 20.0, 25.0])
EFFICIENCY_SUBSONIC = np.array([0.55, 0.60, 0.65, 0.70, 0.72])
EFFICIENCY_SUBSONIC_MACH = 0.6        # eta is its subsonic value up to this crossflow Mach ...
EFFICIENCY_SUPERSONIC_MACH = 1.0      # ... and 1 from this one (linear between)
HANDOVER = math.sin(10.0 * DEG)   # |cos alpha| of the hand-over band (80-100 deg)

# rows of AeroArrays.ref
A_ON = 0            # 1 when the vehicle has aerodynamics
A_AREA = 1          # m^2, reference area S (largest cross-section)
A_ETA = 2           # Jorgensen's subsonic efficiency for the body's fineness ratio
A_NOSE_X = 3        # m, station of the nose's slender-body centre of pressure
A_NOSE_AREA = 4     # m^2, base area of the nose (0: blunt top, no nose lift)
A_BASE_AREA = 5     # m^2, area of the base (leading end when flying tail first)
A_REACH = 6         # m, farthest any contact point can be from the centre of mass
A_WIND = 7          # 1 when the day has wind (sampled once per step)
A_GROUND = 8        # m, height of the (flat) ground above the ellipsoid (0: the ellipsoid)
A_TAIL_X = 9        # m, station of the boattail's slender-body centre of pressure
A_TAIL_AREA = 10    # m^2, the boattail's change of area, aft less fore (0: none; < 0: it narrows)
N_REF = 11
# rows of AeroArrays.seg: station of the segment's middle, its length, its diameter
SEG_X, SEG_DX, SEG_D = 0, 1, 2
# rows of AeroArrays.fin (planar fin sets): centre of pressure, C_N_alpha * S (m^2 per rad)
FIN_X, FIN_CNA_S = 0, 1


def centre_of_pressure(ref, fin) -> float:
    """Station (m) of the centre of pressure at small angles of attack, nose first: where
    the normal-force slopes act, the nose's slender-body lift (``2 S_nose`` per radian at
    ``A_NOSE_X``), a boattail's (``2 (S_aft - S_fore)``, negative, at ``A_TAIL_X``) and the
    fins' (``C_N_alpha S`` at their centres of pressure), as Barrowman's method sums them
    (J. S. Barrowman, "The practical calculation of the aerodynamic characteristics of
    slender finned vehicles", Catholic University of America thesis, 1967); the crossflow
    adds nothing at zero angle (it grows as ``sin^2 alpha``). nan when nothing lifts."""
    slope = 2.0 * ref[A_NOSE_AREA] + 2.0 * ref[A_TAIL_AREA] + float(np.sum(fin[:, FIN_CNA_S]))
    if slope <= 0.0:
        return math.nan
    return (2.0 * ref[A_NOSE_AREA] * ref[A_NOSE_X] + 2.0 * ref[A_TAIL_AREA] * ref[A_TAIL_X]
            + float(np.sum(fin[:, FIN_CNA_S] * fin[:, FIN_X]))) / slope


@njit(borrows=True)
def interp(xs, ys, x):
    """Linear interpolation in a table with increasing ``xs``, clamped at both ends."""
    n = xs.shape[0]
    if x <= xs[0]:
        return ys[0]
    if x >= xs[n - 1]:
        return ys[n - 1]
    lo = 0
    hi = n - 1
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if xs[mid] <= x:
            lo = mid
        else:
            hi = mid
    f = (x - xs[lo]) / (xs[hi] - xs[lo])
    return ys[lo] + f * (ys[hi] - ys[lo])


@njit
def tail_first_weight(cos_alpha):
    """0 nose first, 1 tail first; a smoothstep across 80-100 degrees of angle of attack."""
    s = 0.5 * (1.0 - cos_alpha / HANDOVER)
    if s <= 0.0:
        return 0.0
    if s >= 1.0:
        return 1.0
    return s * s * (3.0 - 2.0 * s)


@njit
def plume_shielding(c_t):
    """Fraction of the tail-first axial coefficient left with thrust coefficient
    ``C_T = T / (q S)`` against the flow: ``exp(-C_T)``.

    docs/physics.md#plume-shielding. No published closed form exists for it;
    this one follows the trend of the wind-tunnel data for a single central
    retro-nozzle collected by A. M.
    Korzun, J. R. Cruz & R. D. Braun, "A survey of supersonic retropropulsion
    technology for Mars entry, descent, and landing", IEEE Aerospace Conference
    2008 (and J. Spacecraft Rockets 46(5), 2009), sec. 4, from C. R. Jarvinen &
    R. H. Adams, NASA CR-114251 (1970): the aerodynamic drag falls steeply
    with C_T and is nearly gone (a few percent) for C_T above about 3. The
    exponential is this project's fit to that trend, not a published formula.
    """
    if c_t <= 0.0:
        return 1.0
    return math.exp(-c_t)


@njit(borrows=True, inline="always")
def axial_coefficient(mach, cos_alpha, c_t, ca_nose_first, ca_tail_first):
    """``C_A`` for Mach ``mach``, ``cos(alpha)`` and thrust coefficient ``c_t``
    (against the flow; 0 without thrust). Tables are (n, 2) arrays of (Mach, C_A)."""
    w = tail_first_weight(cos_alpha)
    nose = interp(ca_nose_first[:, 0], ca_nose_first[:, 1], mach)
    if w == 0.0:
        return nose
    tail = interp(ca_tail_first[:, 0], ca_tail_first[:, 1], mach) * plume_shielding(c_t)
    return (1.0 - w) * nose + w * tail


@njit
def crossflow_efficiency(eta_subsonic, crossflow_mach):
    """Jorgensen's ``eta``: its subsonic value up to crossflow Mach 0.6, 1 from Mach 1."""
    if crossflow_mach <= EFFICIENCY_SUBSONIC_MACH:
        return eta_subsonic
    if crossflow_mach >= EFFICIENCY_SUPERSONIC_MACH:
        return 1.0
    f = ((crossflow_mach - EFFICIENCY_SUBSONIC_MACH)
         / (EFFICIENCY_SUPERSONIC_MACH - EFFICIENCY_SUBSONIC_MACH))
    return eta_subsonic + f * (1.0 - eta_subsonic)


@njit
def moment_about_cm(d, ry, rz, gx, gy, gz):
    """Moment (N m) of the force ``(gx, gy, gz)`` (N) applied at ``(d, ry, rz)`` (m) from
    the centre of mass: ``r x F``."""
    return ry * gz - rz * gy, rz * gx - d * gz, d * gy - ry * gx


NO_LOAD = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)     # (fx, fy, fz, mx, my, mz) with no force yet


@njit(inline="always")     # a few operations: typed in its callers' loops
def with_force(load, d, ry, rz, gx, gy, gz):
    """``load``, a force and moment ``(fx, fy, fz, mx, my, mz)`` (N, N m about the centre
    of mass, body axes), with the force ``(gx, gy, gz)`` (N) applied at ``(d, ry, rz)`` (m
    from the centre of mass) and its moment (:func:`moment_about_cm`) added."""
    m = moment_about_cm(d, ry, rz, gx, gy, gz)
    return load[0] + gx, load[1] + gy, load[2] + gz, load[3] + m[0], load[4] + m[1], load[5] + m[2]


@njit
def _lift(d, k, v, w, wy, wz):
    """Lateral force ``-k (v + wz d, w - wy d)`` at ``d`` (m) from the centre of mass,
    and its pitch and yaw moments: ``(fy, fz, my, mz)``."""
    gy = -k * (v + wz * d)
    gz = -k * (w - wy * d)
    return gy, gz, -d * gz, d * gy


@njit(borrows=True)
def body_aero(u, v, w, wx, wy, wz, rho, sound, thrust, x_cm, ref, seg, fin, ca_nf, ca_tf):
    """Axial, crossflow, nose-lift and fin force and moment of the body.

    ``(u, v, w)`` air-relative velocity of the centre of mass in body axes
    (m/s), ``(wx, wy, wz)`` body rates (rad/s), ``rho`` density (kg/m^3),
    ``sound`` speed of sound (m/s), ``thrust`` the engines' force along body +x
    (N, for the plume shielding), ``x_cm`` station of the centre of mass (m).
    Returns ``(fx, fy, fz, mx, my, mz)`` (N; N m about the centre of mass).
    """
    speed2 = u * u + v * v + w * w
    if speed2 == 0.0 and wy == 0.0 and wz == 0.0:
        return 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
    speed = math.sqrt(speed2)
    area = ref[A_AREA]
    fx = fy = fz = my = mz = 0.0
    if speed > 0.0:
        mach = speed / sound
        cos_alpha = u / speed
        q = 0.5 * rho * speed2
        c_t = 0.0
        if thrust > 0.0 and u < 0.0:
            c_t = thrust / (q * area)
        fx = -0.5 * rho * speed * u * area * axial_coefficient(mach, cos_alpha, c_t, ca_nf, ca_tf)
    # crossflow, segment by segment, with the rotation-induced flow
    eta_sub = ref[A_ETA]
    for i in range(seg.shape[0]):
        d = seg[i, SEG_X] - x_cm
        cy = v + wz * d
        cz = w - wy * d
        vc2 = cy * cy + cz * cz
        if vc2 == 0.0:
            continue
        vc = math.sqrt(vc2)
        mc = vc / sound
        k = -0.5 * rho * vc * crossflow_efficiency(eta_sub, mc) * interp(
            CROSSFLOW_MACH, CROSSFLOW_CD, mc) * seg[i, SEG_D] * seg[i, SEG_DX]
        fy += k * cy
        fz += k * cz
        my -= d * k * cz
        mz += d * k * cy
    # slender-body lift at the leading end and of a boattail, fins
    tail = tail_first_weight(u / speed) if speed > 0.0 else 0.5
    au = abs(u)
    a = _lift(ref[A_NOSE_X] - x_cm, rho * (1.0 - tail) * ref[A_NOSE_AREA] * au, v, w, wy, wz)
    b = _lift(-x_cm, rho * tail * ref[A_BASE_AREA] * au, v, w, wy, wz)
    c = _lift(ref[A_TAIL_X] - x_cm, rho * (1.0 - 2.0 * tail) * ref[A_TAIL_AREA] * au, v, w, wy, wz)
    fy += a[0] + b[0] + c[0]
    fz += a[1] + b[1] + c[1]
    my += a[2] + b[2] + c[2]
    mz += a[3] + b[3] + c[3]
    for i in range(fin.shape[0]):
        a = _lift(fin[i, FIN_X] - x_cm, 0.5 * rho * fin[i, FIN_CNA_S] * au, v, w, wy, wz)
        fy += a[0]
        fz += a[1]
        my += a[2]
        mz += a[3]
    return fx, fy, fz, 0.0, my, mz
