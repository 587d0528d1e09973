"""Spheres of influence and the handover between central bodies.

docs/physics.md#spheres-of-influence: ``r_SOI = a (mu / mu_parent)^(2/5)`` (Laplace), with ``a``
the body's orbital semi-major axis about its parent (Earth and Mars about
the Sun, the Moon about Earth). Crossing one re-centres the frame on the new
body with its IAU pole as ``z`` (docs/physics.md#frames); nothing else
changes: position and velocity are the same vectors, expressed from the new
centre in the new axes.

Frames (rotation matrix frame -> J2000 equatorial, :func:`frame_rotation`):

- Earth: the mission's ECI, J2000 turned about its pole by the Greenwich
  mean sidereal time of the epoch (``r_J2000 = R_z(GMST0) r_ECI``);
- Moon and Mars: ``z`` the IAU pole at the handover instant, ``x`` the
  ascending node of the body's equator on the J2000 equator (the IAU
  rotation with ``W = 0``), held fixed afterwards: the frame is inertial;
- Sun: J2000 equatorial itself.
"""

from __future__ import annotations

import math

import numpy as np

from rocketsim.bodies.orientation import pole_and_meridian, spin_rate
from rocketsim.constants import (EARTH_J2, EARTH_MU, EARTH_OMEGA, EARTH_ORBIT_A, EARTH_RADIUS_EQ,
                                 EARTH_RADIUS_POLAR, MARS_FLATTENING, MARS_J2, MARS_MU,
                                 MARS_ORBIT_A, MARS_RADIUS_EQ, MOON_J2, MOON_MU, MOON_ORBIT_A,
                                 MOON_RADIUS, SECONDS_PER_DAY, SUN_MU, SUN_RADIUS)
from rocketsim.dynamics.nbody import FIELD_CENTER, FIELD_JD0, FIELD_ROT, bodies_at
from rocketsim.layout import P_J2, P_MU, P_POLAR_RADIUS, P_RADIUS, P_SPIN
from rocketsim.ephemeris.solar_system import BODIES

PARENT = {"earth": "sun", "moon": "earth", "mars": "sun"}
_ORBIT = {"earth": (EARTH_ORBIT_A, EARTH_MU, SUN_MU), "moon": (MOON_ORBIT_A, MOON_MU, EARTH_MU),
          "mars": (MARS_ORBIT_A, MARS_MU, SUN_MU)}


def soi_radius(body: str) -> float:
    """Radius (m) of ``body``'s sphere of influence (Laplace); the Sun's is infinite."""
    if body == "sun":
        return math.inf
    a, mu, mu_parent = _ORBIT[body]
    return a * (mu / mu_parent) ** 0.4


SOI = {name: soi_radius(name) for name in BODIES}
SOI_BY_INDEX = np.array([SOI[name] for name in BODIES])
# the bodies whose SOI lies inside each body's (its children)
CHILDREN = {"sun": ("earth", "mars"), "earth": ("moon",), "moon": (), "mars": ()}


# mu (m^3/s^2), reference radius (m), J2, polar radius (m) and rotation rate about the
# frame's z (rad/s) of each central body: Earth's WGS84 rate, the Moon's and Mars's IAU
# W rate (their frames' z is their pole); none for the Sun (its frame's z is J2000's)
CENTRAL = {"sun": (SUN_MU, SUN_RADIUS, 0.0, SUN_RADIUS, 0.0),
           "earth": (EARTH_MU, EARTH_RADIUS_EQ, EARTH_J2, EARTH_RADIUS_POLAR, EARTH_OMEGA),
           "moon": (MOON_MU, MOON_RADIUS, MOON_J2, MOON_RADIUS, spin_rate("moon")),
           "mars": (MARS_MU, MARS_RADIUS_EQ, MARS_J2, MARS_RADIUS_EQ * (1.0 - MARS_FLATTENING),
                    spin_rate("mars"))}


def central_params(p, body: str) -> np.ndarray:
    """A copy of the parameter vector ``p`` with ``body``'s gravity and rotation as the centre's."""
    out = np.array(p, dtype=float)
    out[P_MU], out[P_RADIUS], out[P_J2], out[P_POLAR_RADIUS], out[P_SPIN] = CENTRAL[body]
    return out


def frame_rotation(body: str, jd_tt: float, gmst0: float = 0.0) -> np.ndarray:
    """Rotation matrix (3, 3) taking ``body``-centred frame axes to J2000.

    ``jd_tt``: TT Julian date of the handover (fixes the Moon's or Mars's
    pole); ``gmst0``: GMST (rad) of the mission epoch, for Earth's ECI.
    """
    if body == "sun":
        return np.eye(3)
    if body == "earth":
        c, s = math.cos(gmst0), math.sin(gmst0)
        return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
    alpha, delta, _ = pole_and_meridian(body, jd_tt)
    ca, sa = math.cos(alpha), math.sin(alpha)
    cd, sd = math.cos(delta), math.sin(delta)
    # R3(-(alpha + 90 deg)) R1(-(90 deg - delta)): x the node, z the pole
    return np.array([[-sa, -ca * sd, ca * cd], [ca, -sa * sd, sa * cd], [0.0, cd, sd]])


def central_body(r, fp, t: float) -> str:
    """Name of the body whose sphere of influence holds ``r`` (m, frame of ``fp``) at ``t``.

    Leaving the centre's sphere hands over to its parent; entering a child's
    sphere (the Moon's from Earth, Earth's or Mars's from the Sun) to the child.
    """
    center = BODIES[int(fp[FIELD_CENTER])]
    r = np.asarray(r, dtype=float)
    if np.linalg.norm(r) > SOI[center]:
        return PARENT[center]
    s = bodies_at(np.asarray(fp, dtype=float), t)[0]
    for child in CHILDREN[center]:
        if np.linalg.norm(r - s[BODIES.index(child)]) < SOI[child]:
            return child
    return center


def handover(r, v, fp, t: float, new_center: str, gmst0: float = 0.0):
    """Re-centre a state on ``new_center`` at mission time ``t`` (s).

    ``r``, ``v``: position (m) and velocity (m/s) in the frame of field
    ``fp``. Returns ``(r_new, v_new, fp_new)``: the same state from the new
    centre in its frame (:func:`frame_rotation` at ``t``), and a copy of the
    field about the new centre (same bodies, same SRP).
    """
    fp = np.asarray(fp, dtype=float)
    old_rot = fp[FIELD_ROT:FIELD_ROT + 9].reshape(3, 3)
    jd = fp[FIELD_JD0] + t / SECONDS_PER_DAY
    new_rot = frame_rotation(new_center, jd, gmst0)
    s, u = bodies_at(fp, t)
    j = BODIES.index(new_center)
    # old frame -> J2000, from the new centre, J2000 -> new frame
    r_new = new_rot.T @ (old_rot @ (np.asarray(r, float) - s[j]))
    v_new = new_rot.T @ (old_rot @ (np.asarray(v, float) - u[j]))
    fp_new = fp.copy()
    fp_new[FIELD_CENTER] = j
    fp_new[FIELD_ROT:FIELD_ROT + 9] = new_rot.reshape(9)
    return r_new, v_new, fp_new
