"""The day's air tabulated every 50 m, and the compiled lookup the flight loop calls.

:class:`AtmosphereTable` holds numpy float64 arrays on a uniform grid of
geometric height above the reference surface (the WGS84 ellipsoid on Earth,
the reference sphere on Mars), ``h = h0 + i * dh``, from the lowest height the
day needs to :data:`TOP` (600 km, where the flight model's air ends).

Interpolation is linear in every quantity. Density and pressure fall
exponentially, so linear interpolation over a row overestimates by at most
``(dh / H)^2 / 8`` of the value for a scale height ``H``: with 50 m rows and
``H >= 5.5 km`` anywhere below 600 km that is below 1.1e-5, well under the
model's own accuracy, and it costs no ``exp``/``log`` per lookup (the
log-linear alternative needs three transcendental calls). Where the profile
itself has a kink (the standard's layer bases, a sounding's levels) the row
across it is off by up to ``dh/4`` times the change of gradient: 3.75e-4 of
temperature and density at the 11 km tropopause, the worst case.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rocketsim.jit import njit
from rocketsim.frames.geodetic import enu_basis

STEP = 50.0                 # m, the table's row spacing
TOP = 600_000.0             # m, the flight model sees no air above this height


@dataclass(frozen=True)
class AtmosphereTable:
    """The air of one day on a uniform height grid (SI units, arrays of float64).

    ``h0`` (m) is the height of row 0 and ``dh`` (m) the row spacing; winds are
    the east and north components (m/s) of the air's velocity relative to the
    rotating ground (the direction it blows *to*).
    """

    h0: float
    dh: float
    density: np.ndarray          # kg/m^3
    pressure: np.ndarray         # Pa
    temperature: np.ndarray      # K
    speed_of_sound: np.ndarray   # m/s
    viscosity: np.ndarray        # Pa s
    wind_east: np.ndarray        # m/s
    wind_north: np.ndarray       # m/s

    @property
    def heights(self) -> np.ndarray:
        """Height of every row (m)."""
        return self.h0 + self.dh * np.arange(len(self.density))

    @property
    def has_wind(self) -> bool:
        """True when any row has a non-zero wind."""
        return bool(np.any(self.wind_east != 0.0) or np.any(self.wind_north != 0.0))

    def arrays(self):
        """The arguments of :func:`air_at` before the height, in order."""
        return (float(self.h0), float(self.dh), self.density, self.pressure, self.temperature,
                self.speed_of_sound, self.wind_east, self.wind_north)

    def at(self, h):
        """Vectorised lookup: six arrays (see :func:`air_at`) at heights ``h`` (m)."""
        heights = np.ascontiguousarray(np.atleast_1d(np.asarray(h, dtype=np.float64)).ravel())
        return air_at_many(*self.arrays(), heights)


def make_table(h0, dh, density, pressure, temperature, speed_of_sound, viscosity,
               wind_east=None, wind_north=None) -> AtmosphereTable:
    """Build a table from row arrays (copied to contiguous float64, read-only).

    Parameters
    ----------
    h0 : float
        Height of row 0 above the reference surface, m.
    dh : float
        Row spacing, m.
    density, pressure, temperature, speed_of_sound, viscosity : array
        One value per row: kg/m^3, Pa, K, m/s, Pa s.
    wind_east, wind_north : array, optional
        The air's velocity over the ground per row, m/s, towards east and north
        (calm when omitted).
    """
    def frozen(a):
        a = np.ascontiguousarray(a, dtype=np.float64).copy()
        a.setflags(write=False)
        return a
    zeros = np.zeros(len(density))
    return AtmosphereTable(float(h0), float(dh), frozen(density), frozen(pressure),
                           frozen(temperature), frozen(speed_of_sound), frozen(viscosity),
                           frozen(zeros if wind_east is None else wind_east),
                           frozen(zeros if wind_north is None else wind_north))


def grid(h_low: float, top: float = TOP, dh: float = STEP) -> np.ndarray:
    """Row heights from ``h_low`` (rounded down to a multiple of ``dh``) to ``top`` (m)."""
    h0 = np.floor(h_low / dh) * dh
    return h0 + dh * np.arange(int(round((top - h0) / dh)) + 1)


@njit
def air_at(h0, dh, density, pressure, temperature, speed_of_sound, wind_east, wind_north, h):
    """The air at height ``h`` (m) from a table: (density kg/m^3, pressure Pa,
    temperature K, speed of sound m/s, wind east m/s, wind north m/s).

    Linear interpolation between rows; below row 0 the first row is returned
    (clamped); above 600 km density and pressure are zero (no air for the
    flight model) and the other quantities are those of the top row. A NaN
    height gives NaNs.
    """
    n = density.shape[0]
    x = (h - h0) / dh
    if x != x:
        return np.nan, np.nan, np.nan, np.nan, np.nan, np.nan
    if x <= 0.0:
        return (density[0], pressure[0], temperature[0], speed_of_sound[0],
                wind_east[0], wind_north[0])
    if h > TOP or x >= n - 1:
        k = n - 1
        rho = density[k] if h <= TOP else 0.0
        p = pressure[k] if h <= TOP else 0.0
        return rho, p, temperature[k], speed_of_sound[k], wind_east[k], wind_north[k]
    i = int(x)
    f = x - i
    g = 1.0 - f
    return (g * density[i] + f * density[i + 1], g * pressure[i] + f * pressure[i + 1],
            g * temperature[i] + f * temperature[i + 1],
            g * speed_of_sound[i] + f * speed_of_sound[i + 1],
            g * wind_east[i] + f * wind_east[i + 1], g * wind_north[i] + f * wind_north[i + 1])


@njit(borrows=True)
def air_in(air, h):
    """:func:`air_at` of the table ``air``: the tuple of
    :meth:`AtmosphereTable.arrays` (what a vehicle carries as its ``air``)."""
    return air_at(air[0], air[1], air[2], air[3], air[4], air[5], air[6], air[7], h)


@njit
def air_at_many(h0, dh, density, pressure, temperature, speed_of_sound, wind_east, wind_north,
                heights):
    """:func:`air_at` for an array of heights: six arrays shaped like ``heights``."""
    out = np.empty((6, heights.shape[0]))
    for j in range(heights.shape[0]):
        out[0, j], out[1, j], out[2, j], out[3, j], out[4, j], out[5, j] = air_at(
            h0, dh, density, pressure, temperature, speed_of_sound, wind_east, wind_north,
            heights[j])
    return out[0], out[1], out[2], out[3], out[4], out[5]


@njit
def wind_earth_fixed(wind_east, wind_north, lat, lon):
    """The wind (m/s) as an Earth-fixed vector, from its east and north components at
    geodetic ``lat`` and ``lon`` (rad) (the air moves horizontally: no vertical part)."""
    basis = enu_basis(lat, lon)
    return wind_east * basis[0] + wind_north * basis[1]
