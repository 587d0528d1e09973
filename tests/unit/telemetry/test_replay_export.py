"""``rocketsim replay --export`` and ``--plot``: tables equal to the MCAP (columns named
with their units, times without float noise, the events' figures as columns), a drawn PNG."""

import csv
import json
import sys

import numpy as np
import pytest
from click.testing import CliRunner
from mcap.reader import make_reader

from rocketsim.scenario.load import load
from rocketsim.api.telemetry_flight import fly_to_file as fly
from tests.run_files import write_scenario

PROGRAM = """
def main(fc):
    fc.sleep(2.0)
    fc.event("marker", altitude_m=fc.altitude)
"""

AXES = {"position": "xyz", "velocity": "xyz", "body_rates": "xyz", "attitude": "wxyz"}


def replay(*args):
    from rocketsim_cli.main import main
    return CliRunner().invoke(main, ["replay", *map(str, args)], catch_exceptions=False)


@pytest.fixture(scope="module")
def run_file(tmp_path_factory):
    folder = tmp_path_factory.mktemp("export")
    scenario = write_scenario(folder, PROGRAM, "5 s")
    out = folder / "run.mcap"
    fly(load(scenario), out)
    return out


def mcap_states(path):
    """The state messages straight from the mcap reader (the reference)."""
    with open(path, "rb") as stream:
        return [json.loads(m.data) for _, _, m in make_reader(stream).iter_messages(topics=["/probe/state"])]


# the units of the state's fields as the columns name them (docs/reference/telemetry.md's table)
UNITS = {"t": "s", "position": "m", "velocity": "m_s", "body_rates": "rad_s", "altitude": "m", "height_agl": "m",
         "inertial_speed": "m_s", "surface_speed": "m_s", "mass": "kg", "acceleration": "m_s2",
         "sensed_acceleration": "m_s2", "airspeed": "m_s", "dynamic_pressure": "Pa",
         "semi_major_axis": "m", "periapsis_altitude": "m", "apoapsis_altitude": "m", "period": "s"}


def by_hand(message):
    """A state message's values by column, flattened and named with units by hand."""
    out = {}
    for key, value in message.items():
        if key in AXES:
            out.update({f"{key}_{a}_{UNITS[key]}" if key in UNITS else f"{key}_{a}": v
                        for a, v in zip(AXES[key], value)})
        elif key == "orbit":
            out.update({f"orbit_{k}_{UNITS[k]}" if k in UNITS else f"orbit_{k}": v for k, v in value.items()})
        else:
            out[f"{key}_{UNITS[key]}" if key in UNITS else key] = value
    out["t_s"] = round(out["t_s"], 6)
    return out


def expected_value(message, column):
    """The value of a CSV column in a state message, found by hand (None: absent)."""
    return by_hand(message).get(column)


def test_csv_rows_and_values_equal_the_mcap(run_file, tmp_path):
    result = replay(run_file, "--export", "csv", tmp_path / "tables")
    assert result.exit_code == 0, result.output
    with open(tmp_path / "tables" / "probe.csv", newline="") as stream:
        rows = list(csv.DictReader(stream))
    states = mcap_states(run_file)
    assert len(rows) == len(states) == 51
    assert set(rows[0]) >= {"t_s", "position_x_m", "attitude_w", "orbit_eccentricity", "altitude_m",
                            "inertial_speed_m_s", "orbit_periapsis_altitude_m", "mass_kg"}
    assert [row["t_s"] for row in rows[:4]] == ["0.0", "0.1", "0.2", "0.3"]       # no float noise
    for row, message in zip(rows, states):
        for column, text in row.items():
            value = expected_value(message, column)
            if isinstance(value, str):              # central_body
                assert text == value, column
                continue
            assert (text == "" if value is None else float(text) == value), column   # every digit kept
    with open(tmp_path / "tables" / "events.csv", newline="") as stream:
        events = list(csv.DictReader(stream))
    marker = [e for e in events if e["name"] == "marker"]
    assert [e["t_s"] for e in marker] == ["2.0"]
    assert float(marker[0]["altitude_m"]) == states[20]["altitude"]       # a figure is a column
    with open(run_file, "rb") as stream:                    # every event of the file, in order
        recorded = [json.loads(m.data) for _, _, m in make_reader(stream).iter_messages(topics=["/events"])]
    assert [(float(e["t_s"]), e["name"]) for e in events] == [(round(e["t"], 6), e["name"]) for e in recorded]


def test_parquet_rows_and_values_equal_the_mcap(run_file, tmp_path):
    pyarrow_parquet = pytest.importorskip("pyarrow.parquet")
    assert replay(run_file, "--export", "parquet", tmp_path / "pq").exit_code == 0
    table = pyarrow_parquet.read_table(tmp_path / "pq" / "probe.parquet").to_pydict()
    states = mcap_states(run_file)
    assert len(table["t_s"]) == len(states)
    for column, values in table.items():
        assert values == [expected_value(m, column) for m in states], column


def test_parquet_without_pyarrow_is_a_clear_error(run_file, tmp_path, monkeypatch):
    monkeypatch.setitem(sys.modules, "pyarrow", None)         # as if not installed
    monkeypatch.setitem(sys.modules, "pyarrow.parquet", None)
    result = replay(run_file, "--export", "parquet", tmp_path / "pq")
    assert result.exit_code == 2
    assert "pyarrow" in result.output and "rocketsim[parquet]" in result.output
    assert "Traceback" not in result.output


def test_plot_writes_a_png_that_is_not_blank(run_file, tmp_path):
    from matplotlib.image import imread
    out = tmp_path / "flight.png"
    result = replay(run_file, "--plot", out)
    assert result.exit_code == 0, result.output
    pixels = imread(out)[..., :3]
    assert pixels.shape[0] > 400 and pixels.shape[1] > 600
    drawn = np.any(pixels < 0.9, axis=-1)
    assert 0.01 < drawn.mean() < 0.6                            # axes, text and lines, not a blank page
    # the default colour of the first line (matplotlib C0, #1f77b4) is on the page
    blue = np.all(np.abs(pixels - np.array([0x1f, 0x77, 0xb4]) / 255) < 0.05, axis=-1)
    assert blue.sum() > 200
