"""Reanalysis and forecast weather: ERA5 (and GFS) pressure-level NetCDF at a site and instant.

A reanalysis file holds, on a latitude-longitude grid, at several times and
pressure levels: geopotential (or geopotential height), temperature, the
east (``u``) and north (``v``) wind, and often humidity. :func:`read_reanalysis`
takes the column over a site at an instant:

- **Space**: bilinear in latitude and longitude between the four grid points
  around the site (longitudes 0..360 or -180..180, either order; a global grid
  wraps across its seam).
- **Time**: linear between the two file times that bracket the instant.

Each quantity is interpolated on each pressure level separately (the wind
as its ``u`` and ``v`` components), so the column keeps the file's levels,
each with its interpolated height. ERA5's ``z`` is geopotential (m^2/s^2):
divided by ``g0 = 9.806 65`` it is geopotential height, which
:func:`~rocketsim.atmosphere.day.profile_table` turns into geometric height
with the site's normal gravity, as for radiosondes; GFS files carry
geopotential height directly. Humidity comes from the specific humidity
(``q``, ``w = q / (1 - q)``) when the file has it, else from the relative
humidity (``r``, over water, Bolton 1980), else the air is dry. Above the
top level the day blends into the standard atmosphere as a sounding does.

Names recognised (ERA5 old and new CDS files, GFS/NOAA THREDDS and NOMADS):

==============  ===============================================================
role            names
==============  ===============================================================
time            ``time``, ``valid_time``
level           ``level``, ``pressure_level``, ``isobaric``, ``lev`` (hPa; Pa when
                the unit says so or the values exceed 1 100)
latitude        ``latitude``, ``lat`` (degrees north)
longitude       ``longitude``, ``lon`` (degrees east)
geopotential    ``z`` (m^2/s^2)
geop. height    ``Geopotential_height_isobaric``, ``hgtprs``, ``gh`` (m')
temperature     ``t``, ``Temperature_isobaric``, ``tmpprs`` (K)
wind            ``u``/``v``, ``u-component_of_wind_isobaric``/``v-...``,
                ``ugrdprs``/``vgrdprs`` (m/s)
humidity        ``q``, ``Specific_humidity_isobaric``, ``spfhprs`` (kg/kg);
                ``r``, ``Relative_humidity_isobaric``, ``rhprs`` (%)
==============  ===============================================================

xarray and netCDF4 are imported only when such a file is read.
"""

from __future__ import annotations

import datetime as dt
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from rocketsim.atmosphere.sounding import (Sounding, mixing_ratio_from_vapour,
                                           saturation_vapour_pressure)
from rocketsim.constants import CELSIUS_ZERO, G0
from rocketsim.errors import InputError
from rocketsim.extras import needs

TIME = ("time", "valid_time")
LEVEL = ("level", "pressure_level", "isobaric", "lev")
LATITUDE = ("latitude", "lat")
LONGITUDE = ("longitude", "lon")
GEOPOTENTIAL = ("z",)
GEOPOTENTIAL_HEIGHT = ("Geopotential_height_isobaric", "hgtprs", "gh")
TEMPERATURE = ("t", "Temperature_isobaric", "tmpprs")
U_WIND = ("u", "u-component_of_wind_isobaric", "ugrdprs")
V_WIND = ("v", "v-component_of_wind_isobaric", "vgrdprs")
SPECIFIC_HUMIDITY = ("q", "Specific_humidity_isobaric", "spfhprs")
RELATIVE_HUMIDITY = ("r", "Relative_humidity_isobaric", "rhprs")
SNAP = 1e-9         # a weight this close to 0 or 1 is the grid point itself (deg or fraction)


@dataclass(frozen=True)
class ReanalysisColumn:
    """The column over a site at an instant, one row per pressure level, bottom up (SI):
    pressure (Pa), geopotential height (m', ``g0 = 9.806 65``), temperature (K), the
    air's east and north velocity ``u``, ``v`` (m/s) and the water-vapour mixing ratio
    (kg/kg, zero for a file without humidity)."""

    pressure: np.ndarray
    height: np.ndarray
    temperature: np.ndarray
    u: np.ndarray
    v: np.ndarray
    mixing_ratio: np.ndarray
    source: str = ""

    def sounding(self) -> Sounding:
        """The column as a :class:`Sounding` (wind speed and the direction it blows from)."""
        speed = np.hypot(self.u, self.v)
        # the air moves toward (u, v): it blows from the opposite azimuth
        wind_from = np.mod(np.arctan2(-self.u, -self.v), 2.0 * np.pi)
        return Sounding(self.height, self.pressure, self.temperature, self.mixing_ratio,
                        speed, wind_from, True, self.source)


def _name(names, available):
    """The first of ``names`` the file has, or None."""
    for name in names:
        if name in available:
            return name
    return None


