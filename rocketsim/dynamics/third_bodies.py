"""The other bodies' pull in a field about a central body, and the field a body carries.

docs/physics.md#n-body-field: with the central body ``c``, the
other bodies ``k`` at ``s_k`` from ``c`` and the vehicle at ``r`` from ``c``,
the perturbation is::

    sum_k mu_k [ (s_k - r)/|s_k - r|^3  -  s_k/|s_k|^3 ]

(direct minus indirect term), plus solar radiation pressure when its
coefficient is set. The field array ``fp`` (slots ``F_*`` below, built by
:func:`rocketsim.dynamics.nbody.make_field`) says which bodies pull, where
mission time 0 is (TT Julian date) and how the frame's axes lie in J2000.

A body flying in the n-body field carries its field in its parameter vector
``p`` (:func:`with_field`): its :data:`~rocketsim.layout.P_NBODY` slot is 1 and
the slots after :data:`~rocketsim.layout.N_PARAMS` hold ``fp``, the other bodies' positions held for the current 5 s bucket of
mission time (:data:`~rocketsim.constants.NBODY_HOLD`) and that bucket. The
flight model's step refreshes them (:func:`hold_field`, once per step, from
the step's start) and :func:`rocketsim.dynamics.derivative.derivative` adds
:func:`held_perturbation` to the central body's gravity: the very arithmetic
of the rails' field (:func:`rocketsim.dynamics.nbody.field_acceleration`),
so an awake and a sleeping body about the Moon or Mars stay bit-identical.
A parameter vector with ``P_NBODY`` 0 (length :data:`N_PARAMS`) flies the
central body's point mass and J2 alone.
"""

from __future__ import annotations

import math

import numpy as np

from rocketsim.jit import njit
from rocketsim.constants import (AU, EARTH_MU, MARS_MU, MOON_MU, NBODY_HOLD, SECONDS_PER_DAY,
                                 SOLAR_IRRADIANCE_1AU, SPEED_OF_LIGHT, SUN_MU)
from rocketsim.layout import N_PARAMS, P_NBODY
from rocketsim.ephemeris.solar_system import _truncated_one

# field slots
FIELD_CENTER = 0     # index of the central body in BODIES
FIELD_JD0 = 1        # TT Julian date of mission time 0
FIELD_SRP = 2        # C_R A / m, m^2/kg (0: no radiation pressure)
FIELD_ROT = 3        # 9 slots: rotation frame -> J2000, row-major
FIELD_MU = 12        # 4 slots: mu of sun, earth, moon, mars in the field (0: left out)
FIELD_DRAG = 16      # C_D A / m, m^2/kg, point-mass drag (0: none)
FIELD_WIND = 17      # 3 slots: the wind held for the step, m/s, frame axes (a tumbling part's drag)
N_FIELD = 20

# parameter slots of a body flying in the n-body field (after the plain parameters)
P_FIELD = N_PARAMS                  # N_FIELD slots: its field fp
P_HELD = P_FIELD + N_FIELD          # 12 slots: the other bodies' held positions (4, 3), m
P_BUCKET = P_HELD + 12              # mission time (s) the held positions are for (nan: none yet)
N_FIELD_PARAMS = P_BUCKET + 1

MU = {"sun": SUN_MU, "earth": EARTH_MU, "moon": MOON_MU, "mars": MARS_MU}
SRP_1AU = SOLAR_IRRADIANCE_1AU / SPEED_OF_LIGHT     # N/m^2, radiation pressure at 1 AU


@njit
def bodies_at(fp, t):
    """Positions (4, 3) m and velocities (4, 3) m/s of the Sun, Earth, Moon, Mars
    relative to the field's centre, frame axes, at mission time ``t`` (s)."""
    r, v = _truncated_one(fp[FIELD_JD0] + t / SECONDS_PER_DAY, int(fp[FIELD_CENTER]))
    s = np.empty((4, 3))
    u = np.empty((4, 3))
    for i in range(4):
        for k in range(3):
            # frame = M^T J2000, M row-major in fp
            s[i, k] = (fp[FIELD_ROT + k] * r[i, 0] + fp[FIELD_ROT + 3 + k] * r[i, 1]
                       + fp[FIELD_ROT + 6 + k] * r[i, 2])
            u[i, k] = (fp[FIELD_ROT + k] * v[i, 0] + fp[FIELD_ROT + 3 + k] * v[i, 1]
                       + fp[FIELD_ROT + 6 + k] * v[i, 2])
    return s, u


