"""Soundings: reading the Wyoming/CSV/YAML formats, the day's table built from them, bad input.

Reference: the measurements themselves. The fixture
``fixtures/atmosphere/oun_20110522_12z_extract.txt`` is an extract of the
Norman, Oklahoma radiosonde of 22 May 2011 12Z (University of Wyoming
listing; origin in its first lines). The table must give back the reported
surface pressure, temperatures and winds at the reported heights, and the
hydrostatic pressure (integrated from the surface with virtual temperature
and WGS84 normal gravity) must agree with the independently measured
pressure of every level within 0.5 %. Geopotential-to-geometric heights are
checked against the 1976 standard's formula z = r0 H / (r0 - H), which holds
where normal gravity equals g0 (latitude 45.54°).
"""

import math
from pathlib import Path

import numpy as np
import pytest

from rocketsim.atmosphere.day import (BLEND_DEPTH, geometric_from_geopotential, profile_table)
from rocketsim.atmosphere.sounding import parse_wyoming, read_sounding
from rocketsim.atmosphere.ussa1976 import us_standard_1976
from rocketsim.constants import USSA_R0
from rocketsim.errors import InputError

FIXTURE = Path(__file__).parents[2] / "fixtures" / "atmosphere" / "oun_20110522_12z_extract.txt"
NORMAN = math.radians(35.18)           # 72357 OUN, 35.18 N
KNOT = 1852.0 / 3600.0


def _levels():
    """The fixture's levels with a temperature, as numbers read here independently."""
    rows = []
    for line in FIXTURE.read_text().splitlines()[8:]:
        cells = line.split()
        if len(cells) == 8:
            rows.append([float(c) for c in cells])
    return np.array(rows)   # PRES HGHT TEMP DWPT RELH MIXR DRCT SKNT


@pytest.fixture(scope="module")
def day():
    return profile_table(read_sounding(FIXTURE), NORMAN)


def _kink_bound(z, values, below=0.0, above=0.0):
    """Worst error of 50 m linear interpolation at each level of a piecewise-linear profile:
    (dh/4) x the slope changes at the levels within one row (dh = 50 m) of it. ``below`` and
    ``above`` are the slopes beyond the ends (the table's extrapolation below the surface:
    -6.5 K/km, calm-holding wind; the blend above starts flat, and so does the standard
    temperature at the sample's 16 km top)."""
    slopes = np.diff(values) / np.diff(z)
    jump = np.abs(np.diff(slopes, prepend=below, append=above))
    near = np.abs(z[:, None] - z[None, :]) < 50.0
    return 12.5 * (near * jump[None, :]).sum(axis=1) + 1e-9


def test_below_ground_level_is_skipped_and_surface_pressure_recovered(day):
    levels = _levels()
    sounding = read_sounding(FIXTURE)
    assert len(sounding.height) == len(levels)          # the 1000 hPa level has no TEMP
    z0 = geometric_from_geopotential(levels[0, 1], NORMAN)
    assert day.at([z0])[1][0] == pytest.approx(levels[0, 0] * 100.0, rel=1e-5)


def test_temperatures_and_winds_recovered_at_their_heights(day):
    levels = _levels()
    z = geometric_from_geopotential(levels[:, 1], NORMAN)
    _, _, t, _, east, north = day.at(z)
    t_ref = levels[:, 2] + 273.15
    inner = slice(None)
    # (+1 mK: the smoothstep blend's curvature within the row above the top level)
    assert np.all(np.abs(t - t_ref) <= _kink_bound(z, t_ref, below=-0.0065) + 1e-3)
    speed, direction = levels[:, 7] * KNOT, np.radians(levels[:, 6])
    # Speed is interpolated linearly, the direction along the short way round.
    got_speed = np.hypot(east, north)
    assert np.all(np.abs(got_speed - speed)[inner] <= _kink_bound(z, speed)[inner] + 1e-6)
    got_from = np.arctan2(-east, -north)
    turn = np.abs(np.angle(np.exp(1j * (got_from - direction))))
    bound = _kink_bound(z, np.unwrap(direction)) + 2e-3
    assert np.all(turn[inner] <= bound[inner])


