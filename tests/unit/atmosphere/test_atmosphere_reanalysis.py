"""Reanalysis weather: ERA5 pressure-level NetCDF taken at a site and an instant.

References: the files' own values read independently with netCDF4 (at a grid
point and a file time the column must be those values exactly); bilinear and
linear interpolation written out by hand for points and times between; the
file's pressure levels, which the day's hydrostatic pressure (integrated from
the lowest level with the file's temperatures) must reproduce at each level's
geopotential height; and RocketPy (a peer library used only in tests) reading
the same ERA5 file.

Real file: ERA5 over Three Oaks, Michigan, 2020-02-23 (the Notre Dame
flight's day), copied from RocketPy's repository (scenarios/measured/README.md).
"""

import datetime as dt
import math
from pathlib import Path

import netCDF4
import numpy as np
import pytest
import xarray as xr
from click.testing import CliRunner

from rocketsim.atmosphere.day import STANDARD_LAPSE, geometric_from_geopotential
from rocketsim.atmosphere.reanalysis import read_reanalysis
from rocketsim.atmosphere.table import STEP
from rocketsim.constants import G0
from rocketsim.errors import InputError
from rocketsim.scenario.weather import ReanalysisWeather, build_atmosphere
from rocketsim_cli.main import main

WEATHER = Path(__file__).parents[3] / "scenarios" / "measured" / "weather"
NDRT = WEATHER / "ndrt_2020_weather_data_ERA5.nc"
NDRT_NEW = Path(__file__).parents[2] / "fixtures" / "measured" / "ndrt_2020_weather_data_ERA5_new_cropped.nc"
UTC = dt.timezone.utc
T16 = dt.datetime(2020, 2, 23, 16, tzinfo=UTC)


def _synthetic(path, longitudes=(350.0, 355.0, 0.0), seam=False):
    """A small ERA5-like file (new CDS names): 2 times, 4 levels, 3 x 3 points, with
    specific humidity; values are distinct smooth functions of every coordinate."""
    times = np.array(["2021-06-01T12:00", "2021-06-01T18:00"], dtype="datetime64[ns]")
    levels = np.array([1000.0, 925.0, 850.0, 700.0])
    lats = np.array([46.5, 46.25, 46.0])                      # descending, as ERA5's
    lons = np.asarray(longitudes)
    it, il, ja, jo = np.meshgrid(np.arange(2), np.arange(4), np.arange(3), np.arange(3),
                                 indexing="ij")
    base_h = np.array([110.0, 760.0, 1480.0, 3010.0])[il]
    shape = ("valid_time", "pressure_level", "latitude", "longitude")
    data = xr.Dataset(
        {"z": (shape, G0 * (base_h + 3.0 * it + 2.0 * ja - 1.5 * jo)),
         "t": (shape, 290.0 - 6.5e-3 * base_h + 1.25 * it - 0.5 * ja + 0.3 * jo),
         "u": (shape, 2.0 + 0.004 * base_h + 1.5 * it + 0.7 * ja - 0.9 * jo),
         "v": (shape, -1.0 + 0.002 * base_h - 0.5 * it + 0.2 * ja + 1.1 * jo),
         "q": (shape, 0.008 * np.exp(-base_h / 2500.0) * (1.0 + 0.05 * it + 0.02 * jo))},
        coords={"valid_time": times, "pressure_level": ("pressure_level", levels,
                                                        {"units": "hPa"}),
                "latitude": lats, "longitude": lons})
    data.to_netcdf(path, engine="netcdf4")
    return path


def _independent(path, name, time, lat, lon):
    """Variable ``name`` at index (time, :, lat, lon), read with netCDF4 (scaled, masked)."""
    with netCDF4.Dataset(path) as nc:
        return np.asarray(nc[name][time, :, lat, lon], dtype=float)


def test_at_a_grid_point_and_file_time_the_column_is_the_files_values(tmp_path):
    path = _synthetic(tmp_path / "day.nc")
    column = read_reanalysis(path, 46.25, -5.0, dt.datetime(2021, 6, 1, 18, tzinfo=UTC))
    # grid index: time 1, latitude 46.25 -> 1, longitude -5 = 355 -> 1; levels bottom up
    for name, got in (("t", column.temperature), ("u", column.u), ("v", column.v)):
        assert np.array_equal(got, _independent(path, name, 1, 1, 1)), name
    assert np.array_equal(column.height, _independent(path, "z", 1, 1, 1) / G0)
    q = _independent(path, "q", 1, 1, 1)
    assert np.array_equal(column.mixing_ratio, q / (1.0 - q))
    assert np.array_equal(column.pressure, [100_000.0, 92_500.0, 85_000.0, 70_000.0])


