"""The weather: section (random and classic days, scenario models) and ``rocketsim atmosphere``.

References: the seeded streams' documented distributions (random_day's
table of spreads), the 1976 standard (classic days are it, shifted), and the
sounding fixture's reported surface pressure.
"""

import math
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner
from pydantic import ValidationError

from rocketsim.atmosphere.random_day import SPREADS, random_profile
from rocketsim.atmosphere.ussa1976 import us_standard_1976
from rocketsim.scenario.weather import WeatherFile, build_atmosphere
from rocketsim_cli.main import main

FIXTURE = Path(__file__).parents[2] / "fixtures" / "atmosphere" / "oun_20110522_12z_extract.txt"
LAT = math.radians(28.5)


def _build(data, base_dir="."):
    return build_atmosphere(WeatherFile.model_validate(data), LAT, base_dir)


def test_same_seed_same_day_bit_for_bit():
    a, b = _build({"kind": "random", "seed": 11}), _build({"kind": "random", "seed": 11})
    for field in ("density", "pressure", "temperature", "speed_of_sound", "wind_east",
                  "wind_north"):
        assert np.array_equal(getattr(a, field), getattr(b, field))


def test_different_seeds_give_different_days_within_the_documented_spreads():
    s2 = math.sin(LAT) ** 2
    surface_t, sea_p, seen = [], [], set()
    for seed in range(20):
        day = random_profile(seed, LAT)
        surface_t.append(day.temperature[0])
        sea_p.append(day.pressure[0])
        seen.add(round(float(day.temperature[0]), 6))
    assert len(seen) == 20
    t_mean, t_sigma = 300.0 - 45.0 * s2, SPREADS["temperature_sigma"]
    assert np.all(np.abs(np.array(surface_t) - t_mean) <= 3 * t_sigma + 1e-9)
    assert np.all(np.abs(np.array(sea_p) - 101_325.0) <= 3 * SPREADS["pressure_sigma"] + 1e-9)
    # A spread, not a constant: 20 draws of N(0, 6 K) have a sample deviation within 2-12 K.
    assert 2.0 < np.std(surface_t) < 12.0


def test_random_day_table_starts_from_its_sea_level_pressure():
    day = random_profile(5, LAT)
    table = _build({"kind": "random", "seed": 5})
    assert table.at([0.0])[1][0] == pytest.approx(day.pressure[0], rel=1e-6)
    assert table.has_wind


def test_classic_day_is_the_standard_shifted_by_the_surface_temperature():
    table = _build({"kind": "classic", "surface_temperature": "30 C"})
    h = np.array([0.0, 2_000.0, 8_000.0])
    shift = 303.15 - 288.15
    np.testing.assert_allclose(table.at(h)[2], us_standard_1976(h).temperature + shift,
                               atol=1e-9)
    assert table.at([0.0])[1][0] == pytest.approx(101_325.0, rel=1e-9)
    np.testing.assert_allclose(table.at([40_000.0])[2], us_standard_1976(40_000.0).temperature)
    # A warm day is less dense at the ground than the standard.
    assert table.at([0.0])[0][0] < us_standard_1976(0.0).density


def test_standard_weather_is_the_standard():
    table = _build({"kind": "standard"})
    assert table.at([5_000.0])[1][0] == pytest.approx(us_standard_1976(5_000.0).pressure,
                                                      rel=1e-9)


def test_sounding_file_resolves_relative_to_the_base_dir():
    table = _build({"kind": "sounding", "file": FIXTURE.name}, FIXTURE.parent)
    assert table.has_wind and table.h0 < 345.0


def test_inline_columns_and_their_errors():
    ok = {"kind": "sounding", "columns": {"PRES": [966, 925, 850], "HGHT": [345, 720, 1454],
                                          "TEMP": [22.2, 20.4, 22.0]}}
    assert _build(ok).at([345.0])[1][0] == pytest.approx(96_600.0, rel=1e-3)
    bad = {"kind": "sounding", "columns": {"PRES": [966, 925], "HGHT": [720, 345],
                                           "TEMP": [22.2, 20.4]}}
    with pytest.raises(Exception) as caught:        # refused as it is validated, at the column's cell
        _build(bad)
    assert "columns.HGHT[1]: heights out of order" in str(caught.value)


@pytest.mark.parametrize("data", [
    {"kind": "sunny"},
    {"kind": "standard", "wind": 3},
    {"kind": "random"},
    {"kind": "sounding"},
    {"kind": "sounding", "file": "a.txt", "columns": {"PRES": [1]}},
    {"kind": "classic", "surface_temperature": "400 K"},
])
def test_bad_weather_is_refused(data):
    with pytest.raises(ValidationError):
        WeatherFile.model_validate(data)


def test_cli_csv_columns_and_wind(tmp_path):
    weather = tmp_path / "day.yaml"
    weather.write_text(f"kind: sounding\nfile: {FIXTURE}\n")
    runner = CliRunner()
    result = runner.invoke(main, ["atmosphere", "--weather", str(weather), "--latitude",
                                  "35.18 deg", "--to", "20 km", "--step", "5 km",
                                  "--format", "csv"])
    assert result.exit_code == 0, result.output
    lines = result.output.strip().splitlines()
    assert lines[0] == ("height_m,temperature_K,pressure_Pa,density_kg_m3,speed_of_sound_m_s,"
                        "wind_east_m_s,wind_north_m_s")
    assert len(lines) == 6
    calm = runner.invoke(main, ["atmosphere", "--to", "10 km", "--format", "csv"])
    assert calm.output.splitlines()[0].endswith("speed_of_sound_m_s")
    first = [float(v) for v in calm.output.splitlines()[1].split(",")]
    assert first[2] == pytest.approx(101_325.0, rel=1e-5)


def test_cli_mars_plot_and_bad_input(tmp_path):
    runner = CliRunner()
    png = tmp_path / "mars.png"
    result = runner.invoke(main, ["atmosphere", "--body", "mars", "--to", "150 km",
                                  "--step", "10 km", "--plot", str(png)])
    assert result.exit_code == 0, result.output
    assert png.stat().st_size > 1000
    bad = tmp_path / "bad.yaml"
    bad.write_text("kind: random\nseed: [1]\n")
    result = runner.invoke(main, ["atmosphere", "--weather", str(bad)])
    assert result.exit_code == 2 and "bad.yaml:2" in result.output
    result = runner.invoke(main, ["atmosphere", "--to", "700 km"])
    assert result.exit_code == 2
