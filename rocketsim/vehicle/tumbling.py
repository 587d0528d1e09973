"""Drag of a tumbling body: its mean projected area and drag coefficient.

A part that nobody steers (a fairing half, a deployed payload) tumbles, so it
is flown as a point mass with the drag of a randomly tumbling body,
``F = -1/2 rho |v_air| v_air C_D(M, Kn) A_mean``
(:mod:`rocketsim.dynamics.free_body`).

Mean area. The projected area of a convex body averaged over uniformly random
orientations is a quarter of its surface area (Cauchy's surface-area formula;
e.g. Santalo, Integral Geometry and Geometric Probability, 1976, section 13.6).
A concave part (a half shell) is taken as its convex hull: the half cylinder
closed by its diametral plane and its two half-disc ends.

Drag coefficient, on that mean area:

- continuum (Knudsen number below 1e-3): the drag of a sphere against Mach
  number, :data:`SPHERE_MACH` / :data:`SPHERE_CD`, approximate readings (to a
  few hundredths, not re-checked against the originals here) of the
  subcritical-Reynolds curves of Bailey & Hiatt, "Sphere drag coefficients for
  a broad range of Mach and Reynolds numbers", AIAA J. 10 (1972) 1436, and
  Hoerner, Fluid-Dynamic Drag (1965), ch. 16 (subcritical: a tumbling body
  with edges has no drag crisis). The sphere is the tumbling body
  whose drag does not depend on its attitude, and at hypersonic speed every
  convex body tumbling at random has its drag: in Newtonian flow (surface
  pressure ``C_p,max cos^2 theta`` on the faces the flow meets) a surface
  element ``dA`` facing the flow at ``theta`` gives the drag
  ``q C_p,max cos^3 theta dA``, whose mean over random attitudes is
  ``q C_p,max dA / 8``; over the body ``q C_p,max S / 8``, so on the mean area
  ``S / 4`` the drag coefficient is ``C_p,max / 2`` whatever the convex shape:
  0.92 with the modified-Newtonian ``C_p,max = 1.839`` (the stagnation pressure
  behind a normal shock at M -> infinity, gamma = 1.4; Anderson, Hypersonic and
  High-Temperature Gas Dynamics, 2nd ed., 2006, section 3.2), the table's value
  from Mach 5 on;
- free molecular (Knudsen number above 10): 2.2, the value used for satellites
  with diffuse re-emission (Vallado, Fundamentals of Astrodynamics and
  Applications, 4th ed., 2013, section 8.6.2; Wertz & Larson, Space Mission
  Analysis and Design, 3rd ed., 1999, section 8.1);
- between them, a sine-squared bridging in ``log10 Kn``,
  ``C_D = C_c + (C_fm - C_c) sin^2(pi (3/8 + log10(Kn) / 8))``, of the kind the
  re-entry literature uses for the transitional regime (e.g. Wilmoth,
  Mitcheltree & Moss, "Low-density aerodynamics of the Stardust sample return
  capsule", J. Spacecraft Rockets 36, 1999); its end points 1e-3 and 10 are
  this module's choice.

The Knudsen number is the air's mean free path over the body's length; the
mean free path scales as ``1/rho`` from its sea-level value 6.6328e-8 m at
1.225 kg/m^3 (U.S. Standard Atmosphere 1976, table I).
"""

from __future__ import annotations

import math

import numpy as np

from rocketsim.jit import njit
from rocketsim.constants import USSA_MEAN_FREE_PATH0, USSA_RHO0

# sphere drag against Mach number, high Reynolds number (see the module docstring)
SPHERE_MACH = np.array([0.0, 0.5, 0.7, 0.8, 0.9, 1.0, 1.2, 1.5, 2.0, 3.0, 5.0])
SPHERE_CD = np.array([0.47, 0.50, 0.56, 0.62, 0.75, 0.90, 1.00, 1.02, 0.98, 0.94, 0.92])
FREE_MOLECULAR_CD = 2.2             # diffuse re-emission (Vallado 2013, 8.6.2)
KN_CONTINUUM, KN_FREE = 1e-3, 10.0  # the bridging's ends


@njit
def continuum_cd(mach):
    """Drag coefficient of a tumbling body in continuum flow at Mach ``mach``
    (:data:`SPHERE_CD`, linear between rows, constant beyond the last)."""
    n = SPHERE_MACH.shape[0]
    if mach >= SPHERE_MACH[n - 1]:
        return SPHERE_CD[n - 1]
    i = 0
    while SPHERE_MACH[i + 1] <= mach:
        i += 1
    f = (mach - SPHERE_MACH[i]) / (SPHERE_MACH[i + 1] - SPHERE_MACH[i])
    return SPHERE_CD[i] + f * (SPHERE_CD[i + 1] - SPHERE_CD[i])


@njit
def tumbling_cd(mach, rho, length):
    """Drag coefficient (on the mean projected area) of a body ``length`` m long
    tumbling at Mach ``mach`` in air of density ``rho`` kg/m^3: continuum, free
    molecular or bridged by the Knudsen number (module docstring)."""
    kn = USSA_MEAN_FREE_PATH0 * USSA_RHO0 / (rho * length)
    if kn >= KN_FREE:
        return FREE_MOLECULAR_CD
    c = continuum_cd(mach)
    if kn <= KN_CONTINUUM:
        return c
    s = math.sin(math.pi * (0.375 + 0.125 * math.log10(kn)))
    return c + (FREE_MOLECULAR_CD - c) * s * s


def cylinder_area(radius: float, length: float) -> float:
    """Mean projected area (m^2) of a tumbling closed cylinder: surface / 4."""
    return 0.25 * (2.0 * math.pi * radius * length + 2.0 * math.pi * radius ** 2)


def half_shell_area(radius: float, length: float) -> float:
    """Mean projected area (m^2) of a tumbling half cylindrical shell: its convex
    hull's surface (half the lateral surface, the diametral rectangle, two half
    discs) over 4."""
    return 0.25 * (math.pi * radius * length + 2.0 * radius * length + math.pi * radius ** 2)