def _required(names, available, path, what):
    name = _name(names, available)
    if name is None:
        raise InputError(f"no {what} in the file (looked for {', '.join(names)}; it has "
                         f"{', '.join(sorted(map(str, available))) or 'nothing'})",
                         file=path, field=names[0])
    return name


def _bracket(grid, x, periodic=False):
    """``[(index, weight), ...]`` of the grid points around ``x`` (``grid`` monotonic, either
    order) for linear interpolation; None when ``x`` is outside. ``periodic``: the grid
    is longitudes covering the whole circle (wraps from its last point to its first)."""
    order = np.argsort(grid, kind="stable")
    g = np.asarray(grid, dtype=float)[order]
    n = len(g)
    if periodic:
        x = g[0] + np.mod(x - g[0], 360.0)
    k = int(np.searchsorted(g, x, side="right")) - 1
    if 0 <= k < n and abs(x - g[k]) <= SNAP:
        return [(int(order[k]), 1.0)]
    if k + 1 < n and abs(g[k + 1] - x) <= SNAP:
        return [(int(order[k + 1]), 1.0)]
    if 0 <= k < n - 1:
        w = (x - g[k]) / (g[k + 1] - g[k])
        return [(int(order[k]), 1.0 - w), (int(order[k + 1]), w)]
    if periodic and k == n - 1:
        w = (x - g[k]) / (g[0] + 360.0 - g[k])
        return [(int(order[k]), 1.0 - w), (int(order[0]), w)]
    return None


def _site_longitude(longitudes, lon):
    """``lon`` (deg east) in the convention of the file's longitudes (0..360 or -180..180)."""
    if float(np.max(longitudes)) > 180.0:
        return float(np.mod(lon, 360.0))
    return float(np.mod(lon + 180.0, 360.0) - 180.0)


def _iso(t) -> str:
    return np.datetime_as_string(np.datetime64(t, "s")) + "Z"


def read_reanalysis(path: str | Path, latitude: float, longitude: float,
                    when: dt.datetime) -> ReanalysisColumn:
    """The column of the pressure-level file ``path`` over geodetic ``latitude``, ``longitude``
    (degrees north, east) at the UTC instant ``when``: bilinear between the four grid points
    around the site, linear between the two file times around ``when``.

    A file that cannot be read as NetCDF, lacks a needed variable, does not cover the
    site or the instant, or whose column is not ordered (heights rising as pressure
    falls) raises an :class:`InputError` naming the file and the field.
    """
    path = Path(path)
    if not path.is_file():
        raise InputError("no such reanalysis file", file=path)
    needs("weather", "a reanalysis weather file", "xarray", "netCDF4")
    import xarray as xr
    try:
        data = xr.open_dataset(path, engine="netcdf4")
    except Exception as error:       # netCDF4/HDF5 raise OSError, ValueError, RuntimeError...
        raise _unreadable(path, error) from None
    with data:
        return _column(data, path, latitude, longitude, when)


def _unreadable(path, error) -> InputError:
    """The error for a file xarray could not open: its times' units when the file opens
    without decoding them, else not NetCDF at all."""
    import xarray as xr
    try:
        with xr.open_dataset(path, engine="netcdf4", decode_times=False) as raw:
            names = [n for n in TIME if n in raw.variables]
    except Exception:                # not NetCDF (or HDF5) at all
        return InputError(f"cannot read the file as NetCDF ({type(error).__name__}: {error})",
                          file=path)
    return InputError(f"cannot read the times ({error})", file=path,
                      field=names[0] if names else None)


def _coordinate(data, name, path):
    """The values of coordinate ``name`` as floats: some, all finite, none repeated."""
    try:
        values = np.asarray(data[name].values, dtype=float).ravel()
    except (TypeError, ValueError):
        raise InputError(f"{name} is not numeric", file=path, field=name) from None
    if len(values) == 0 or not np.all(np.isfinite(values)) \
            or len(np.unique(values)) != len(values):
        raise InputError(f"{name} needs at least one value, all finite and distinct",
                         file=path, field=name)
    return values