def test_hydrostatic_pressure_matches_the_reported_pressure(day):
    levels = _levels()
    z = geometric_from_geopotential(levels[:, 1], NORMAN)
    p = day.at(z)[1]
    err = np.abs(p / (levels[:, 0] * 100.0) - 1.0)
    assert err.max() < 0.005        # measured: 0.21 %


def test_surface_density_is_that_of_moist_air(day):
    # Moist air as a mixture of dry air and vapour (WMO-No. 8, annex 4.B):
    # rho = (p - e) / (R_d T) + e / (R_v T), e = p w / (0.62198 + w), with R_d = R*/M_air,
    # R_v = R*/M_water (M_air 28.9644, M_water 18.0153 g/mol).
    p, t, w = 96_600.0, 295.35, 16.50e-3          # the fixture's surface level
    e = p * w / (0.62198 + w)
    rho = (p - e) / (8.31432 / 0.0289644 * t) + e / (8.31432 / 0.0180153 * t)
    z0 = geometric_from_geopotential(345.0, NORMAN)
    assert day.at([z0])[0][0] == pytest.approx(rho, rel=2e-5)
    # ... 0.6 % lighter than dry air at the same p and T: humidity is not ignored.
    assert rho < 0.995 * p / (8.31432 / 0.0289644 * t)


def test_dew_point_gives_the_archive_mixing_ratio(tmp_path):
    # The archive's MIXR column is computed independently from PRES and DWPT; ours from
    # DWPT alone (Bolton 1980) must agree with it to its printed precision and a few %.
    levels = _levels()
    path = tmp_path / "dew.csv"
    path.write_text("PRES,HGHT,TEMP,DWPT\n" + "".join(
        f"{r[0]:g},{r[1]:g},{r[2]:g},{r[3]:g}\n" for r in levels))
    ours = read_sounding(path).mixing_ratio * 1000.0
    np.testing.assert_allclose(ours, levels[:, 5], rtol=0.03, atol=0.006)


def test_geopotential_conversion_matches_the_standard_where_gravity_is_g0():
    lat = math.radians(45.5425)
    h = np.array([1_000.0, 16_000.0, 30_000.0])
    assert np.allclose(geometric_from_geopotential(h, lat), USSA_R0 * h / (USSA_R0 - h), atol=0.5)


def test_blend_into_the_standard_is_continuous(day):
    top = float(geometric_from_geopotential(_levels()[-1, 1], NORMAN))
    heights = day.heights
    for joint in (top, top + BLEND_DEPTH):
        i = int(np.searchsorted(heights, joint)) - 1        # row below the joint
        for values in (day.temperature, np.log(day.pressure)):
            step = abs(values[i + 1] - values[i])
            neighbours = np.abs(np.diff(values[i - 4:i + 6]))
            assert step <= 2.0 * np.delete(neighbours, 4).max()
    above = heights > top + BLEND_DEPTH
    above &= heights < 80_000.0
    np.testing.assert_allclose(day.temperature[above], us_standard_1976(heights[above]).temperature,
                               rtol=1e-12)
    assert not np.any(day.wind_east[above]) and not np.any(day.wind_north[above])
    # Pressure stays continuous at 86 km where the standard's upper air takes over.
    i = int(np.searchsorted(heights, 86_000.0))
    step = abs(np.log(day.pressure[i + 1] / day.pressure[i]))
    assert step <= 1.5 * abs(np.log(day.pressure[i] / day.pressure[i - 1]))


