"""The ``weather:`` section of a scenario, and the day's atmosphere table it gives.

One of five kinds, chosen by ``kind``::

    weather: {kind: standard}                       # US Standard Atmosphere 1976, calm
    weather: {kind: sounding, file: soundings/72357_OUN_20110522_12Z.txt}
    weather:                                        # or the same columns inline
      kind: sounding
      columns: {PRES: [966, 925, 850], HGHT: [345, 720, 1454], TEMP: [22.2, 20.4, 22.0]}
    weather: {kind: random, seed: 7}                # a seeded random day
    weather: {kind: classic, surface_temperature: "31 C"}   # standard shifted to the day
    weather: {kind: reanalysis, file: era5_day.nc}  # ERA5/GFS pressure levels (NetCDF)

A sounding ``file`` is resolved relative to the scenario (or weather) file;
``.csv`` and ``.yaml`` files carry the Wyoming columns by name (see
:mod:`rocketsim.atmosphere.sounding`), anything else is read as the
University of Wyoming text listing. A reanalysis ``file`` (resolved the same
way) is taken at the site and the mission's epoch
(:mod:`rocketsim.atmosphere.reanalysis`).
"""

from __future__ import annotations

import datetime as dt
import math
from pathlib import Path
from typing import TYPE_CHECKING, Annotated, Literal, Optional, Union

from pydantic import BaseModel, Field, RootModel, model_validator

from rocketsim.constants import USSA_P0
from rocketsim.errors import InputError
from rocketsim.limits import MAX_SEED
from rocketsim.scenario.units import STRICT, Pressure, Temperature
from rocketsim.scenario.validation import validate
from rocketsim.scenario.yaml_source import read_yaml

if TYPE_CHECKING:       # the atmosphere's modules (numpy) load when a table is built, so that
    from rocketsim.atmosphere.table import AtmosphereTable    # validating a file stays light


class _Weather(BaseModel):
    model_config = STRICT


class StandardWeather(_Weather):
    """The 1976 standard atmosphere, no wind."""

    kind: Literal["standard"]


class SoundingWeather(_Weather):
    """A measured profile: a file, or the Wyoming columns written inline."""

    kind: Literal["sounding"]
    file: Optional[str] = Field(None, description="sounding file, relative to this file")
    columns: Optional[dict[str, list[Optional[float]]]] = Field(
        None, description="Wyoming columns by name (PRES hPa, HGHT m, TEMP C, ...)")

    @model_validator(mode="after")
    def _one_source(self) -> "SoundingWeather":
        if (self.file is None) == (self.columns is None):
            raise ValueError("give exactly one of 'file' and 'columns'")
        if self.columns is not None:
            from rocketsim.atmosphere.sounding import COLUMNS, from_columns
            unknown = [name for name in self.columns if name.upper() not in COLUMNS]
            if unknown:
                raise ValueError(f"unknown column {unknown[0]!r} (known: {', '.join(COLUMNS)})")
            try:        # the sounding's own checks (lengths, plausible values), here where
                from_columns(self.column_values(), None, prefix="columns.")   # the file is known
            except InputError as error:
                raise ValueError(f"{error.field}: {error.message}" if error.field else error.message) from None
        return self

    def column_values(self) -> dict[str, list[float]]:
        """The inline columns by upper-case name, a blank (None) as nan."""
        return {k.upper(): [float("nan") if v is None else v for v in values]
                for k, values in self.columns.items()}


class RandomWeather(_Weather):
    """A seeded random day (same seed, same day)."""

    kind: Literal["random"]
    seed: int = Field(ge=0, le=MAX_SEED, description="seed of the day's random streams (0 .. 2^64 - 1)")


class ClassicWeather(_Weather):
    """A classic-range day: the standard atmosphere shifted by the day's surface temperature."""

    kind: Literal["classic"]
    surface_temperature: Annotated[Temperature, Field(gt=180.0, lt=340.0)] = Field(
        description="sea-level temperature of the day (e.g. '31 C' or 304.15)")
    surface_pressure: Annotated[Pressure, Field(gt=85_000.0, lt=110_000.0)] = Field(
        USSA_P0, description="sea-level pressure of the day")


class ReanalysisWeather(_Weather):
    """A reanalysis or forecast on pressure levels (ERA5, GFS NetCDF), taken at the launch
    site and the mission's epoch."""

    kind: Literal["reanalysis"]
    file: str = Field(description="NetCDF file, relative to this file")


Weather = Annotated[Union[StandardWeather, SoundingWeather, RandomWeather, ClassicWeather,
                          ReanalysisWeather], Field(discriminator="kind")]


class WeatherFile(RootModel[Weather]):
    """A weather YAML file on its own: the ``weather:`` mapping at top level."""


KINDS = {"standard": StandardWeather, "sounding": SoundingWeather, "random": RandomWeather,
         "classic": ClassicWeather, "reanalysis": ReanalysisWeather}


def load_weather(path):
    """Read and validate a weather YAML file (or the source of one already read, as
    overrides left it); errors name the file, line and field.

    The model of the file's ``kind`` validates it directly, so error locations
    carry no union tag and point at the line of the offending field.
    """
    source = read_yaml(Path(path)) if isinstance(path, (str, Path)) else path
    kind = source.data.get("kind") if isinstance(source.data, dict) else None
    if isinstance(kind, str) and kind in KINDS:
        return validate(source, KINDS[kind])
    return validate(source, WeatherFile).root


def build_atmosphere(weather: Weather, site_latitude: float, base_dir: str | Path,
                     standard_gravity: bool = False, site_longitude: float | None = None,
                     epoch: dt.datetime | None = None) -> "AtmosphereTable":
    """The day's 50 m :class:`AtmosphereTable` for ``weather`` at geodetic ``site_latitude``
    (rad); a sounding or reanalysis ``file`` is resolved relative to ``base_dir``.
    ``standard_gravity``: the classic range's hydrostatics
    (:func:`~rocketsim.atmosphere.day.profile_table`). A reanalysis is taken at
    ``site_longitude`` (rad, east) and the UTC instant ``epoch``, both needed for it."""
    from rocketsim.atmosphere.day import classic_profile, profile_table, standard_table
    from rocketsim.atmosphere.random_day import random_profile
    from rocketsim.atmosphere.sounding import from_columns, read_sounding

    if isinstance(weather, WeatherFile):
        weather = weather.root
    if isinstance(weather, StandardWeather):
        return standard_table()
    if isinstance(weather, ReanalysisWeather):
        if site_longitude is None or epoch is None:
            raise InputError("a reanalysis weather is taken at the launch site's longitude "
                             "and the mission's epoch: give both (rocketsim atmosphere: "
                             "--longitude, --epoch)", field="weather")
        from rocketsim.atmosphere.reanalysis import read_reanalysis
        profile = read_reanalysis(Path(base_dir) / weather.file, math.degrees(site_latitude),
                                  math.degrees(site_longitude), epoch).sounding()
    elif isinstance(weather, SoundingWeather):
        if weather.file is not None:
            profile = read_sounding(Path(base_dir) / weather.file)
        else:
            profile = from_columns(weather.column_values(), None, prefix="weather.columns.")
    elif isinstance(weather, RandomWeather):
        profile = random_profile(weather.seed, site_latitude)
    else:
        profile = classic_profile(weather.surface_temperature, weather.surface_pressure)
    return profile_table(profile, site_latitude, standard_gravity)
