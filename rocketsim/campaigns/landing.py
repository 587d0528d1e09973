"""How and where a campaign's bodies came down: the landing outcome, the east/north
scatter about the target, its covariance ellipses, the circles that hold a share of the
points, and GeoJSON of them.

**Outcomes.** From a body's events (docs/physics.md#ground-contact: the checks that
report touchdown, tip-over, impact and breakup; the engines' dry flag), the first that
applies of:

* ``broke up``: a ``breakup`` event (its bending or axial load beyond the structure's);
* ``tipped over``: it touched down, then leaned past the tilt at which its centre of mass
  left the footprint of its feet (``tip-over``);
* ``ran dry``: it hit the ground (``impact``) after a stage of it ran out of usable
  propellant (``stage_dry``, or ``MECO``/``SECO`` for a vehicle's first/second stage);
* ``impact``: it hit the ground (a first contact faster than the 10 m/s the legs take,
  or no legs);
* ``under a parachute``: it touched down under a canopy (the touchdown carries a drift
  time);
* ``hard landing``: it touched down and stayed up, but faster than HARD_VERTICAL_SPEED
  down or HARD_HORIZONTAL_SPEED sideways (this report's limits: a Falcon 9 booster
  touches down at 1-2 m/s; beyond 3 m/s the legs' shock absorbers are taken as
  damaged, and a stage sliding 2 m/s on its feet as one that needs no tip-over to be
  lost);
* ``upright on target``: touched down softly within ON_TARGET_RADIUS (horizontal, from
  the centre of mass to the mission's pad, or the launch site);
* ``upright off target``: touched down softly farther away.

No outcome (None) for a body that neither came down nor broke up.

**Offsets.** A landing point (geodetic latitude/longitude, degrees, WGS84) and the target
(the mission's pad, else the launch site) both stand on the ellipsoid (height 0); the
point's east and north (m) are the components of the Earth-fixed difference along the
target's local east and north (:func:`rocketsim.frames.geodetic.enu_basis`: the local
frame of docs/physics.md#frames).
The up component (about ``-d^2 / 2R``: 8 m at 10 km) is left out: a map of the scatter is
the tangent plane's.

**Ellipses.** The points' mean ``m`` and covariance ``C`` (``ddof=1``) fit a bivariate
normal; the ellipse ``(x - m)^T C^-1 (x - m) = k^2`` holds the share ``P`` of that
normal for ``k^2 = -2 ln(1 - P)``: the squared Mahalanobis distance of a 2-D normal is
chi-square with 2 degrees of freedom, whose CDF is ``1 - exp(-k^2 / 2)``. Its semi-axes
are ``k sqrt(lambda)`` for the eigenvalues ``lambda`` of ``C``. The 50/90/99 % ellipses
have ``k`` = 1.177, 2.146, 3.035. Scaling by the 1-D sigmas instead (``k`` = 1, 2, 3, as
RocketPy's Monte Carlo plots label their 1/2/3-sigma ellipses) draws ellipses that hold
39.3, 86.5 and 98.9 % of a 2-D normal, not 68.3/95.4/99.7 %. The ellipses are those of the
fitted normal, not prediction regions for a further run (which a few dozen runs widen by
the F quantile); :class:`Dispersion` also gives the share of the points each one holds, so a
scatter that is not normal shows.

**Circles.** ``R_P`` is the smallest radius about a centre that holds at least the share
``P`` of the points (the ``ceil(P n)``-th smallest distance: ``numpy.quantile``'s
``inverted_cdf``), about the target (the accuracy a pad sees: a CEP when ``P = 0.5``) and
about the mean (the precision of the scatter). For a circular normal about the centre
``R_50 = sigma sqrt(2 ln 2)`` (the median of the Rayleigh distribution).

docs/physics.md#campaign-statistics gives the tests that check all of this.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from rocketsim.constants import DEG
from rocketsim.frames.geodetic import ecef_to_geodetic, enu_basis, geodetic_to_ecef

ON_TARGET_RADIUS = 10.0                # m: "on target"
HARD_VERTICAL_SPEED = 3.0              # m/s down at the first contact: a hard landing beyond
HARD_HORIZONTAL_SPEED = 2.0            # m/s sideways at the first contact: likewise
UPRIGHT = ("upright on target", "upright off target", "hard landing")
OUTCOMES = (*UPRIGHT, "tipped over", "impact", "ran dry", "broke up", "under a parachute")
DRY_EVENTS = ("stage_dry", "MECO", "SECO")
PROBABILITIES = (0.5, 0.9, 0.99)       # of the ellipses and the circles
OUTLINE_POINTS = 180                   # vertices of a drawn or exported ellipse (area 0.02 % short)
_INVERSE_PASSES = 20                   # corrections at most, of geodetic_of (8 at 1000 km)
_INVERSE_TOLERANCE = 1e-6              # m, of geodetic_of's round trip
_DECIMALS = 9                          # of GeoJSON degrees: 1e-9 deg is 0.1 mm


def landing_outcome(events: dict) -> str | None:
    """The body's landing outcome (see the module) from its ``events``: event name ->
    ``(time s, figures)`` of the first event of that name."""
    if "breakup" in events:
        return "broke up"
    if "tip-over" in events:
        return "tipped over"
    if "impact" in events:
        down = events["impact"][0]
        dry = any(name in events and events[name][0] <= down for name in DRY_EVENTS)
        return "ran dry" if dry else "impact"
    if "touchdown" not in events:
        return None
    figures = events["touchdown"][1]
    if "drift_time_s" in figures:
        return "under a parachute"
    vertical = abs(float(figures.get("vertical_speed_m_s", 0.0)))
    horizontal = float(figures.get("horizontal_speed_m_s", 0.0))
    if vertical > HARD_VERTICAL_SPEED or horizontal > HARD_HORIZONTAL_SPEED:
        return "hard landing"
    distance = figures.get("distance_to_target_m")
    return "upright on target" if distance is not None and distance <= ON_TARGET_RADIUS else "upright off target"


def east_north(latitude_deg, longitude_deg, target_latitude_deg: float, target_longitude_deg: float):
    """``(east, north)`` (m) of the points ``latitude_deg``, ``longitude_deg`` (geodetic,
    degrees; scalars or arrays broadcast together) about the target, all on the WGS84
    ellipsoid (see the module)."""
    lat0, lon0 = target_latitude_deg * DEG, target_longitude_deg * DEG
    offset = (geodetic_to_ecef(np.asarray(latitude_deg, dtype=float) * DEG,
                               np.asarray(longitude_deg, dtype=float) * DEG, 0.0)
              - geodetic_to_ecef(lat0, lon0, 0.0))
    basis = enu_basis(lat0, lon0)
    return offset @ basis[0], offset @ basis[1]


def geodetic_of(east, north, target_latitude_deg: float, target_longitude_deg: float):
    """``(latitude_deg, longitude_deg)`` of the points on the ellipsoid whose
    :func:`east_north` about the target is ``(east, north)`` (m; arrays or scalars): the
    geodetic coordinates of the tangent-plane point, corrected by the residual of the
    forward conversion until it is below 1 um (a pass shrinks it by about ``(d / R)^2``:
    one correction at 10 km, three at 100 km, eight at 1000 km)."""
    east = np.asarray(east, dtype=float)
    north = np.asarray(north, dtype=float)
    shape = np.broadcast_shapes(east.shape, north.shape)
    east, north = np.broadcast_to(east, shape).ravel(), np.broadcast_to(north, shape).ravel()
    lat0, lon0 = target_latitude_deg * DEG, target_longitude_deg * DEG
    origin = geodetic_to_ecef(lat0, lon0, 0.0)
    basis = enu_basis(lat0, lon0)
    e, n = east.copy(), north.copy()
    for _ in range(_INVERSE_PASSES):
        lat, lon, _ = ecef_to_geodetic(origin + e[:, None] * basis[0] + n[:, None] * basis[1])
        lat, lon = np.atleast_1d(lat) / DEG, np.atleast_1d(lon) / DEG
        fe, fn = east_north(lat, lon, target_latitude_deg, target_longitude_deg)
        if east.size == 0 or max(np.abs(east - fe).max(), np.abs(north - fn).max()) < _INVERSE_TOLERANCE:
            break
        e += east - fe
        n += north - fn
    return lat.reshape(shape), lon.reshape(shape)


def ellipse_scale(probability: float) -> float:
    """``k``: the Mahalanobis radius of the ellipse that holds ``probability`` of a 2-D
    normal, ``sqrt(-2 ln(1 - P))`` (the chi-square quantile with 2 degrees of freedom)."""
    return math.sqrt(-2.0 * math.log1p(-probability))


def _outline(east: float, north: float, a: float, b: float, azimuth_deg: float, points: int):
    """``(east, north)`` arrays of ``points + 1`` vertices (the last repeats the first) of
    the ellipse with centre ``(east, north)``, semi-axes ``a`` along the azimuth (degrees
    clockwise from north) and ``b`` across it, counterclockwise seen from above."""
    t = np.linspace(0.0, 2.0 * np.pi, points, endpoint=False)
    ue, un = math.sin(azimuth_deg * DEG), math.cos(azimuth_deg * DEG)   # major axis
    ve, vn = -un, ue                                                     # a quarter turn left of it
    e = east + a * np.cos(t) * ue + b * np.sin(t) * ve
    n = north + a * np.cos(t) * un + b * np.sin(t) * vn
    return np.append(e, e[0]), np.append(n, n[0])


@dataclass(frozen=True)
class Ellipse:
    """The covariance ellipse holding ``probability`` of the fitted normal: centre
    (``east_m``, ``north_m``) about the target, semi-axes (m), the major axis's azimuth
    (degrees clockwise from north, 0..180) and ``share`` (the share of the points inside)."""

    probability: float
    east_m: float
    north_m: float
    semi_major_m: float
    semi_minor_m: float
    azimuth_deg: float
    share: float

    def outline(self, points: int = OUTLINE_POINTS):
        """``(east, north)`` (m) of a closed counterclockwise ring of ``points`` vertices."""
        return _outline(self.east_m, self.north_m, self.semi_major_m, self.semi_minor_m,
                        self.azimuth_deg, points)


@dataclass(frozen=True)
class Circle:
    """The smallest circle about ``about`` (``"target"`` or ``"mean"``, centre
    ``east_m``, ``north_m`` about the target) holding at least ``probability`` of the
    points: radius ``radius_m``."""

    probability: float
    about: str
    east_m: float
    north_m: float
    radius_m: float

    def outline(self, points: int = OUTLINE_POINTS):
        """``(east, north)`` (m) of a closed counterclockwise ring of ``points`` vertices."""
        return _outline(self.east_m, self.north_m, self.radius_m, self.radius_m, 0.0, points)


def covariance_ellipse(mean, covariance, probability: float) -> tuple[float, float, float]:
    """``(semi_major, semi_minor, azimuth_deg)`` of the ellipse holding ``probability`` of the
    2-D normal of ``mean`` (east, north) and ``covariance`` (2 x 2, m^2)."""
    values, vectors = np.linalg.eigh(np.asarray(covariance, dtype=float))   # ascending
    k = ellipse_scale(probability)
    major, minor = np.sqrt(np.clip(values[::-1], 0.0, None))
    azimuth = math.degrees(math.atan2(vectors[0, 1], vectors[1, 1])) % 180.0
    return k * float(major), k * float(minor), azimuth


def radius_containing(distances, probability: float) -> float:
    """The smallest radius holding at least ``probability`` of the ``distances`` (m)."""
    return float(np.quantile(np.asarray(distances, dtype=float), probability, method="inverted_cdf"))


@dataclass(frozen=True)
class Dispersion:
    """One body's landing points about the target and their figures (see the module).

    ``east_m``, ``north_m`` (n,) the points (m); ``kinds`` (n,) how each came down
    (``touchdown``/``impact``); ``mean`` (2,) and ``covariance`` (2, 2) east-north, m and
    m²; ``ellipses`` one per probability (none below three points); ``circles`` about the
    target, then about the mean, one per probability each."""

    body: str
    east_m: np.ndarray
    north_m: np.ndarray
    kinds: tuple
    mean: np.ndarray
    covariance: np.ndarray
    ellipses: tuple[Ellipse, ...] = field(default=())
    circles: tuple[Circle, ...] = field(default=())

    @property
    def n(self) -> int:
        return int(self.east_m.size)


def dispersion(body: str, east, north, kinds=None, probabilities=PROBABILITIES) -> Dispersion:
    """The :class:`Dispersion` of the points ``east``, ``north`` (m about the target)."""
    east = np.asarray(east, dtype=float)
    north = np.asarray(north, dtype=float)
    kinds = tuple(kinds) if kinds is not None else ("",) * east.size
    points = np.stack([east, north], axis=1)
    n = east.size
    mean = points.mean(axis=0) if n else np.full(2, np.nan)
    covariance = np.cov(points, rowvar=False) if n > 1 else np.full((2, 2), np.nan)
    ellipses = []
    if n >= 3:
        deviation = points - mean
        try:
            inverse = np.linalg.inv(covariance)
            mahalanobis2 = np.einsum("ij,jk,ik->i", deviation, inverse, deviation)
        except np.linalg.LinAlgError:               # all points on a line: no inside
            mahalanobis2 = np.full(n, np.inf)
        for p in probabilities:
            a, b, azimuth = covariance_ellipse(mean, covariance, p)
            share = float(np.mean(mahalanobis2 <= ellipse_scale(p) ** 2))
            ellipses.append(Ellipse(p, float(mean[0]), float(mean[1]), a, b, azimuth, share))
    circles = []
    if n:
        for about, centre in (("target", np.zeros(2)), ("mean", mean)):
            distances = np.hypot(east - centre[0], north - centre[1])
            circles += [Circle(p, about, float(centre[0]), float(centre[1]), radius_containing(distances, p))
                        for p in probabilities]
    return Dispersion(body, east, north, kinds, mean, covariance, tuple(ellipses), tuple(circles))


def _ring(east, north, target) -> list:
    lat, lon = geodetic_of(east, north, target["latitude_deg"], target["longitude_deg"])
    return [[round(float(x), _DECIMALS), round(float(y), _DECIMALS)] for x, y in zip(lon, lat)]


def _feature(geometry: dict, properties: dict) -> dict:
    return {"type": "Feature", "geometry": geometry, "properties": properties}


def geojson(target: dict, dispersions) -> dict:
    """A GeoJSON FeatureCollection (RFC 7946: WGS84 longitude, latitude in degrees; rings
    closed and counterclockwise) of the target (a Point, with the ``target`` mapping's
    ``name`` and ``kind``) and, for each :class:`Dispersion`, its landing points (a
    MultiPoint), its mean (a Point), its ellipses and circles (Polygons) with their figures
    as properties; an ellipse or circle of no area (points all on a line or on one spot) has
    no polygon. A ring that crosses the antimeridian is not split."""
    features = [_feature({"type": "Point", "coordinates": [target["longitude_deg"], target["latitude_deg"]]},
                         {"feature": "target", "name": target.get("name"), "kind": target.get("kind")})]
    for d in dispersions:
        if not d.n:
            continue
        features.append(_feature({"type": "MultiPoint", "coordinates": _ring(d.east_m, d.north_m, target)},
                                 {"feature": "landings", "body": d.body, "count": d.n}))
        features.append(_feature({"type": "Point", "coordinates": _ring(d.mean[:1], d.mean[1:], target)[0]},
                                 {"feature": "mean", "body": d.body, "east_m": float(d.mean[0]),
                                  "north_m": float(d.mean[1])}))
        for e in (e for e in d.ellipses if e.semi_minor_m > 0.0):
            features.append(_feature({"type": "Polygon", "coordinates": [_ring(*e.outline(), target)]},
                                     {"feature": "ellipse", "body": d.body, "probability": e.probability,
                                      "semi_major_m": e.semi_major_m, "semi_minor_m": e.semi_minor_m,
                                      "azimuth_deg": e.azimuth_deg, "share_of_points": e.share}))
        for c in (c for c in d.circles if c.radius_m > 0.0):
            features.append(_feature({"type": "Polygon", "coordinates": [_ring(*c.outline(), target)]},
                                     {"feature": "circle", "body": d.body, "probability": c.probability,
                                      "about": c.about, "radius_m": c.radius_m}))
    return {"type": "FeatureCollection", "features": features}
