"""The day's air: a measured or synthetic profile on top of the 1976 standard, as a 50 m table.

Given a :class:`~rocketsim.atmosphere.sounding.Sounding` (measured, or made
by :mod:`.random_day` or :func:`classic_profile`) and the site's geodetic
latitude, :func:`profile_table` builds the :class:`AtmosphereTable`:

1. Heights. Radiosonde heights are geopotential metres (``g0 = 9.806 65``);
   they become geometric heights above sea level (taken as the ellipsoid)
   with the site's normal gravity, ``Phi = g0 H = integral of g(z) dz``.
2. Temperature, humidity and wind are interpolated linearly in height to the
   top of the profile, or to :data:`BLEND_START_MAX` if it goes higher. Above
   that height ``z_b`` they blend into the standard atmosphere (and into dry,
   calm air) over :data:`BLEND_DEPTH` with a smoothstep weight ``s``:
   ``T = T_std + (T(z_b) - T_std(z_b)) (1 - s)``; the blend is complete by
   31 km at the latest. Below the lowest level the temperature follows the
   standard 6.5 K/km lapse rate; humidity and wind hold their lowest value.
3. Pressure is integrated hydrostatically, up and down, from the lowest
   level's measured pressure: ``d ln p/dz = -g(z) M0 / (R* T_v)`` with the
   virtual temperature ``T_v = T (1 + w/eps) / (1 + w)`` (``w`` mixing ratio)
   and WGS84 normal gravity at the site's latitude falling off as the inverse
   square of the distance from the centre (on the classic range, the 1976
   standard's own gravity instead: ``standard_gravity``). Between 80 and 86 km the
   standard's ``M/M0`` enters through its molecular-scale temperature.
4. Above 86 km the air is the standard's, with pressure and density scaled by
   the day's-to-standard pressure ratio at 86 km (continuous there).
5. Wind speed and the direction it blows from become east and north
   components of the velocity of the air (the Earth-fixed frame's local
   east-north axes at the site).
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np

from rocketsim.atmosphere.hydrostatic import hermite, integrate_log_pressure
from rocketsim.atmosphere.sounding import Sounding
from rocketsim.atmosphere.table import STEP, AtmosphereTable, grid, make_table
from rocketsim.atmosphere.ussa1976 import LAPSE, Z_86, sutherland_viscosity, us_standard_1976
from rocketsim.atmosphere.ussa1976 import standard_gravity as ussa_gravity
from rocketsim.constants import (EARTH_RADIUS_EQ, EARTH_RADIUS_POLAR, G0, GAS_CONSTANT_USSA,
                                 USSA_GAMMA, USSA_M0, USSA_P0, USSA_R0, WATER_AIR_MOLAR_RATIO)
from rocketsim.frames.geodetic import normal_gravity

BLEND_DEPTH = 5_000.0          # m, depth of the blend into the standard atmosphere
BLEND_START_MAX = 26_000.0     # m, data above this is not used: the blend ends by 31 km
LOWEST = -500.0                # m, every table reaches at least this far down
STANDARD_LAPSE = -float(LAPSE[0])   # K/m, extrapolation below the lowest level (standard layer 0)


def geocentric_radius(lat):
    """Distance (m) from the Earth's centre to the WGS84 ellipsoid at geodetic ``lat`` (rad)."""
    a, b = EARTH_RADIUS_EQ, EARTH_RADIUS_POLAR
    c, s = np.cos(lat), np.sin(lat)
    return float(np.sqrt(((a * a * c) ** 2 + (b * b * s) ** 2) / ((a * c) ** 2 + (b * s) ** 2)))


def gravity(z, lat):
    """Gravity (m/s^2) at height ``z`` (m) over the ellipsoid at latitude ``lat`` (rad):
    Somigliana normal gravity on the ellipsoid times ``(r / (r + z))^2``."""
    r = geocentric_radius(lat)
    return normal_gravity(lat) * (r / (r + np.asarray(z, dtype=float))) ** 2


def geometric_from_geopotential(h_gp, lat):
    """Geometric height (m) of geopotential height ``h_gp`` (m', g0 = 9.806 65) at ``lat`` (rad).

    Inverts ``g0 H = gamma r z / (r + z)`` (the integral of :func:`gravity`).
    """
    r = geocentric_radius(lat)
    k = G0 * np.asarray(h_gp, dtype=float) / normal_gravity(lat)
    return r * k / (r - k)


def smoothstep(x):
    """0 below 0, 1 above 1, ``3x^2 - 2x^3`` between (continuous slope)."""
    x = np.clip(x, 0.0, 1.0)
    return x * x * (3.0 - 2.0 * x)


@lru_cache(maxsize=4)
def standard_table(h_low: float = LOWEST) -> AtmosphereTable:
    """The 1976 standard atmosphere, no wind, every 50 m from ``h_low`` to 600 km.

    Built once per ``h_low`` and shared: the table is immutable
    (a frozen dataclass of read-only arrays)."""
    z = grid(min(h_low, LOWEST))
    air = us_standard_1976(z)
    return make_table(z[0], STEP, air.density, air.pressure, air.temperature,
                      air.speed_of_sound, air.viscosity)


