"""A seeded random day: tropopause, sea-level pressure, surface temperature, humidity, wind.

``random_profile(seed, latitude)`` draws a synthetic sounding (geometric
heights, sea level to 20 km, every 250 m) that :func:`.day.profile_table`
turns into the day's table (hydrostatic pressure, blend into the standard
atmosphere above 20 km). Each quantity has its own ``numpy.random.Generator``
stream spawned from the seed, so adding a quantity never changes another's
draws; the same seed and latitude give the same day, bit for bit.

The distributions are simple climatological approximations chosen for this
simulator (not fitted to a dataset); their spreads are the documented range
of days a test can expect:

====================  ==============================================  =================
quantity              distribution                                    why
====================  ==============================================  =================
tropopause height     N(16.5 km - 7.5 km sin^2(lat), 0.75 km),        ~16.5 km tropics,
                      clipped to +-3 sigma                            ~9 km polar
sea-level pressure    N(1013.25 hPa, 10 hPa), clipped to +-3 sigma    synoptic spread
surface temperature   N(300 K - 45 K sin^2(lat), 6 K), +-3 sigma      annual-mean zonal
tropopause temp.      N(195 K + 25 K sin^2(lat), 4 K), +-3 sigma      ~195 K tropics,
                                                                      ~220 K polar
surface rel. humidity U(20 %, 95 %), falling as exp(-z / 3 km)        boundary layer
surface wind          Rayleigh(3 m/s), from U(0, 360°)                light to fresh
jet stream            U(10, 60) m/s at the tropopause, Gaussian of    westerlies aloft
                      4 km half-width, from 270° + N(0, 30°)
====================  ==============================================  =================

The temperature falls linearly from the surface to the tropopause (the lapse
rate follows, about 6.4 K/km in the tropics, 5.5 at 45°) and stays constant
above it to 20 km.
"""

from __future__ import annotations

import numpy as np

from rocketsim.atmosphere.sounding import (Sounding, mixing_ratio_from_vapour,
                                           saturation_vapour_pressure)
from rocketsim.constants import CELSIUS_ZERO, USSA_P0

QUANTITIES = ("tropopause", "pressure", "temperature", "tropopause_temperature", "humidity",
              "wind")
TOP = 20_000.0                # m, top of the synthetic profile
SPREADS = {                   # the documented spreads (1 sigma, or range)
    "tropopause_sigma": 750.0, "pressure_sigma": 1000.0, "temperature_sigma": 6.0,
    "tropopause_temperature_sigma": 4.0, "humidity_range": (0.20, 0.95),
    "surface_wind_scale": 3.0, "jet_range": (10.0, 60.0), "jet_direction_sigma": np.radians(30.0),
}


def streams(seed: int) -> dict[str, np.random.Generator]:
    """One independent generator per quantity, spawned from ``seed``."""
    children = np.random.SeedSequence(seed).spawn(len(QUANTITIES))
    return {name: np.random.default_rng(child) for name, child in zip(QUANTITIES, children)}


def _clipped_normal(rng, mean, sigma):
    return mean + sigma * float(np.clip(rng.standard_normal(), -3.0, 3.0))


def random_profile(seed: int, latitude: float) -> Sounding:
    """The synthetic sounding of day ``seed`` at geodetic ``latitude`` (rad)."""
    rng = streams(seed)
    s2 = np.sin(latitude) ** 2
    tropopause = _clipped_normal(rng["tropopause"], 16_500.0 - 7_500.0 * s2,
                                 SPREADS["tropopause_sigma"])
    p_sl = _clipped_normal(rng["pressure"], USSA_P0, SPREADS["pressure_sigma"])
    t_sl = _clipped_normal(rng["temperature"], 300.0 - 45.0 * s2, SPREADS["temperature_sigma"])
    t_tp = _clipped_normal(rng["tropopause_temperature"], 195.0 + 25.0 * s2,
                           SPREADS["tropopause_temperature_sigma"])
    rh0 = rng["humidity"].uniform(*SPREADS["humidity_range"])
    wind = rng["wind"]
    surface_speed = wind.rayleigh(SPREADS["surface_wind_scale"])
    surface_from = wind.uniform(0.0, 2 * np.pi)
    jet_speed = wind.uniform(*SPREADS["jet_range"])
    jet_from = 1.5 * np.pi + SPREADS["jet_direction_sigma"] * wind.standard_normal()

    z = np.arange(0.0, TOP + 1.0, 250.0)
    t = t_sl + (t_tp - t_sl) * np.minimum(z, tropopause) / tropopause
    # A rough column pressure only for the humidity conversion (the table integrates its own).
    p_hpa = p_sl / 100.0 * np.exp(-z / 8_000.0)
    e = rh0 * np.exp(-z / 3_000.0) * saturation_vapour_pressure(t - CELSIUS_ZERO)
    w = mixing_ratio_from_vapour(e, p_hpa)
    base = surface_speed + (jet_speed - surface_speed) * np.clip(z / tropopause, 0.0, 1.0) * 0.3
    speed = base + (jet_speed - base) * np.exp(-(((z - tropopause) / 4_000.0) ** 2))
    turn = np.angle(np.exp(1j * (jet_from - surface_from)))      # shortest way round
    x = np.clip(z / tropopause, 0.0, 1.0)
    direction = np.mod(surface_from + turn * x * x * (3 - 2 * x), 2 * np.pi)
    return Sounding(z, p_hpa * 100.0, t, w, speed, direction, geopotential=False,
                    source=f"random day {seed}")