@njit
def hold_time(t):
    """The mission time (s) whose body positions are held at ``t``: ``t`` rounded
    down to a multiple of :data:`NBODY_HOLD`."""
    return math.floor(t / NBODY_HOLD) * NBODY_HOLD


@njit
def held_bodies(fp, t):
    """Body positions (4, 3) held for the 5 s bucket of mission time ``t``."""
    return bodies_at(fp, hold_time(t))[0]


@njit(borrows=True, inline="always")
def perturbation(x, y, z, s, fp):
    """Acceleration (m/s^2, frame axes) at ``(x, y, z)`` from every body but the
    centre (direct minus indirect term) plus radiation pressure when on."""
    ax = ay = az = 0.0
    c = int(fp[FIELD_CENTER])
    for k in range(4):
        mu = fp[FIELD_MU + k]
        if k == c or mu == 0.0:
            continue
        dx = s[k, 0] - x
        dy = s[k, 1] - y
        dz = s[k, 2] - z
        d2 = dx * dx + dy * dy + dz * dz
        d3 = d2 * math.sqrt(d2)
        s2 = s[k, 0] * s[k, 0] + s[k, 1] * s[k, 1] + s[k, 2] * s[k, 2]
        s3 = s2 * math.sqrt(s2)
        ax += mu * (dx / d3 - s[k, 0] / s3)
        ay += mu * (dy / d3 - s[k, 1] / s3)
        az += mu * (dz / d3 - s[k, 2] / s3)
    if fp[FIELD_SRP] != 0.0:
        # from the Sun to the vehicle (the Sun is at s[0], or at the origin when central)
        ux = x - s[0, 0]
        uy = y - s[0, 1]
        uz = z - s[0, 2]
        d2 = ux * ux + uy * uy + uz * uz
        d = math.sqrt(d2)
        k = SRP_1AU * AU * AU / d2 * fp[FIELD_SRP] / d
        ax += k * ux
        ay += k * uy
        az += k * uz
    return ax, ay, az


def with_field(p, fp) -> np.ndarray:
    """The parameter vector ``p`` (its first :data:`N_PARAMS` slots) extended by
    the field ``fp``: a body that flies in the n-body field (nothing held yet)."""
    out = np.full(N_FIELD_PARAMS, math.nan)
    out[:N_PARAMS] = np.asarray(p, dtype=float)[:N_PARAMS]
    out[P_NBODY] = 1.0
    out[P_FIELD:P_FIELD + N_FIELD] = fp
    return out


def field_of(p):
    """The field array carried by ``p`` (a copy), or None for Earth's gravity alone."""
    return None if p[P_NBODY] < 0.5 else np.array(p[P_FIELD:P_FIELD + N_FIELD])


def nbody_flag(p):
    """The ``nbody`` argument of the flight model's step for the parameters ``p``
    (:func:`rocketsim.dynamics.rk4.step`): True when ``p`` carries an n-body field,
    None when it does not (the step's hold of the other bodies compiled away)."""
    return True if p[P_NBODY] > 0.5 else None


@njit
def hold_field(p, t):
    """Hold the other bodies' positions in ``p`` for the 5 s bucket of mission time
    ``t`` (s); recomputed only when the bucket changes. ``p`` must carry a field."""
    bucket = hold_time(t)
    if p[P_BUCKET] != bucket:
        s = bodies_at(p[P_FIELD:P_FIELD + N_FIELD], bucket)[0]
        for i in range(4):
            for k in range(3):
                p[P_HELD + 3 * i + k] = s[i, k]
        p[P_BUCKET] = bucket


@njit
def held_perturbation(x, y, z, p):
    """:func:`perturbation` at ``(x, y, z)`` (m, frame axes) from the positions held
    in ``p`` (m/s^2)."""
    return perturbation(x, y, z, p[P_HELD:P_HELD + 12].reshape((4, 3)),
                        p[P_FIELD:P_FIELD + N_FIELD])
