"""Earth-centred inertial (ECI) <-> Earth-fixed (ECEF) rotation.

Frames (docs/physics.md#frames): ECI has ``z`` along
Earth's spin axis and ``x`` through the Greenwich meridian at mission time 0
(rotated by ``theta0`` when the launch instant's sidereal angle is wanted).
Earth-fixed axes are ECI turned about ``z`` by

    theta(t) = theta0 + omega_E * t,      omega_E = EARTH_OMEGA (WGS84)

so ``r_ecef = R3(theta) r_eci`` with ``R3`` the frame rotation about ``z``.
Velocities carry the transport term: ``v_ecef = R3(theta) (v_eci - w x r_eci)``
with ``w = (0, 0, omega_E)``.

Positions and velocities are metres and m/s, of shape (3,) or (N, 3); ``t`` is
seconds of mission time, a scalar or an (N,) array matched row by row.
"""

from __future__ import annotations

import math

import numpy as np

from rocketsim.constants import EARTH_OMEGA


def earth_rotation_angle(t, theta0=0.0):
    """Angle (rad) from ECI ``x`` to the Greenwich meridian at mission time ``t`` (s).

    ``theta0 + EARTH_OMEGA * t``, not wrapped (wrapping would lose nothing
    but makes the angle jump); a scalar for a scalar ``t``, else an array.
    """
    theta = theta0 + EARTH_OMEGA * np.asarray(t, dtype=float)
    return float(theta) if theta.ndim == 0 else theta


def _rotate_z(vec, angle):
    """Components of ``vec`` (3,) or (N, 3) in axes turned by ``angle`` about z.

    ``angle`` is a scalar or (N,). Returns ``R3(angle) vec``:
    ``x' = cos a x + sin a y``, ``y' = -sin a x + cos a y``, ``z' = z``.
    """
    if np.ndim(angle) == 0 and np.shape(vec) == (3,):
        # one vector: plain floats, a few times faster than the array path
        c, s = math.cos(angle), math.sin(angle)
        x, y = float(vec[0]), float(vec[1])
        return np.array((c * x + s * y, -s * x + c * y, float(vec[2])))
    vec = np.asarray(vec, dtype=float)
    angle = np.asarray(angle, dtype=float)
    c = np.cos(angle)
    s = np.sin(angle)
    x = vec[..., 0]
    y = vec[..., 1]
    out = np.empty(np.broadcast_shapes(vec.shape, angle.shape + (3,)))
    out[..., 0] = c * x + s * y
    out[..., 1] = -s * x + c * y
    out[..., 2] = vec[..., 2]
    return out


def _omega_cross(r):
    """``w x r`` for Earth's rotation vector ``w = (0, 0, EARTH_OMEGA)``; r (3,) or (N, 3)."""
    r = np.asarray(r, dtype=float)
    out = np.zeros_like(r)
    out[..., 0] = -EARTH_OMEGA * r[..., 1]
    out[..., 1] = EARTH_OMEGA * r[..., 0]
    return out


def eci_to_ecef(r, t, theta0=0.0):
    """Earth-fixed position (m) of the ECI position ``r`` (m) at mission time ``t`` (s)."""
    return _rotate_z(r, earth_rotation_angle(t, theta0))


def ecef_to_eci(r, t, theta0=0.0):
    """ECI position (m) of the Earth-fixed position ``r`` (m) at mission time ``t`` (s)."""
    return _rotate_z(r, -np.asarray(earth_rotation_angle(t, theta0)))


def eci_to_ecef_velocity(r, v, t, theta0=0.0):
    """Earth-fixed velocity (m/s) of a point at ECI ``r`` (m) moving at ECI ``v`` (m/s).

    ``v_ecef = R3(theta) (v - w x r)``: a point at rest on the ground has
    ECI velocity ``w x r`` and Earth-fixed velocity zero.
    """
    return _rotate_z(np.asarray(v, dtype=float) - _omega_cross(r), earth_rotation_angle(t, theta0))


def ecef_to_eci_velocity(r_ecef, v_ecef, t, theta0=0.0):
    """ECI velocity (m/s) of a point at Earth-fixed ``r_ecef`` moving at ``v_ecef``.

    ``v_eci = R3(-theta) v_ecef + w x r_eci``; on the pad (``v_ecef = 0``) this
    is the ground's eastward speed ``omega_E R cos(lat)`` (465.1 m/s at the
    equator).
    """
    back = -np.asarray(earth_rotation_angle(t, theta0))
    r_eci = _rotate_z(r_ecef, back)
    return _rotate_z(v_ecef, back) + _omega_cross(r_eci)