def test_real_era5_file_at_a_grid_point_is_the_files_values():
    """ERA5 over Three Oaks (packed int16 with scale and offset), 42.0 N 86.5 W at 16 UTC:
    index time 3, latitude 4, longitude 6; levels 600..1000 hPa stored top down."""
    column = read_reanalysis(NDRT, 42.0, -86.5, T16)
    for name, got in (("t", column.temperature), ("u", column.u), ("v", column.v)):
        assert np.array_equal(got, _independent(NDRT, name, 3, 4, 6)[::-1]), name
    assert np.array_equal(column.height, _independent(NDRT, "z", 3, 4, 6)[::-1] / G0)
    assert column.pressure[0] == 100_000.0 and column.pressure[-1] == 60_000.0


def test_between_points_and_times_bilinear_and_linear_by_hand(tmp_path):
    path = _synthetic(tmp_path / "day.nc")
    lat, lon = 46.1, -7.0                 # between 46.0/46.25 and 350/355 (= -10/-5)
    when = dt.datetime(2021, 6, 1, 13, 30, tzinfo=UTC)     # a quarter of the way to 18 UTC
    column = read_reanalysis(path, lat, lon, when)
    wt, wa, wo = 0.25, (lat - 46.0) / 0.25, (lon + 10.0) / 5.0
    for name, got in (("t", column.temperature), ("u", column.u), ("v", column.v),
                      ("z", column.height * G0)):
        def at(i, a, o):
            return _independent(path, name, i, a, o)
        # latitude index 2 is 46.0, 1 is 46.25; longitude index 0 is 350, 1 is 355
        space = [(1 - wa) * (1 - wo) * at(i, 2, 0) + (1 - wa) * wo * at(i, 2, 1)
                 + wa * (1 - wo) * at(i, 1, 0) + wa * wo * at(i, 1, 1) for i in (0, 1)]
        expected = (1 - wt) * space[0] + wt * space[1]
        np.testing.assert_allclose(got, expected, rtol=1e-13, err_msg=name)
    # the synthetic fields are linear in every index: the exact value is known
    base_h = np.array([110.0, 760.0, 1480.0, 3010.0])
    ja, jo = 2 - wa, wo                       # fractional indices of the site
    np.testing.assert_allclose(column.temperature, 290.0 - 6.5e-3 * base_h + 1.25 * wt
                               - 0.5 * ja + 0.3 * jo, rtol=1e-13)


def test_longitudes_across_a_global_grids_seam(tmp_path):
    """A global grid (0..270 every 90 deg) wraps: 315 E = -45 is halfway from 270 to 0."""
    times = np.array(["2021-06-01T12:00"], dtype="datetime64[ns]")
    shape = ("time", "level", "latitude", "longitude")
    lons = np.array([0.0, 90.0, 180.0, 270.0])
    u = np.broadcast_to(np.array([1.0, 2.0, 3.0, 5.0]), (1, 2, 2, 4))
    xr.Dataset({"z": (shape, np.broadcast_to(G0 * np.array([100.0, 1500.0])[None, :, None, None],
                                             (1, 2, 2, 4))),
                "t": (shape, np.full((1, 2, 2, 4), 280.0)), "u": (shape, u),
                "v": (shape, np.zeros((1, 2, 2, 4)))},
               coords={"time": times, "level": [1000, 850], "latitude": [10.0, 0.0],
                       "longitude": lons}).to_netcdf(tmp_path / "g.nc", engine="netcdf4")
    when = dt.datetime(2021, 6, 1, 12, tzinfo=UTC)
    assert np.array_equal(read_reanalysis(tmp_path / "g.nc", 5.0, -45.0, when).u, [3.0, 3.0])
    assert np.array_equal(read_reanalysis(tmp_path / "g.nc", 5.0, 315.0, when).u, [3.0, 3.0])


