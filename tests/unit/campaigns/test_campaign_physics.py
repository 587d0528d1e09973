"""A campaign's spread against the analytic one: a vacuum arc dispersed in launch speed
and elevation.

Reference: the flat-Earth vacuum range of a projectile launched at speed ``v`` and
elevation ``theta`` in uniform gravity ``g``, ``R = v^2 sin(2 theta) / g``, with
``dR/dv = 2 v sin(2 theta) / g`` and ``dR/dtheta = 2 v^2 cos(2 theta) / g``; for small
independent normal dispersions ``sigma_v``, ``sigma_theta`` the range's standard
deviation is ``sqrt((dR/dv sigma_v)^2 + (dR/dtheta sigma_theta)^2)`` (first order;
the second-order terms add 0.1 % to the variance here).

The scenario's start takes the release velocity's components (east, north,
up), so the campaign disperses the north and up components as correlated normals
with the covariance ``J diag(sigma_v^2, sigma_theta^2) J^T`` that the speed and
elevation dispersions give them to first order (``J`` the Jacobian of
``(v cos theta, v sin theta)``): the same law to the order the reference holds.

``g`` is WGS84's normal gravity at the site's latitude on the ellipsoid
(Somigliana's formula with the WGS84 constants, NIMA TR8350.2 eq. 4-1:
gravity and the centrifugal acceleration of the rotating ground, which the
simulator's point-mass-plus-J2 field and rotating ground reproduce to about
1e-4). The arc is short (about 1 km, 19 s) so that the Earth's curvature
(a 0.08 m drop over the range) and the Coriolis acceleration (2 Omega v ~ 0.015
m/s^2 against 9.8) change the derivatives by less than 0.2 %, far inside the
sampling error. The range is measured to the impact point (pymap3d's geodetic ->
east-north-up, a peer implementation), recorded where the arc crosses the ground
(:mod:`rocketsim.sim.ground_crossing`, to a fraction of a millimetre in vacuum).

The bound: the sample standard deviation of N = 200 runs within the two-sided
99 % chi-square interval of the prediction, ``sigma^2 chi2(0.005 | 0.995, N - 1) / (N - 1)``
(about +-13 %); leaving the elevation's term out would be 32 % low.
"""

from __future__ import annotations

import math

import numpy as np
import pymap3d
import rocketsim
from scipy import stats

from tests.campaign_files import ELEVATION, LATITUDE, SPEED, write_arc

N = 200
SIGMA_V = 1.0                   # m/s
SIGMA_THETA = math.radians(1.0)


def somigliana(latitude_deg: float) -> float:
    """WGS84 normal gravity on the ellipsoid (m/s^2), NIMA TR8350.2 eq. 4-1."""
    s2 = math.sin(math.radians(latitude_deg)) ** 2
    return 9.7803253359 * (1 + 0.00193185265241 * s2) / math.sqrt(1 - 0.00669437999013 * s2)


def test_range_spread_of_a_vacuum_arc_is_the_linearised_prediction(tmp_path):
    v, theta = SPEED, ELEVATION
    jacobian = np.array([[math.cos(theta), -v * math.sin(theta)],
                         [math.sin(theta), v * math.cos(theta)]])
    covariance = jacobian @ np.diag([SIGMA_V ** 2, SIGMA_THETA ** 2]) @ jacobian.T
    rows = ", ".join(f"[{float(a)!r}, {float(b)!r}]" for a, b in covariance)
    campaign = write_arc(tmp_path, f"""\
        name: arc-spread
        scenario: arc.yaml
        runs: {N}
        seed: 3
        dispersions:
          v_north: {{path: "mission.start.site.velocity[1]", kind: normal}}
          v_up: {{path: "mission.start.site.velocity[2]", kind: normal}}
        correlations:
          - {{names: [v_north, v_up], covariance: [{rows}]}}
        """)
    results = rocketsim.campaign(campaign, tmp_path / "out", workers=1)
    assert (results["status"] == "ok").all()
    east, north, _ = pymap3d.geodetic2enu(results["slug.landing.latitude_deg"].to_numpy(),
                                          results["slug.landing.longitude_deg"].to_numpy(), 0.0,
                                          LATITUDE, -106.9, 0.0)
    ranges = np.hypot(east, north)
    g = somigliana(LATITUDE)
    predicted = math.hypot(2 * v * math.sin(2 * theta) / g * SIGMA_V,
                           2 * v * v * math.cos(2 * theta) / g * SIGMA_THETA)
    lo, hi = np.sqrt(stats.chi2.ppf([0.005, 0.995], N - 1) / (N - 1))
    measured = ranges.std(ddof=1)
    assert lo < measured / predicted < hi, (measured, predicted)
    # and the arc is the reference's: the mean range within 4 standard errors of
    # v^2 sin(2 theta) / g
    nominal = v * v * math.sin(2 * theta) / g
    assert abs(ranges.mean() - nominal) < 4 * predicted / math.sqrt(N)
