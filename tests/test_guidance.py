"""The compiled guidance predictor (rocketsim.flight.guidance) against independent references.

The falling stage's predictor: in a vacuum without J2 it lands where the Kepler conic
meets the ellipsoid (rocketsim.flight.impact, itself checked against the reference
integrator in tests/test_impact.py); with drag against DOP853 on the same rotating-frame
equations; with the landing burn it stops the fall at the ground.
"""

import math

import numpy as np
from scipy.integrate import solve_ivp

from rocketsim.bodies.gravity import point_mass_j2
from rocketsim.constants import (DEG, EARTH_J2, EARTH_MU, EARTH_OMEGA, EARTH_RADIUS_EQ,
                                 EARTH_RADIUS_POLAR)
from rocketsim.flight.guidance import descent_point
from rocketsim.flight.impact import predict_impact
from rocketsim.frames.earth_fixed import eci_to_ecef
from rocketsim.frames.geodetic import enu_basis, geodetic_to_ecef
from rocketsim.vehicle.contact import point_height


def ecef_state(lat_deg, lon_deg, height, speed, elevation_deg, heading_deg):
    """Earth-fixed position and velocity (m, m/s) of a point moving over the ground."""
    lat, lon = lat_deg * DEG, lon_deg * DEG
    east, north, up = enu_basis(lat, lon)
    el, hd = elevation_deg * DEG, heading_deg * DEG
    d = math.cos(el) * (math.sin(hd) * east + math.cos(hd) * north) + math.sin(el) * up
    return geodetic_to_ecef(lat, lon, height), speed * d


def test_a_vacuum_fall_without_j2_lands_where_the_kepler_conic_meets_the_ground():
    r, v = ecef_state(28.5, -80.5, 90e3, 1800.0, -20.0, 250.0)
    # at mission time 0 the ECI and Earth-fixed axes coincide: ECI velocity = v + w x r
    v_eci = v + np.cross([0.0, 0.0, EARTH_OMEGA], r)
    impact = predict_impact(r, v_eci, 0.0, EARTH_MU)
    expected = eci_to_ecef(impact.position, impact.time)
    point = descent_point(*r, *v, 1800.0, 0.0, 2.0, 0.0, 7200.0, 8e3, 0.5, 0.5, 0.0)
    assert np.linalg.norm(np.array(point) - expected) < 5.0            # m, over a ~2 min fall


def test_a_fall_through_the_air_matches_the_reference_integrator():
    r, v = ecef_state(28.5, -80.5, 60e3, 1200.0, -60.0, 250.0)
    ballistic, rho0, scale = 1800.0, 1.225, 7200.0

    def rhs(t, s):
        x, y, z, vx, vy, vz = s
        gx, gy, gz = point_mass_j2(x, y, z, EARTH_MU, EARTH_RADIUS_EQ, EARTH_J2)
        h = point_height(x, y, z, EARTH_RADIUS_EQ, EARTH_RADIUS_POLAR)
        k = rho0 * math.exp(-max(h, 0.0) / scale) * math.sqrt(vx * vx + vy * vy + vz * vz) / (2 * ballistic)
        w = EARTH_OMEGA
        return (vx, vy, vz, gx + 2 * w * vy + w * w * x - k * vx, gy - 2 * w * vx + w * w * y - k * vy,
                gz - k * vz)

    def ground(t, s):
        return point_height(s[0], s[1], s[2], EARTH_RADIUS_EQ, EARTH_RADIUS_POLAR)
    ground.terminal, ground.direction = True, -1
    sol = solve_ivp(rhs, (0.0, 1e4), (*r, *v), method="DOP853", rtol=1e-11, atol=1e-6, events=ground)
    expected = sol.y_events[0][0][:3]
    errors = [np.linalg.norm(np.array(descent_point(*r, *v, ballistic, 0.0, step, rho0, scale, 8e3,
                                                    0.5, 0.5, EARTH_J2)) - expected)
              for step in (2.0, 1.0, 0.5)]
    assert errors[0] < 6.0 and errors[2] < 0.5       # m: a few metres at the 2 s step the programs use,
    assert 3.0 < errors[0] / errors[1] < 5.0         # converging at second order


def test_the_landing_burn_stops_the_fall_at_the_ground():
    r, v = ecef_state(28.5, -80.5, 9e3, 280.0, -85.0, 250.0)
    x, y, z = descent_point(*r, *v, 1800.0, 25.0, 2.0, 1.225, 7200.0, 8e3, 0.5, 0.5, EARTH_J2)
    height = point_height(x, y, z, EARTH_RADIUS_EQ, EARTH_RADIUS_POLAR)
    assert 0.0 <= height < 3.0                       # m: slowed to 0.5 m/s just above the ground
    no_burn = descent_point(*r, *v, 1800.0, 0.0, 2.0, 1.225, 7200.0, 8e3, 0.5, 0.5, EARTH_J2)
    # braking along the velocity keeps the stage near its line: within ~100 m of the unbraked point
    assert np.linalg.norm(np.array((x, y, z)) - np.array(no_burn)) < 300.0