def test_old_and_new_era5_names_and_longitude_conventions_give_the_same_column(tmp_path):
    """The same analysis (23 Feb 2020 16 UTC) as the old CDS file (time/level, int16 packed)
    and the new one (valid_time/pressure_level, float32, 37 levels): the 14 shared levels
    agree within the old file's packing step; the old file shifted to 0..360 longitudes
    gives the same column (to rounding: the site's longitude weight is computed from
    273.43 - 273.25 instead of -86.57 + 86.75)."""
    site = (41.775447, -86.572467)
    old = read_reanalysis(NDRT, *site, T16)
    new = read_reanalysis(NDRT_NEW, *site, T16)
    shared = np.isin(new.pressure, old.pressure)
    assert np.array_equal(new.pressure[shared], old.pressure)
    with netCDF4.Dataset(NDRT) as nc:
        steps = {k: float(nc[k].scale_factor) for k in ("z", "t", "u", "v")}
    np.testing.assert_allclose(new.temperature[shared], old.temperature, atol=steps["t"])
    np.testing.assert_allclose(new.u[shared], old.u, atol=steps["u"])
    np.testing.assert_allclose(new.height[shared], old.height, atol=steps["z"] / G0 + 0.05)
    shifted = xr.open_dataset(NDRT).load()
    shifted = shifted.assign_coords(longitude=shifted.longitude + 360.0)
    shifted.to_netcdf(tmp_path / "east.nc", engine="netcdf4")
    east = read_reanalysis(tmp_path / "east.nc", *site, T16)
    for name in ("height", "temperature", "u", "v"):
        np.testing.assert_allclose(getattr(east, name), getattr(old, name), rtol=1e-12,
                                   err_msg=name)


def test_the_days_pressure_meets_the_files_levels():
    """The table integrates pressure hydrostatically up from the 1000 hPa level with the
    file's temperatures (dry: the file has no humidity); at every level's geometric height
    it must give that level's pressure. ERA5's own heights include the moisture this file
    lacks (about 3 g/kg near the ground in February, +0.5 K virtual temperature): 0.1 %
    allowed over the 4 km column; measured worst 0.066 %."""
    lat, lon = math.radians(41.775447), math.radians(-86.572467)
    table = build_atmosphere(ReanalysisWeather(kind="reanalysis", file=NDRT.name), lat,
                             WEATHER, site_longitude=lon, epoch=T16)
    column = read_reanalysis(NDRT, 41.775447, -86.572467, T16)
    z = geometric_from_geopotential(column.height, lat)
    _, p, t, _, east, north = table.at(z)
    # the anchor, to the 50 m rows' linear interpolation of an exponential, (dh/H)^2/8 = 5e-6
    assert p[0] == pytest.approx(column.pressure[0], rel=5e-6)
    np.testing.assert_allclose(p, column.pressure, rtol=1e-3)
    # temperature and wind at the levels: the 50 m rows' linear interpolation across a
    # level's kink is off by at most a quarter row times the change of gradient there
    # (docs/physics.md, air table); 0.17 K at the 925 hPa inversion. Below the lowest
    # level and above the top the day follows the standard's lapse rate (the blend into
    # the standard starts with zero slope).
    slopes = np.diff(column.temperature) / np.diff(z)
    kink = np.abs(np.diff(slopes, prepend=-STANDARD_LAPSE, append=-STANDARD_LAPSE))
    assert np.all(np.abs(t - column.temperature) <= STEP / 4 * kink + 1e-9)
    # Between levels the wind's speed and direction are interpolated separately (as a
    # sounding's), and the rows are linear in its components: within 0.25 m/s at the
    # levels (measured 0.21 m/s, at 1000 hPa under a 14 m/s-per-km shear).
    np.testing.assert_allclose(east, column.u, atol=0.25)
    np.testing.assert_allclose(north, column.v, atol=0.25)


def test_rocketpy_reads_the_same_era5_file_alike():
    """RocketPy's Environment on the same file, site and hour (its acceptance test's set-up):
    temperature, wind and pressure at heights between the levels agree within 0.05 K,
    0.25 m/s and 0.1 % (measured 0.009 K, 0.16 m/s, 0.073 %: RocketPy interpolates the
    wind's components and the pressure between levels, we interpolate speed and
    direction and integrate the pressure hydrostatically)."""
    rocketpy = pytest.importorskip("rocketpy")
    env = rocketpy.Environment(latitude=41.775447, longitude=-86.572467,
                               date=(2020, 2, 23, 16), elevation=206)
    env.set_atmospheric_model(type="Reanalysis", file=str(NDRT), dictionary="ECMWF_v0")
    lat, lon = math.radians(41.775447), math.radians(-86.572467)
    table = build_atmosphere(ReanalysisWeather(kind="reanalysis", file=NDRT.name), lat,
                             WEATHER, site_longitude=lon, epoch=T16)
    heights = np.array([300.0, 700.0, 1200.0, 1800.0, 2500.0, 3500.0])
    _, p, t, _, east, north = table.at(heights)
    theirs = np.array([[env.temperature(h), env.wind_velocity_x(h), env.wind_velocity_y(h),
                        env.pressure(h)] for h in heights])
    np.testing.assert_allclose(t, theirs[:, 0], atol=0.05)
    np.testing.assert_allclose(east, theirs[:, 1], atol=0.25)
    np.testing.assert_allclose(north, theirs[:, 2], atol=0.25)
    np.testing.assert_allclose(p, theirs[:, 3], rtol=1e-3)


