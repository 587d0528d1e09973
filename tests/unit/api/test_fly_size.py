"""``rocketsim fly`` says how large its telemetry will be and asks before a large one; long
coasts thinned by ``telemetry.coast_rate``.

References: the file sizes the flights write (the estimate is to be within a factor of
two of them: it prices the samples of the body a flight starts with,
rocketsim/api/file_size.py; the hobby rocket flown to 150 s, before its touchdown at
171 s: a flight that ends early writes fewer samples than its duration holds); a 60-day coast at 10 Hz is 51 840 001 samples; the coast
rule's samples are those at whole multiples of the coast interval
(docs/reference/telemetry.md) and the same flight writes the same messages twice.
"""

import json

import pytest
from click.testing import CliRunner
from mcap.reader import make_reader

from rocketsim.api import fly_to_file, load, telemetry_size
from rocketsim.api.file_size import LARGE
from rocketsim_cli import fly as fly_command
from rocketsim_cli.main import main
from tests.conftest import ROOT

ISS = ROOT / "scenarios" / "iss-coast.yaml"


def fly_cli(*args, input=None):
    return CliRunner().invoke(main, ["fly", *map(str, args)], input=input)


def test_a_60_day_coast_at_10_hz_is_refused_with_its_size_and_nothing_written(tmp_path):
    out = tmp_path / "coast.mcap"
    result = fly_cli(ISS, "--duration", "60d", "-o", out)
    assert result.exit_code == 2
    assert "51,840,001 samples of cubesat-6u at 10 Hz over 60 d" in result.output
    assert "--rate" in result.output and "--yes" in result.output and "GB" in result.output
    assert len(result.output.strip().splitlines()) == 1 and "Traceback" not in result.output
    assert not out.exists()
    size = telemetry_size(load(ISS), 60 * 86400.0)
    assert size.large and 15e9 < size.bytes < 30e9      # a 10-minute coast writes 413 bytes a sample
    assert not telemetry_size(load(ISS, {"telemetry.rate": "0.01 Hz"}), 60 * 86400.0).large
    assert not telemetry_size(load(ISS, {"telemetry.coast_rate": "0.01 Hz"}), 60 * 86400.0).large


def test_on_a_terminal_the_size_is_said_and_asked(tmp_path, monkeypatch):
    monkeypatch.setattr(fly_command, "_terminal", lambda: (True, True))
    result = fly_cli(ISS, "--duration", "60d", "-o", tmp_path / "coast.mcap", input="n\n")
    assert result.exit_code == 2
    assert "telemetry: about" in result.output and "write about" in result.output
    assert not (tmp_path / "coast.mcap").exists()
    result = fly_cli(ISS, "--duration", "10s", "-o", tmp_path / "short.mcap")     # small: said, not asked
    assert result.exit_code == 0 and "telemetry: about" in result.output and "write about" not in result.output


@pytest.mark.parametrize("scenario, seconds", [("iss-coast.yaml", 600.0), ("hobby-rocket.yaml", 150.0)])
def test_the_estimate_is_the_files_size_within_a_factor_of_two(tmp_path, scenario, seconds):
    loaded = load(ROOT / "scenarios" / scenario)
    out = tmp_path / "run.mcap"
    fly_to_file(loaded, out, duration=seconds)
    size = telemetry_size(loaded, seconds)
    written = out.stat().st_size
    print(f"\n[size] {scenario}: estimated {size.bytes / 1e6:.2f} MB, written {written / 1e6:.2f} MB")
    assert 0.5 < size.bytes / written < 2.0
    assert LARGE == 2e9


def states(path):
    with open(path, "rb") as stream:
        return [(m.log_time, m.data) for _, c, m in make_reader(stream).iter_messages()
                if c.topic == "/cubesat-6u/state"]


def test_a_coast_thinned_by_rule_keeps_its_multiples_and_its_last_sample_bit_for_bit(tmp_path):
    """Two hours of the ISS coast at 10 Hz, coasts at 0.01 Hz: a sample every 100 s
    (the CubeSat has no engine, and at 415 km the air's dynamic pressure is far under
    1 Pa) and the last one; the same flight writes the same samples again, and each is
    the sample the full-rate flight writes at that instant, bit for bit."""
    loaded = load(ISS, {"telemetry.coast_rate": "0.01 Hz"})
    runs = []
    for k in range(2):
        fly_to_file(loaded, tmp_path / f"thin{k}.mcap", duration=7200.0)
        runs.append(states(tmp_path / f"thin{k}.mcap"))
    assert runs[0] == runs[1]
    times = [round(json.loads(data)["t"], 6) for _, data in runs[0]]
    assert times == [100.0 * k for k in range(73)]
    fly_to_file(load(ISS), tmp_path / "full.mcap", duration=7200.0)
    full = dict(states(tmp_path / "full.mcap"))
    assert len(full) == 72001 and all(full[stamp] == data for stamp, data in runs[0])
    assert telemetry_size(loaded, 7200.0).samples == 73
