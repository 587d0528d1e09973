"""The local frame of a point over a turning ellipsoid, and velocities relative to it.

The central body turns at ``spin`` (rad/s) about its inertial frame's ``z``
(its pole): Earth at ``EARTH_OMEGA`` in the ECI of the mission epoch, the Moon
and Mars at their IAU rates in their own frames (the parameters' ``P_SPIN``).
A point's local east, north and up (the ellipsoid's normal) follow from its
geodetic latitude and longitude on the body's ellipsoid (WGS84 about Earth);
the ground and the air turn with the body, so the velocity relative to them
is ``v - omega x r`` and the velocity the aerodynamics see ``v - omega x r - w``
with ``w`` the wind (docs/physics.md#frames). All vectors in the inertial
frame's axes, m and m/s.
"""

import math

import numpy as np

from rocketsim.jit import njit
from rocketsim.constants import DEG, EARTH_OMEGA, EARTH_RADIUS_EQ, EARTH_RADIUS_POLAR
from rocketsim.frames.quaternion import rotate_components
from rocketsim.layout import Q, R, V
from rocketsim.frames.geodetic import ecef_to_geodetic_njit, enu_basis, geodetic_on

_STILL = (0.0, 0.0, 0.0)     # no wind (m/s): a tuple, typed as a constant in the kernels

# sin(pitch) above which the nose counts as vertical (within 0.01 deg): heading
# and roll are then read from body z instead
VERTICAL = math.cos(0.01 * DEG)


@njit(inline="always")     # a few operations: typed in its callers, no kernel of its own
def _air_velocity(rx, ry, vx, vy, vz, wind, spin):
    """``v - omega x r - wind`` as a 3-tuple (see :func:`air_velocity`)."""
    return vx + spin * ry - wind[0], vy - spin * rx - wind[1], vz - wind[2]


@njit
def air_velocity(r, v, wind, spin=EARTH_OMEGA):
    """``v - omega x r - wind`` (m/s, frame axes) for position ``r`` (m) and velocity
    ``v`` (m/s), ``omega = (0, 0, spin)`` the central body's rotation (rad/s; Earth's
    by default)."""
    out = np.empty(3)
    out[0], out[1], out[2] = _air_velocity(r[0], r[1], v[0], v[1], v[2], wind, spin)
    return out


@njit(inline="always")     # small: typed in its callers, no kernel of its own
def air_velocity_inertial(y, wind, spin):
    """Air-relative velocity of the centre of mass of state ``y`` (:mod:`rocketsim.layout`;
    m/s, frame axes, a 3-tuple): ``v - omega x r - wind``, ``wind`` inertial (m/s), the air
    turning with the central body at ``spin`` (rad/s about the frame's z: ``p[P_SPIN]``)."""
    return _air_velocity(y[R], y[R + 1], y[V], y[V + 1], y[V + 2], wind, spin)


@njit(borrows=True)
def body_air_velocity(y, wind, spin):
    """Air-relative velocity of the centre of mass (m/s) in body axes:
    ``q* (v - omega x r - wind) q`` (docs/physics.md#equations-of-motion), arguments as
    :func:`air_velocity_inertial`'s."""
    ax, ay, az = air_velocity_inertial(y, wind, spin)
    return rotate_components(y[Q], -y[Q + 1], -y[Q + 2], -y[Q + 3], ax, ay, az)


@njit(inline="always")     # a few operations: typed in its callers, no kernel of its own
def turned(x, y, angle):
    """``R3(angle) (x, y)``: components in axes turned by ``angle`` (rad) about z, in
    the order of :func:`rocketsim.frames.earth_fixed.eci_to_ecef` (the same bits)."""
    c = math.cos(angle)
    s = math.sin(angle)
    return c * x + s * y, -s * x + c * y


@njit
def where_and_how_fast(r, v, t, spin=EARTH_OMEGA, a=EARTH_RADIUS_EQ, b=EARTH_RADIUS_POLAR):
    """One compiled call for the readings every step needs: ``(lat rad, lon rad, height
    m, enu, surface velocity)`` of the position ``r`` (m) and velocity ``v`` (m/s) in the
    central body's inertial frame at mission time ``t`` (s), on the central body's
    ellipsoid (equatorial radius ``a``, polar ``b``, m: ``p[P_RADIUS]``,
    ``p[P_POLAR_RADIUS]``; WGS84 by default) turning at ``spin`` (rad/s about the frame's
    z, the body's pole: ``p[P_SPIN]``; Earth's by default). ``enu`` (3, 3) has the local
    east, north and up (the ellipsoid's normal) unit vectors in the frame's axes as rows;
    the surface velocity (m/s, same axes) is relative to the turning ground. Both are
    views of one array (:func:`where_into`)."""
    both = np.empty(12)
    lat, lon, h = where_into(both, 0, r, v, t, spin, a, b)
    return lat, lon, h, both[:9].reshape((3, 3)), both[9:]


@njit(inline="always")     # typed in its callers: its numbers go to their array, none made
def where_into(out, at, r, v, t, spin, a, b):
    """:func:`where_and_how_fast` into the float64 array ``out``: the rows of ``enu`` in
    ``out[at:at + 9]``, the surface velocity in ``out[at + 9:at + 12]``; returns ``(lat rad,
    lon rad, height m)``. About Earth, geodetic over WGS84 with the same operations, in
    the same order, as :func:`~rocketsim.frames.earth_fixed.eci_to_ecef`,
    :func:`~rocketsim.frames.geodetic.ecef_to_geodetic`,
    :func:`~rocketsim.frames.geodetic.enu_basis` turned back (``ecef_to_eci``) and
    :func:`air_velocity` with no wind; elsewhere the longitude is counted from the
    frame's x turned by ``spin t``, not from the IAU prime meridian (the local axes and
    the surface velocity do not depend on it;
    :func:`rocketsim.dynamics.central.planetocentric` gives the body's own latitude and
    longitude)."""
    theta = 0.0 + spin * t
    x, y = turned(r[0], r[1], theta)
    if a == EARTH_RADIUS_EQ and b == EARTH_RADIUS_POLAR:
        lat, lon, h = ecef_to_geodetic_njit(x, y, r[2])
    else:
        lat, lon, h = geodetic_on(x, y, r[2], a, b)
    basis = enu_basis(lat, lon)
    for k in range(3):
        out[at + 3 * k], out[at + 3 * k + 1] = turned(basis[k, 0], basis[k, 1], -theta)
        out[at + 3 * k + 2] = basis[k, 2]
    # the air velocity with no wind: the surface velocity
    out[at + 9], out[at + 10], out[at + 11] = _air_velocity(r[0], r[1], v[0], v[1], v[2], _STILL, spin)
    return lat, lon, h