def test_errors_name_the_file_and_the_field(tmp_path):
    path = _synthetic(tmp_path / "day.nc")
    when = dt.datetime(2021, 6, 1, 15, tzinfo=UTC)
    with pytest.raises(InputError) as outside:
        read_reanalysis(path, 47.0, -6.0, when)
    assert outside.value.file == str(path) and outside.value.field == "latitude"
    assert "outside the file's grid (latitude 46 to 46.5 deg, longitude 0 to 355 deg)" \
        in outside.value.message
    with pytest.raises(InputError) as late:
        read_reanalysis(path, 46.2, -6.0, dt.datetime(2021, 6, 2, tzinfo=UTC))
    assert late.value.field == "valid_time"
    assert ("the mission's epoch 2021-06-02T00:00:00Z is outside the file's times "
            "(2021-06-01T12:00:00Z to 2021-06-01T18:00:00Z)") in late.value.message
    garbage = tmp_path / "garbage.nc"
    garbage.write_bytes(b"CDF\x01 this is not really NetCDF" * 10)
    with pytest.raises(InputError) as corrupt:
        read_reanalysis(garbage, 46.2, -6.0, when)
    assert corrupt.value.file == str(garbage)
    assert corrupt.value.message.startswith("cannot read the file as NetCDF")
    for units, message in (("hours since 1900-13-45", "cannot read the times"),
                           ("fortnights after lunch", "the valid_time coordinate is not a time")):
        day = xr.open_dataset(path).load()
        day["valid_time"] = ("valid_time", [0.0, 6.0], {"units": units})
        day.drop_encoding().to_netcdf(tmp_path / "bad_time.nc", engine="netcdf4")
        with pytest.raises(InputError) as bad_time:
            read_reanalysis(tmp_path / "bad_time.nc", 46.2, -6.0, when)
        assert bad_time.value.field == "valid_time", units
        assert bad_time.value.message.startswith(message), bad_time.value.message
    day = xr.open_dataset(path).load()
    day["latitude"] = ("latitude", [46.5, np.nan, 46.0])
    day.drop_encoding().to_netcdf(tmp_path / "nan_lat.nc", engine="netcdf4")
    with pytest.raises(InputError) as nan_lat:
        read_reanalysis(tmp_path / "nan_lat.nc", 46.2, -6.0, when)
    assert nan_lat.value.field == "latitude" and "all finite" in nan_lat.value.message
    xr.open_dataset(path).drop_vars("u").to_netcdf(tmp_path / "no_u.nc", engine="netcdf4")
    with pytest.raises(InputError) as no_u:
        read_reanalysis(tmp_path / "no_u.nc", 46.2, -6.0, when)
    assert no_u.value.field == "u" and "no east wind (u) in the file" in no_u.value.message


def test_cli_prints_the_day_and_refuses_a_site_off_the_grid_with_exit_2(tmp_path):
    weather = tmp_path / "day.yaml"
    weather.write_text(f"kind: reanalysis\nfile: {NDRT}\n")
    runner = CliRunner()
    args = ["atmosphere", "--weather", str(weather), "--latitude", "41.775447 deg",
            "--to", "2 km", "--step", "500 m", "--format", "csv"]
    ok = runner.invoke(main, args + ["--longitude", "-86.572467 deg",
                                     "--epoch", "2020-02-23T16:00Z"])
    assert ok.exit_code == 0, ok.output
    assert ok.output.splitlines()[0].endswith("wind_east_m_s,wind_north_m_s")
    off = runner.invoke(main, args + ["--longitude", "-80 deg", "--epoch", "2020-02-23T16:00Z"])
    assert off.exit_code == 2
    assert f"{NDRT}: longitude: the site (41.7754 deg N, -80.0000 deg E) is outside" in off.output
    assert "Traceback" not in off.output
    late = runner.invoke(main, args + ["--longitude", "-86.57 deg", "--epoch", "2020-02-24"])
    assert late.exit_code == 2 and "outside the file's times" in late.output
    none = runner.invoke(main, args)
    assert none.exit_code == 2 and "--epoch" in none.output


