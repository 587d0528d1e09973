"""The state a flight starts from: on a launch site, in orbit, or a state vector.

The inertial frame is the ECI of the mission epoch: ``z`` along Earth's spin
axis, ``x`` through the Greenwich meridian at mission time 0. It is the J2000
equatorial frame turned about its pole by the Greenwich mean sidereal time of
the epoch (precession and nutation ignored), so an orbit's right ascension of
the ascending node, given from the equinox in the mission file, becomes
``raan - GMST(epoch)`` here.

Body axes: ``x`` is the nose (roll axis). On a site the nose points at
``elevation`` above the horizon towards the pad azimuth; ``z`` lies in the same
vertical plane on the ground side of the horizon (for a vertical vehicle it
points along the azimuth, downrange; level, it points down), and
``y = z x x`` completes the right-handed set: roll 0 in
:mod:`rocketsim.flight.readings`.
"""

from __future__ import annotations

import math

import numpy as np

from rocketsim.constants import EARTH_OMEGA
from rocketsim.dynamics.soi import CENTRAL
from rocketsim.frames.earth_fixed import ecef_to_eci_velocity
from rocketsim.frames.elements import Elements, elements_to_state
from rocketsim.frames.mean_elements import mean_to_osculating
from rocketsim.frames.geodetic import enu_basis, geodetic_to_ecef
from rocketsim.frames.quaternion import quat_from_matrix, quat_rotate
from rocketsim.scenario.models import MissionSpec
from rocketsim.scenario.start_spec import SiteSpec
from rocketsim.vehicle.rail import RL_ON, RL_TRAVEL, RL_U, RL_X0, no_rail


def site_attitude(site: SiteSpec, elevation: float, azimuth: float | None = None) -> np.ndarray:
    """Quaternion (body -> ECI at t = 0) of a vehicle on ``site``, nose at ``elevation``
    towards ``azimuth`` (rad from north; default the site's pad azimuth)."""
    east, north, up = enu_basis(site.latitude, site.longitude)
    azimuth = site.pad_azimuth if azimuth is None else azimuth
    heading = math.sin(azimuth) * east + math.cos(azimuth) * north
    nose = math.cos(elevation) * heading + math.sin(elevation) * up
    z_axis = math.sin(elevation) * heading - math.cos(elevation) * up
    y_axis = np.cross(z_axis, nose)
    return _attitude(nose, y_axis, z_axis)


def start_state(mission: MissionSpec, site: SiteSpec | None, gmst0: float):
    """``(r, v, q)`` at mission time 0 in the ECI of the epoch (m, m/s, quaternion)."""
    start = mission.start
    if start.site is not None:
        r = geodetic_to_ecef(site.latitude, site.longitude, site.height)   # ECI = ECEF at t = 0
        east, north, up = enu_basis(site.latitude, site.longitude)
        ground = start.site.velocity
        v_ecef = ground[0] * east + ground[1] * north + ground[2] * up
        v = ecef_to_eci_velocity(r, v_ecef, 0.0)
        rail = start.site.rail
        heading = None if rail is None else rail.heading
        return r, v, site_attitude(site, start.site.nose_elevation, heading)
    if start.orbit is not None:
        orbit = start.orbit
        mu, radius, j2 = CENTRAL[orbit.body][:3]
        a = orbit.semi_major_axis if orbit.altitude is None else radius + orbit.altitude
        node = orbit.raan - gmst0 if orbit.body == "earth" else orbit.raan
        elements = Elements(a, orbit.eccentricity, orbit.inclination, node, orbit.arg_periapsis,
                            orbit.true_anomaly, mu)
        if orbit.elements == "mean":
            elements = mean_to_osculating(elements, radius, j2)
        r, v = elements_to_state(elements.a, elements.e, elements.i, elements.raan, elements.argp,
                                 elements.nu, mu)
        return np.asarray(r), np.asarray(v), prograde_attitude(r, v)
    state = start.state
    r = np.array(state.position, dtype=float)
    v = np.array(state.velocity, dtype=float)
    return r, v, prograde_attitude(r, v)


def _attitude(x_axis, y_axis, z_axis) -> np.ndarray:
    """Quaternion (body -> ECI) of the body axes given in ECI: :func:`quat_from_matrix`
    run as Python (the same operations on float64, so the same bits), not compiled for
    one call per flight (a third of a second of a cold start)."""
    return quat_from_matrix.py_func(np.column_stack((x_axis, y_axis, z_axis)))


def prograde_attitude(r, v) -> np.ndarray:
    """Quaternion with the nose along ``v`` and ``z`` towards the centre (``-r``)."""
    nose = np.asarray(v, dtype=float) / np.linalg.norm(v)
    down = -np.asarray(r, dtype=float)
    z_axis = down - (down @ nose) * nose
    z_axis /= np.linalg.norm(z_axis)
    y_axis = np.cross(z_axis, nose)
    return _attitude(nose, y_axis, z_axis)


def on_rail(site: SiteSpec, rail, q0, x_cm: float):
    """``(r, w, rail array)`` of a vehicle standing on its base at the foot of ``rail``
    (a :class:`~rocketsim.scenario.start_spec.RailSpec`) on ``site``, nose along it (``q0``,
    body -> ECI at t = 0, from :func:`start_state`): its centre of mass ``x_cm`` (m
    above its base) up the rail from the pad, its body rates the ground's turn (so it
    keeps its attitude on the turning Earth), the rail's arrays
    (:mod:`rocketsim.vehicle.rail`)."""
    pad = geodetic_to_ecef(site.latitude, site.longitude, site.height)   # ECI = ECEF at t = 0
    axis = quat_rotate(np.asarray(q0, dtype=float), np.array([1.0, 0.0, 0.0]))
    r = np.asarray(pad, dtype=float) + x_cm * axis
    w = quat_rotate(np.array([q0[0], -q0[1], -q0[2], -q0[3]]), np.array([0.0, 0.0, EARTH_OMEGA]))
    arrays = no_rail()
    arrays[RL_ON], arrays[RL_TRAVEL] = 1.0, rail.length - rail.last_button
    arrays[RL_X0:RL_X0 + 3], arrays[RL_U:RL_U + 3] = r, axis
    return r, w, arrays


def standing_on_ground(r, up, x_cm: float, x_lowest: float) -> np.ndarray:
    """Centre-of-mass position of a vehicle standing upright on the ground point ``r``.

    ``up`` is the local vertical (unit), ``x_cm`` the centre of mass and
    ``x_lowest`` the lowest contact point (legs' feet, or the base), both body-x
    stations (m): the feet touch the ground with the springs unloaded.
    """
    return np.asarray(r, dtype=float) + (x_cm - x_lowest) * np.asarray(up, dtype=float)
