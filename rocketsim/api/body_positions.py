"""Where the Sun, Earth, Moon or Mars is at UTC instants: what ``rocketsim ephemeris``
prints.

Positions and velocities in the J2000 mean equatorial frame from the project's
truncated VSOP87D and ELP2000-82B series (:mod:`rocketsim.ephemeris.solar_system`),
which run on TT; UTC instants become TT through Delta T (Espenak & Meeus,
:class:`rocketsim.timescales.Epoch`).
"""

from __future__ import annotations

import datetime as dt
from dataclasses import dataclass

import numpy as np

from rocketsim.argument_checks import expect, one_of
from rocketsim.constants import AU
from rocketsim.ephemeris.solar_system import BODIES, states
from rocketsim.timescales import Epoch

# the origin of the vectors when none is named: the Sun for the planets, the Earth for
# the Moon and the Sun
DEFAULT_CENTER = {"sun": "earth", "earth": "sun", "mars": "sun", "moon": "earth"}


@dataclass
class BodyPositions:
    """``body`` from ``center`` at each of the instants ``utc``: their TT Julian dates
    ``jd_tt`` (N,), ``position`` (N, 3) m and ``velocity`` (N, 3) m/s, the ``distance``
    (m and ``distance_au``), the ``speed`` (m/s), the distance ``from_earth`` (m) and the
    ``elongation_deg``, the angle Sun-Earth-body (None for the Earth and the Sun)."""

    body: str
    center: str
    utc: list[dt.datetime]
    jd_tt: np.ndarray
    position: np.ndarray
    velocity: np.ndarray
    distance: np.ndarray
    distance_au: np.ndarray
    speed: np.ndarray
    from_earth: np.ndarray
    elongation_deg: np.ndarray | None


def ephemeris(body: str, utc: list[dt.datetime], center: str | None = None) -> BodyPositions:
    """The :class:`BodyPositions` of ``body`` (one of
    :data:`rocketsim.ephemeris.solar_system.BODIES`) from ``center`` (default
    :data:`DEFAULT_CENTER`'s) at the UTC instants ``utc`` (aware datetimes)."""
    one_of(body, BODIES, "body")
    center = center or DEFAULT_CENTER[body]
    one_of(center, BODIES, "center")
    expect(utc, (list, tuple, np.ndarray), "utc", "a list of UTC instants (aware datetimes)")
    for moment in utc:
        expect(moment, (dt.datetime,), "utc", "a list of UTC instants (aware datetimes)")
    jd_tt = np.array([Epoch.from_utc(moment).jd_tt() for moment in utc])
    field = states(jd_tt, center="earth")
    r = field[body][0] - field[center][0]
    v = field[body][1] - field[center][1]
    distance = np.linalg.norm(r, axis=1)
    elongation = (_elongation_deg(field["sun"][0], field[body][0])
                  if body not in ("earth", "sun") else None)
    return BodyPositions(body, center, list(utc), jd_tt, r, v, distance, distance / AU,
                         np.linalg.norm(v, axis=1), np.linalg.norm(field[body][0], axis=1), elongation)


def _elongation_deg(sun: np.ndarray, body: np.ndarray) -> np.ndarray:
    """Angle Sun-Earth-body (deg) from geocentric vectors (N, 3)."""
    cos = np.sum(sun * body, axis=1) / (np.linalg.norm(sun, axis=1) * np.linalg.norm(body, axis=1))
    return np.degrees(np.arccos(np.clip(cos, -1.0, 1.0)))
