"""The air against height, of a day on Earth or of Mars: what ``rocketsim atmosphere``
prints and draws.

Earth's air is the US Standard Atmosphere 1976 by default, or a weather file's day
(``kind: standard | sounding | random | classic | reanalysis``,
:func:`rocketsim.scenario.weather.build_atmosphere`); Mars has one mean atmosphere
(:func:`rocketsim.atmosphere.mars.mars_table`). Heights are geometric, m, above the
reference ellipsoid (Earth) or sphere (Mars); the tables stop at 600 km, where the
flight model sees no air.
"""

from __future__ import annotations

import datetime as dt
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

COLUMNS = ("height_m", "temperature_K", "pressure_Pa", "density_kg_m3", "speed_of_sound_m_s")
WIND = ("wind_east_m_s", "wind_north_m_s")


@dataclass
class AirProfile:
    """The air at each height: ``columns`` by name (:data:`COLUMNS`, then :data:`WIND`
    when the day has wind), arrays of one length; ``name`` says whose air it is."""

    name: str
    columns: dict[str, np.ndarray]

    @property
    def has_wind(self) -> bool:
        return WIND[0] in self.columns


def atmosphere(heights, *, weather: str | Path | None = None, body: str = "earth",
               latitude: float = math.radians(45.0), longitude: float = 0.0,
               epoch: dt.datetime | None = None) -> AirProfile:
    """The :class:`AirProfile` at ``heights`` (m) of ``body`` (``"earth"`` or ``"mars"``):
    on Earth the day of the ``weather`` file (None: US Standard 1976) at the site's
    geodetic ``latitude`` and east ``longitude`` (rad; gravity, a random day, a
    reanalysis) and, for a reanalysis, the UTC instant ``epoch``."""
    table, name = _air(body, weather, latitude, longitude, epoch)
    heights = np.asarray(heights, dtype=float)
    rho, p, t, a, we, wn = table.at(heights)
    values = [heights, t, p, rho, a] + ([we, wn] if table.has_wind else [])
    return AirProfile(name, dict(zip(COLUMNS + (WIND if table.has_wind else ()), values)))


def _air(body: str, weather, latitude: float, longitude: float, epoch):
    """The air table of ``body`` (on Earth, of the ``weather`` file's day) and its name."""
    if body == "mars":
        if weather is not None:
            raise ValueError("a weather file is for Earth; Mars has one mean atmosphere")
        from rocketsim.atmosphere.mars import mars_table
        return mars_table(), "Mars"
    if body != "earth":
        raise ValueError(f"no atmosphere for {body!r}: 'earth' or 'mars'")
    from rocketsim.scenario.weather import StandardWeather, build_atmosphere, load_weather
    if weather is None:
        return build_atmosphere(StandardWeather(kind="standard"), latitude, "."), "US Standard 1976"
    table = build_atmosphere(load_weather(weather), latitude, Path(weather).resolve().parent,
                             site_longitude=longitude, epoch=epoch)
    return table, str(weather)