def _column(data, path, latitude, longitude, when):
    names = set(data.variables)
    lat_name = _required(LATITUDE, names, path, "latitude coordinate")
    lon_name = _required(LONGITUDE, names, path, "longitude coordinate")
    level_name = _required(LEVEL, names, path, "pressure-level coordinate")
    time_name = _required(TIME, names, path, "time coordinate")
    geo_name = _name(GEOPOTENTIAL, names)
    height_name = None if geo_name else _required(
        GEOPOTENTIAL_HEIGHT, names, path, "geopotential (z) or geopotential height")
    fields = {"height": geo_name or height_name,
              "temperature": _required(TEMPERATURE, names, path, "temperature"),
              "u": _required(U_WIND, names, path, "east wind (u)"),
              "v": _required(V_WIND, names, path, "north wind (v)")}
    humidity = _name(SPECIFIC_HUMIDITY, names)
    relative = None if humidity else _name(RELATIVE_HUMIDITY, names)
    if humidity or relative:
        fields["humidity"] = humidity or relative

    lats, lons, levels = (_coordinate(data, name, path) for name in (lat_name, lon_name,
                                                                        level_name))
    lon = _site_longitude(lons, longitude)
    span = float(np.max(lons) - np.min(lons))
    step = float(np.min(np.abs(np.diff(np.sort(lons))))) if len(lons) > 1 else 0.0
    at_lat = _bracket(lats, latitude)
    at_lon = _bracket(lons, lon, periodic=len(lons) > 1 and span + 1.5 * step >= 360.0)
    if at_lat is None or at_lon is None:
        raise InputError(
            f"the site ({latitude:.4f} deg N, {longitude:.4f} deg E) is outside the file's grid "
            f"(latitude {lats.min():g} to {lats.max():g} deg, longitude {lons.min():g} to "
            f"{lons.max():g} deg)", file=path, field=lat_name if at_lat is None else lon_name)

    times = np.atleast_1d(data[time_name].values)
    if not np.issubdtype(times.dtype, np.datetime64):
        raise InputError(f"the {time_name} coordinate is not a time (units not understood)",
                         file=path, field=time_name)
    epoch = np.datetime64(when.astimezone(dt.timezone.utc).replace(tzinfo=None), "ns")
    offsets = (times.astype("datetime64[ns]") - epoch).astype(np.int64).astype(float)
    at_time = _bracket(offsets / 3.6e12, 0.0)       # hours, so SNAP is a few microseconds
    if at_time is None:
        raise InputError(f"the mission's epoch {_iso(epoch)} is outside the file's times "
                         f"({_iso(times.min())} to {_iso(times.max())})", file=path,
                         field=time_name)

    unit = str(data[level_name].attrs.get("units", "")).strip().lower()
    pressure = levels if unit == "pa" or (unit not in ("hpa", "mb", "millibars")
                                          and levels.max() > 1100.0) else levels * 100.0
    column = {}
    for role, name in fields.items():
        column[role] = _interpolate(data[name], path, name,
                                    {time_name: at_time, lat_name: at_lat, lon_name: at_lon},
                                    level_name)
    order = np.argsort(-pressure, kind="stable")            # bottom up
    p = pressure[order]
    h = column["height"][order] / (G0 if geo_name else 1.0)
    t = column["temperature"][order]
    if "humidity" not in column:
        w = np.zeros_like(p)
    elif humidity:
        q = column["humidity"][order]
        w = q / (1.0 - q)
    else:
        rh = np.clip(column["humidity"][order], 0.0, 100.0)
        w = mixing_ratio_from_vapour(rh / 100.0 * saturation_vapour_pressure(t - CELSIUS_ZERO), p / 100.0)
    if len(p) < 2:
        raise InputError("a column needs at least two pressure levels", file=path,
                         field=level_name)
    for i in range(1, len(p)):
        if not h[i] > h[i - 1] or not p[i] < p[i - 1]:
            raise InputError(f"the level at {p[i] / 100:g} hPa is not above the one at "
                             f"{p[i - 1] / 100:g} hPa ({h[i]:.1f} m' after {h[i - 1]:.1f} m')",
                             file=path, field=fields["height"])
    return ReanalysisColumn(p, h, t, column["u"][order], column["v"][order], w, str(path))


def _interpolate(variable, path, name, weights, level_name):
    """``variable`` at one time and place: one value per level, the weighted sum over the
    bracketing time and grid points (each weight a product of the time, latitude and
    longitude weights, written so a weight of 1 gives the file's value exactly)."""
    extra = [d for d in variable.dims if d not in weights and d != level_name]
    if level_name not in variable.dims:
        raise InputError(f"{name} has no {level_name} dimension (dimensions: "
                         f"{', '.join(variable.dims)})", file=path, field=name)
    for dim in extra:
        if variable.sizes[dim] != 1:
            raise InputError(f"{name} has a dimension {dim!r} of {variable.sizes[dim]} "
                             "entries (an ensemble?): give one member", file=path, field=name)
    variable = variable.isel({d: 0 for d in extra})
    missing = [d for d in weights if d not in variable.dims]
    for dim in missing:                    # a file with one time may have no time dimension
        if len(weights[dim]) != 1:
            raise InputError(f"{name} has no {dim} dimension", file=path, field=name)
    dims = [d for d in weights if d in variable.dims]
    picks = {d: [i for i, _ in weights[d]] for d in dims}
    block = variable.isel(picks).transpose(*dims, level_name).values.astype(float)
    total = None
    for index in np.ndindex(*[len(picks[d]) for d in dims]):
        w = 1.0
        for d, k in zip(dims, index):
            w *= weights[d][k][1]
        term = w * block[index]
        total = term if total is None else total + term
    if not np.all(np.isfinite(total)):
        raise InputError(f"{name} has missing values at the site and time", file=path,
                         field=name)
    return total
