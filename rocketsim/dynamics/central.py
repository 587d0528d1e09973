"""Which body a flying body falls about, and the handover from one to the next.

A body that flies in the n-body field (a mission with ``gravity: n-body``)
carries its field in its parameters (:func:`rocketsim.dynamics.third_bodies.with_field`):
the central body's point mass and J2, and the Sun, Earth, Moon and Mars as
other bodies. Crossing a sphere of influence (:mod:`rocketsim.dynamics.soi`)
re-centres the frame on the new body with its IAU pole as ``z``
(:func:`recentre`): position and velocity are the same vectors seen from the
new centre in the new axes, the attitude quaternion (body -> frame) is turned
by the same change of axes, the body rates (body axes) and everything else
are untouched.
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np

from rocketsim.atmosphere.mars import mars_table
from rocketsim.atmosphere.table import make_table
from rocketsim.dynamics.nbody import FIELD_CENTER, FIELD_ROT, make_field
from rocketsim.bodies.orientation import BODIES as ORIENTED, pole_and_meridian
from rocketsim.dynamics.soi import (_ORBIT, CENTRAL, CHILDREN, SOI, central_body, central_params,
                                   frame_rotation, handover)
from rocketsim.layout import Q, R, V
from rocketsim.dynamics.third_bodies import bodies_at, field_of, with_field
from rocketsim.ephemeris.solar_system import BODIES
from rocketsim.frames.quaternion import quat_from_matrix, quat_multiply

# |r| (m) from a centre beyond which a handover is possible: its own sphere, or
# half the orbital radius of the nearest child (the Moon comes no closer to Earth
# than 356 000 km, so nothing can enter its 66 000 km sphere within 192 000 km)
WATCH_RADIUS = {name: min([SOI[name]] + [0.5 * _ORBIT[child][0] for child in CHILDREN[name]])
                for name in BODIES}


def nbody_field(center: str, jd0_tt: float, gmst0: float, jd_tt_now: float | None = None) -> np.ndarray:
    """The full field (Sun, Earth, Moon, Mars) about ``center`` in its frame: Earth's
    ECI of the mission epoch (``gmst0``, rad) or the IAU-pole frame fixed at
    ``jd_tt_now`` (TT Julian date; default: mission time 0)."""
    jd = jd0_tt if jd_tt_now is None else jd_tt_now
    return make_field(center, jd0_tt, rotation=frame_rotation(center, jd, gmst0))


def next_center(y, p, t: float) -> str | None:
    """The body whose sphere of influence ``y`` (frame of ``p``'s field) has entered
    or fallen back into at mission time ``t`` (s), or None while it stays put.
    Cheap while the body is well inside its centre's sphere and far from any child."""
    fp = field_of(p)
    if fp is None:
        return None
    center = BODIES[int(fp[FIELD_CENTER])]
    r = y[R:R + 3]
    if math.sqrt(r @ r) < WATCH_RADIUS[center]:
        return None
    new = central_body(r, fp, t)
    return None if new == center else new


def recentre(y, p, t: float, new: str, gmst0: float):
    """``(y, p)`` re-centred on ``new`` at mission time ``t`` (s): position,
    velocity and attitude in the new frame (:func:`rocketsim.dynamics.soi.handover`),
    the parameters' central gravity and field the new body's. ``y`` and ``p``
    are not modified."""
    fp = field_of(p)
    r, v, fp_new = handover(y[R:R + 3], y[V:V + 3], fp, t, new, gmst0)
    turn = fp_new[FIELD_ROT:FIELD_ROT + 9].reshape(3, 3).T @ fp[FIELD_ROT:FIELD_ROT + 9].reshape(3, 3)
    out = np.array(y, dtype=float)
    out[R:R + 3] = r
    out[V:V + 3] = v
    q = quat_multiply(quat_from_matrix(turn), out[Q:Q + 4])
    out[Q:Q + 4] = q / np.linalg.norm(q)
    return out, with_field(central_params(p, new), fp_new)


def to_frame(r, v, p_from, p_to, t: float):
    """Position (m) and velocity (m/s) in the frame of ``p_from``'s field re-expressed
    in the frame of ``p_to``'s (both carrying fields) at mission time ``t`` (s)."""
    fa, fb = field_of(p_from), field_of(p_to)
    s, u = bodies_at(fa, t)
    j = int(fb[FIELD_CENTER])
    rot = fb[FIELD_ROT:FIELD_ROT + 9].reshape(3, 3).T @ fa[FIELD_ROT:FIELD_ROT + 9].reshape(3, 3)
    return rot @ (np.asarray(r, float) - s[j]), rot @ (np.asarray(v, float) - u[j])


def air_about(center: str, earth_air):
    """The :class:`~rocketsim.atmosphere.table.AtmosphereTable` a body flies through
    about ``center``: the day's (``earth_air``) about Earth, the Mars reference
    atmosphere about Mars, none (zero density and pressure) elsewhere."""
    if center == "earth":
        return earth_air
    if center == "mars":
        return _mars_air()
    return _NO_AIR


def planetocentric(r, center: str, jd_tt: float):
    """``(latitude rad, longitude rad, height m)`` of ``r`` (m, the IAU-pole frame of
    ``center``, :func:`rocketsim.dynamics.soi.frame_rotation`) at the TT Julian date
    ``jd_tt``: planetocentric latitude, east longitude from the prime meridian
    (``W`` of the IAU rotation, measured from the frame's ``x``, the node of the
    body's equator) and the height over its ellipsoid along the radius. About
    the Sun (no meridian) the longitude is measured from the frame's ``x``."""
    # the Sun has no IAU prime meridian here: longitude is read from the frame's x axis
    w = pole_and_meridian(center, jd_tt)[2] if center in ORIENTED else 0.0
    x, y, z = (float(c) for c in r)
    rn = math.sqrt(x * x + y * y + z * z)
    a, b = CENTRAL[center][1], CENTRAL[center][3]
    s = z / rn
    height = rn - a * b / math.sqrt(b * b * (1.0 - s * s) + a * a * s * s)
    lon = math.remainder(math.atan2(y, x) - float(w), 2.0 * math.pi)
    return math.asin(s), lon, height


@lru_cache(maxsize=1)
def _mars_air():
    return mars_table()


_NO_AIR = make_table(0.0, 1.0e6, np.zeros(2), np.zeros(2), np.zeros(2), np.ones(2), np.zeros(2))