def _as_csv(tmp_path):
    levels = _levels()
    lines = ["PRES,HGHT,TEMP,DWPT,RELH,MIXR,DRCT,SKNT"]
    lines += [",".join(f"{v:g}" for v in row) for row in levels]
    path = tmp_path / "oun.csv"
    path.write_text("\n".join(lines) + "\n")
    return path


def test_csv_and_yaml_read_the_same_columns(tmp_path):
    wyoming = read_sounding(FIXTURE)
    csv_path = _as_csv(tmp_path)
    levels = _levels()
    names = ["PRES", "HGHT", "TEMP", "DWPT", "RELH", "MIXR", "DRCT", "SKNT"]
    yaml_path = tmp_path / "oun.yaml"
    yaml_path.write_text("columns:\n" + "".join(
        f"  {n}: [{', '.join(f'{v:g}' for v in levels[:, k])}]\n" for k, n in enumerate(names)))
    for other in (read_sounding(csv_path), read_sounding(yaml_path)):
        for field in ("height", "pressure", "temperature", "mixing_ratio", "wind_speed",
                      "wind_from"):
            np.testing.assert_allclose(getattr(other, field), getattr(wyoming, field), rtol=1e-12)


def _bad_csv(tmp_path, edit):
    lines = _as_csv(tmp_path).read_text().splitlines()
    edit(lines)
    path = tmp_path / "bad.csv"
    path.write_text("\n".join(lines) + "\n")
    return path


def _swap_heights(lines):
    a, b = lines[3].split(","), lines[4].split(",")
    a[1], b[1] = b[1], a[1]
    lines[3], lines[4] = ",".join(a), ",".join(b)


def _set_cell(row, column, text):
    def edit(lines):
        cells = lines[row].split(",")
        cells[column] = text
        lines[row] = ",".join(cells)
    return edit


def _drop_temp(lines):
    for k, line in enumerate(lines):
        cells = line.split(",")
        lines[k] = ",".join(cells[:2] + cells[3:])


@pytest.mark.parametrize("edit, line, field, words", [
    (_swap_heights, 5, "HGHT", "out of order"),
    (_drop_temp, 1, "TEMP", "no TEMP column"),
    (_set_cell(6, 2, "warm"), 7, "TEMP", "not a number"),
    (_set_cell(6, 2, "95"), 7, "TEMP", "implausible"),
    (_set_cell(2, 7, "900"), 3, "SKNT", "implausible"),
])
def test_bad_csv_names_file_line_and_column(tmp_path, edit, line, field, words):
    path = _bad_csv(tmp_path, edit)
    with pytest.raises(InputError) as caught:
        read_sounding(path)
    error = caught.value
    assert error.file == str(path) and error.line == line and error.field == field
    assert words in error.message


def test_bad_wyoming_cell_names_the_line():
    text = FIXTURE.read_text().splitlines()
    row = text[12]
    text[12] = row[:14] + "  2x.2" + row[20:]      # the TEMP column of the fixture's 13th line
    with pytest.raises(InputError) as caught:
        parse_wyoming("\n".join(text), "oun.txt")
    assert caught.value.line == 13 and caught.value.field == "TEMP"
    assert "oun.txt:13" in str(caught.value)


def test_wyoming_heights_out_of_order_name_the_line():
    text = FIXTURE.read_text().splitlines()
    text[12], text[13] = text[13], text[12]
    with pytest.raises(InputError) as caught:
        parse_wyoming("\n".join(text), "oun.txt")
    assert caught.value.line == 14 and "out of order" in caught.value.message


def test_bad_yaml_cell_names_its_line(tmp_path):
    path = tmp_path / "bad.yaml"
    path.write_text("columns:\n  PRES: [966, 925]\n  HGHT: [345, 720]\n"
                    "  TEMP:\n    - 22.2\n    - hot\n")
    with pytest.raises(InputError) as caught:
        read_sounding(path)
    assert caught.value.line == 6 and caught.value.field == "TEMP"
    assert f"{path}:6" in str(caught.value)
