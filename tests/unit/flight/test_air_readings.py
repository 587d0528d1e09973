"""The day's air as a program reads it: weather in a scenario, air-relative velocity."""

import math

import pytest

from rocketsim.scenario.load import load
from rocketsim.api.telemetry_flight import fly_to_file as fly
from tests.conftest import ROOT, VEHICLE

FIXTURE = ROOT / "tests" / "fixtures" / "atmosphere" / "oun_20110522_12z_extract.txt"

PROGRAM = """
def main(fc):
    fc.event("air", density=fc.air_density, pressure=fc.air_pressure, airspeed=fc.airspeed,
             q=fc.dynamic_pressure, mach=fc.mach, north=float(fc.air_velocity @ fc_north(fc)))

def fc_north(fc):
    import numpy as np
    lat, lon = fc.latitude, fc.longitude
    return np.array([-math.sin(lat) * math.cos(lon), -math.sin(lat) * math.sin(lon), math.cos(lat)])

import math
"""


def test_on_the_pad_the_air_moves_past_at_the_measured_wind(write, tmp_path):
    """Norman, Oklahoma, 22 May 2011 12Z (the fixture's first two levels):
    surface 966 hPa at 345 gpm, 22.2 C, mixing ratio 16.50 g/kg, wind from
    180 deg at 7 kt; next level 462 gpm, wind from 184 deg at 16 kt.
    Radiosonde heights are geopotential: geometric z = H g0 / g(lat), with
    g(35.18 deg) = 9.7970 m/s^2 (Somigliana), so the levels stand at 345.34 m
    and 462.45 m. The pad is put at 350 m, on a row of the 50 m table; there
    the wind, interpolated linearly in height between the two levels, blows
    north at 7.357 kt (3.785 m/s). A vehicle at rest on the pad (ECI
    velocity omega_E x r) sees the air move past it at that speed: its
    air-relative velocity points south. Density from the ideal gas with the
    virtual temperature Tv = T (1 + w/0.622)/(1 + w) (Wallace & Hobbs, eq.
    3.16) and the pressure 5 m above the surface by the hydrostatic equation."""
    write("vehicle.yaml", VEHICLE)
    write("sounding.txt", FIXTURE.read_text())
    write("program.py", PROGRAM)
    path = write("scenario.yaml", """\
        name: pad
        vehicle: vehicle.yaml
        site: {name: Norman, latitude: 35.18 deg, longitude: -97.44 deg, height: 350 m}
        weather: {kind: sounding, file: sounding.txt}
        program: program.py
        mission:
          epoch: 2011-05-22T12:00:00Z
          start: {site: {}}
          duration: 0.02 s
        """)
    loaded = load(path)
    assert loaded.files["sounding"] == (tmp_path / "sounding.txt").resolve()
    summary = fly(loaded, tmp_path / "run.mcap")
    air = summary["bodies"]["probe"]["events"][0]
    w = 16.50e-3
    tv = (22.2 + 273.15) * (1 + w / 0.622) / (1 + w)
    z_surface, z_next = (h * 9.80665 / 9.7970 for h in (345.0, 462.0))
    pressure = 96600.0 * math.exp(-9.797 * (350.0 - z_surface) / (287.05 * tv))
    density = pressure / (287.05 * tv)
    f = (350.0 - z_surface) / (z_next - z_surface)
    north = (7 + f * (16 * math.cos(math.radians(4)) - 7)) * 1852 / 3600
    east = (f * -16 * math.sin(math.radians(4))) * 1852 / 3600
    wind = math.hypot(north, east)
    assert air["pressure"] == pytest.approx(pressure, rel=1e-3)
    assert air["density"] == pytest.approx(density, rel=5e-3)
    assert air["airspeed"] == pytest.approx(wind, rel=1e-3)
    assert air["north"] == pytest.approx(-north, rel=1e-3)
    assert air["q"] == pytest.approx(0.5 * density * wind ** 2, rel=6e-3)
    assert air["mach"] == pytest.approx(wind / math.sqrt(1.4 * 287.05 * tv), rel=5e-3)


def test_a_weather_file_with_a_misspelt_field_names_its_own_line(write, scenario, cli):
    path = scenario(extra="weather: weather.yaml\n")
    write("weather.yaml", "kind: random\nsed: 3\n")
    result = cli("validate", path)
    assert result.exit_code == 2
    assert "weather.yaml:2:1" in result.output and "did you mean 'seed'?" in result.output


def test_a_missing_sounding_file_is_named_at_its_line(write, scenario, cli):
    path = scenario(extra="weather:\n  kind: sounding\n  file: nowhere.txt\n")
    result = cli("validate", path)
    assert result.exit_code == 2
    assert "scenario.yaml:6:3" in result.output and "nowhere.txt" in result.output