def test_a_flight_in_reanalysis_weather_meets_the_files_wind_and_carries_the_file(tmp_path):
    """A payload released straight up at 100 m/s from Three Oaks at the file's 16 UTC:
    its first sample's airspeed is |(0, 0, 100) - wind| with the day's wind at the pad
    (the table's, read above), and the NetCDF file travels in the run as 'reanalysis'."""
    import rocketsim
    from rocketsim.scenario.load import load
    scenario = {"name": "reanalysis-release",
                "vehicle": str(Path(__file__).parents[3] / "vehicles" / "sounding-payload.yaml"),
                "site": {"name": "Three Oaks", "latitude": "41.775447 deg",
                         "longitude": "-86.572467 deg", "height": "206 m"},
                "mission": {"epoch": "2020-02-23T16:00:00Z", "duration": "1 s",
                            "start": {"site": {"velocity": ["0 m/s", "0 m/s", "100 m/s"]}}},
                "weather": {"kind": "reanalysis", "file": str(NDRT)}}
    _, _, _, sound, east, north = load(scenario).atmosphere().at([206.0])
    run = rocketsim.fly(scenario, tmp_path / "run.mcap")
    first = next(iter(run.bodies.values())).table().iloc[0]
    airspeed = math.sqrt(100.0 ** 2 + east[0] ** 2 + north[0] ** 2)
    assert first["airspeed_m_s"] == pytest.approx(airspeed, rel=1e-9)
    assert first["mach"] == pytest.approx(airspeed / sound[0], rel=1e-9)
    carried = rocketsim.open_run(tmp_path / "run.mcap").file.attachments
    assert carried["reanalysis/ndrt_2020_weather_data_ERA5.nc"] == NDRT.read_bytes()


def test_a_gfs_file_geopotential_height_pascals_and_relative_humidity(tmp_path):
    """GFS (NOAA THREDDS) names: lat/lon/isobaric, pressure in Pa, geopotential height in
    m' (no division by g0), relative humidity in %, turned into the mixing ratio
    ``eps e / (p - e)`` with ``e = RH/100 * e_s(T)`` (Bolton 1980, as soundings are);
    checked at a grid point against those formulas written out here."""
    shape = ("time", "isobaric", "lat", "lon")
    h = np.array([120.0, 800.0, 1500.0])[None, :, None, None] * np.ones((1, 3, 2, 2))
    t = np.array([288.0, 284.0, 280.0])[None, :, None, None] * np.ones((1, 3, 2, 2))
    rh = np.array([80.0, 60.0, 40.0])[None, :, None, None] * np.ones((1, 3, 2, 2))
    xr.Dataset({"Geopotential_height_isobaric": (shape, h), "Temperature_isobaric": (shape, t),
                "u-component_of_wind_isobaric": (shape, np.full((1, 3, 2, 2), 3.0)),
                "v-component_of_wind_isobaric": (shape, np.full((1, 3, 2, 2), -4.0)),
                "Relative_humidity_isobaric": (shape, rh)},
               coords={"time": np.array(["2024-05-01T00:00"], dtype="datetime64[ns]"),
                       "isobaric": ("isobaric", [100_000.0, 92_500.0, 85_000.0],
                                    {"units": "Pa"}),
                       "lat": [30.0, 30.5], "lon": [262.0, 262.5]}
               ).to_netcdf(tmp_path / "gfs.nc", engine="netcdf4")
    column = read_reanalysis(tmp_path / "gfs.nc", 30.5, -98.0, dt.datetime(2024, 5, 1, tzinfo=UTC))
    assert np.array_equal(column.height, [120.0, 800.0, 1500.0])
    assert np.array_equal(column.pressure, [100_000.0, 92_500.0, 85_000.0])
    e = np.array([80.0, 60.0, 40.0]) / 100 * 6.112 * np.exp(
        17.67 * (np.array([288.0, 284.0, 280.0]) - 273.15)
        / (np.array([288.0, 284.0, 280.0]) - 273.15 + 243.5))
    np.testing.assert_allclose(column.mixing_ratio, 0.62198 * e / (np.array([1000.0, 925.0, 850.0])
                                                                  - e), rtol=1e-12)
    assert np.array_equal(column.u, [3.0, 3.0, 3.0]) and np.array_equal(column.v, [-4.0] * 3)