def _profile_on(z, sounding, z_data, z_b):
    """Temperature, molecular-scale virtual temperature, wind east/north at heights z."""
    inside = np.clip(z, z_data[0], z_b)
    t = np.interp(inside, z_data, sounding.temperature)
    w = np.interp(inside, z_data, sounding.mixing_ratio)
    speed = np.interp(inside, z_data, sounding.wind_speed)
    sx = np.interp(inside, z_data, np.sin(sounding.wind_from))
    cx = np.interp(inside, z_data, np.cos(sounding.wind_from))
    below = z < z_data[0]
    t = np.where(below, sounding.temperature[0] + STANDARD_LAPSE * (z_data[0] - z), t)
    std = us_standard_1976(np.clip(z, -5_000.0, 1_000_000.0))
    t_b = np.interp(z_b, z_data, sounding.temperature)
    t_std_b = float(us_standard_1976(z_b).temperature)
    s = smoothstep((z - z_b) / BLEND_DEPTH)
    above = z > z_b
    t = np.where(above, std.temperature + (t_b - t_std_b) * (1.0 - s), t)
    w = np.where(above, w * (1.0 - s), w)
    speed = np.where(above, speed * (1.0 - s), speed)
    norm = np.hypot(sx, cx)
    norm = np.where(norm > 0.0, norm, 1.0)
    # Wind blowing FROM azimuth d moves the air toward d + 180°.
    east, north = -speed * sx / norm, -speed * cx / norm
    t_virtual = t * (1.0 + w / WATER_AIR_MOLAR_RATIO) / (1.0 + w)
    # Molecular-scale: include the standard's M/M0 (1 below 80 km) above the blend.
    t_vm = t_virtual * USSA_M0 / std.molar_mass
    return t, t_vm, east, north


def profile_table(sounding: Sounding, latitude: float, standard_gravity: bool = False
                  ) -> AtmosphereTable:
    """The day's :class:`AtmosphereTable` from a profile at geodetic ``latitude`` (rad).

    ``standard_gravity``: the classic range's hydrostatics (docs/physics.md#classic-range;
    real sites use WGS84 normal gravity at the site's latitude):
    ``g = g0 (r0 / (r0 + z))^2`` with the 1976
    standard's ``r0`` (its eq. 17) in place of :func:`gravity`, so a classic
    day's pressure follows the standard's own barometric law.
    """
    if standard_gravity:
        r0 = USSA_R0
        z_data = (r0 * np.asarray(sounding.height, dtype=float)
                  / (r0 - np.asarray(sounding.height, dtype=float)) if sounding.geopotential
                  else np.asarray(sounding.height, dtype=float))
    else:
        z_data = (geometric_from_geopotential(sounding.height, latitude) if sounding.geopotential
                  else np.asarray(sounding.height, dtype=float))
    z_b = min(float(z_data[-1]), BLEND_START_MAX)
    rows = grid(min(float(z_data[0]) - 500.0, LOWEST))
    low = rows[rows <= Z_86]
    half = np.arange(2 * len(low) - 1) * (STEP / 2.0) + low[0]   # rows and midpoints
    _, t_vm, _, _ = _profile_on(half, sounding, z_data, z_b)
    g = ussa_gravity(half) if standard_gravity else gravity(half, latitude)
    rate = -g * USSA_M0 / (GAS_CONSTANT_USSA * t_vm)
    log_p = integrate_log_pressure(low, rate[::2], rate[1::2], 0.0)
    # Anchor at the lowest level: ln p there equals the measured pressure.
    log_p += np.log(sounding.pressure[0]) - hermite(low, log_p, rate[::2], z_data[0])
    p_low = np.exp(log_p)

    t, t_vm_rows, east, north = _profile_on(rows, sounding, z_data, z_b)
    std = us_standard_1976(rows)
    ratio = p_low[-1] / std.pressure[len(low) - 1]
    upper = rows > Z_86
    pressure = np.concatenate((p_low, std.pressure[upper] * ratio))
    density = np.where(upper, std.density * ratio,
                       pressure * USSA_M0 / (GAS_CONSTANT_USSA * t_vm_rows))
    sound = np.where(upper, std.speed_of_sound,
                     np.sqrt(USSA_GAMMA * GAS_CONSTANT_USSA * t_vm_rows / USSA_M0))
    return make_table(rows[0], STEP, density, pressure, t, sound, sutherland_viscosity(t),
                      east, north)


def classic_profile(surface_temperature: float, surface_pressure: float = USSA_P0,
                    top: float = 11_000.0) -> Sounding:
    """A classic-range day: the standard atmosphere shifted by ``surface_temperature - 288.15 K``
    from sea level to ``top`` (the standard tropopause), blending back above it; dry, calm."""
    z = np.arange(0.0, top + 1.0, 250.0)
    shift = surface_temperature - float(us_standard_1976(0.0).temperature)
    t = us_standard_1976(z).temperature + shift
    # Only the surface pressure is used (hydrostatics does the rest); fill the column with the
    # standard's pressures so the profile is a valid sounding.
    p = us_standard_1976(z).pressure * (surface_pressure / USSA_P0)
    zeros = np.zeros_like(z)
    return Sounding(z, p, t, zeros, zeros, zeros, geopotential=False, source="classic")
