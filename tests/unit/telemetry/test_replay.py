"""``rocketsim replay``: summary, safety of shared files, damaged files, --verify."""

import shutil
from pathlib import Path

import pytest
from click.testing import CliRunner

from rocketsim.scenario.load import load
from rocketsim.api.telemetry_flight import fly_to_file as fly
from rocketsim.api.reflight import UntrustedProgram, lay_out, verify
from rocketsim.telemetry.reader import read_run
from tests.run_files import rewrite_run

ROOT = Path(__file__).resolve().parents[3]

PROGRAM = """
def main(fc):
    fc.log("coasting")
    fc.sleep(1.0)
    fc.event("marker", altitude_m=fc.altitude)
"""

# Writes a file when imported and when run: proof of execution.
MALICIOUS = """
from pathlib import Path
Path({proof!r}).write_text("imported")

def main(fc):
    Path({proof!r}).write_text("ran")
"""


def replay(*args):
    from rocketsim_cli.main import main
    return CliRunner().invoke(main, ["replay", *map(str, args)], catch_exceptions=False)


@pytest.fixture
def run_file(scenario, tmp_path):
    out = tmp_path / "run.mcap"
    fly(load(scenario(PROGRAM, duration="3 s")), out)
    return out


def test_summary_lists_outcome_bodies_events_and_files(run_file):
    result = replay(run_file)
    assert result.exit_code == 0, result.output
    text = result.output
    assert "scenario test" in text and "outcome: ok" in text
    assert "probe: 31 states" in text and "last: T+3.00 s" in text
    assert "T+1.00 s  probe: marker" in text
    assert "program/program.py" in text and "not executed" in text
    assert "program log: 1 lines, last: coasting" in text


def test_nothing_from_a_shared_program_runs_without_trust(scenario, tmp_path):
    proof = tmp_path / "proof.txt"
    out = tmp_path / "shared.mcap"
    path = scenario(MALICIOUS.format(proof=str(proof)), duration="1 s")
    fly(load(path), out)
    assert proof.read_text() == "ran"            # flying it did run it
    proof.unlink()
    shutil.rmtree(tmp_path / "__pycache__", ignore_errors=True)
    path.with_name("program.py").unlink()        # only the shared file is left
    assert replay(out).exit_code == 0
    assert replay(out, "--export", "csv", tmp_path / "tables", "--plot", tmp_path / "p.png").exit_code == 0
    refused = replay(out, "--verify")
    assert refused.exit_code == 2 and "--trust" in refused.output
    with pytest.raises(UntrustedProgram):
        verify(out)
    assert not proof.exists()                    # nothing executed it
    trusted = replay(out, "--verify", "--trust")
    assert "executing program (program.py)" in trusted.output
    assert trusted.exit_code == 0 and "bit-identical" in trusted.output
    assert proof.read_text() == "ran"            # --trust did


def test_verify_trust_on_a_shipped_mission_is_bit_identical(tmp_path):
    out = tmp_path / "ballistic.mcap"
    fly(load(ROOT / "scenarios" / "spaceport-ballistic.yaml"), out, duration=12.0)
    result = replay(out, "--verify", "--trust")
    assert result.exit_code == 0, result.output
    assert "verify: bit-identical" in result.output


def test_verify_trust_on_a_staged_mission_with_separated_bodies(tmp_path):
    # the shipped Falcon 9 mission through staging and fairing jettison (three bodies,
    # each with its own channels; the booster flies its return program); a 0.1 s
    # headless step and 215 s of flight (the fairing goes at ~212 s, the booster being cut
    # off early with its return propellant) keep the two flights short (the step is
    # recorded in the run, so the re-flight uses it too)
    out = tmp_path / "falcon9.mcap"
    summary = fly(load(ROOT / "scenarios" / "falcon9-leo.yaml"), out, step=0.1, duration=215.0)
    assert len(summary["bodies"]) >= 3
    result = replay(out, "--verify", "--trust")
    assert result.exit_code == 0, result.output
    assert "verify: bit-identical" in result.output


def test_a_run_edited_by_one_byte_is_caught_at_that_message(run_file, tmp_path):
    edited = tmp_path / "edited.mcap"
    target = {}

    def change(index, topic, data):
        if topic == "/probe/state" and b'"t":2.0,' in data:
            target.update(index=index)
            position = data.index(b'"position":[') + len(b'"position":[')
            digit = data[position + 2:position + 3]
            return data[:position + 2] + (b"1" if digit != b"1" else b"2") + data[position + 3:]
        return data

    rewrite_run(run_file, edited, change)
    assert target
    verdict = verify(edited, trust=True)
    assert not verdict.identical
    assert verdict.difference["index"] == target["index"]
    assert verdict.difference["topic"] == "/probe/state"
    assert verdict.difference["field"] == "position_x"
    result = replay(edited, "--verify", "--trust")
    assert result.exit_code == 1 and f"DIFFERS at message {target['index']} (/probe/state" in result.output
    # the untouched copy is identical
    same = tmp_path / "same.mcap"
    rewrite_run(run_file, same, lambda i, t, d: d)
    assert verify(same, trust=True).identical


def test_a_file_cut_at_half_is_an_error_with_a_summary_of_what_is_readable(scenario, tmp_path):
    run_file = tmp_path / "long.mcap"
    fly(load(scenario(PROGRAM, duration="120 s")), run_file)          # several chunks
    data = run_file.read_bytes()
    cut = tmp_path / "cut.mcap"
    cut.write_bytes(data[:len(data) // 2])
    result = replay(cut)
    assert result.exit_code == 2
    assert "damaged" in result.stderr and "Traceback" not in result.stderr
    assert "scenario test" in result.stdout           # the metadata at the start is readable
    run = read_run(cut)
    states = run.counts.get("/probe/state", 0)
    assert run.problem and 300 < states < 1201
    assert run.final["probe"]["t"] == pytest.approx((states - 1) / 10)    # the last readable state
    assert f"probe: {states} states" in result.stdout


def test_a_corrupted_file_is_an_error_not_a_traceback(run_file, tmp_path):
    data = bytearray(run_file.read_bytes())
    middle = len(data) // 2
    data[middle:middle + 64] = bytes(64)
    bad = tmp_path / "bad.mcap"
    bad.write_bytes(bytes(data))
    result = replay(bad)
    assert result.exit_code == 2
    not_mcap = tmp_path / "not.mcap"
    not_mcap.write_text("hello")
    assert replay(not_mcap).exit_code == 2
    assert replay(tmp_path / "missing.mcap").exit_code == 2


def test_a_program_exception_leaves_a_readable_file_with_the_error(scenario, tmp_path):
    out = tmp_path / "failed.mcap"
    program = "def main(fc):\n    fc.sleep(0.5)\n    raise ValueError('bad gain')\n"
    with pytest.raises(Exception, match="bad gain"):
        fly(load(scenario(program, duration="3 s")), out)
    result = replay(out)
    assert result.exit_code == 0
    assert "outcome: error" in result.output and "error at T+0.50 s: " in result.output
    assert "bad gain" in result.output


def test_lay_out_keeps_the_files_inside_the_folder(run_file, tmp_path):
    run = read_run(run_file)
    run.metadata["files"] = dict(run.metadata["files"], vehicle="../../../../etc/vehicle.yaml")
    scenario = lay_out(run, tmp_path / "files")
    assert (tmp_path / "files").resolve() in scenario.resolve().parents
    run.metadata["files"]["vehicle"] = "/etc/vehicle.yaml"
    with pytest.raises(ValueError):
        lay_out(run, tmp_path / "other")


class _FullDisk:
    """A file that takes ``budget`` bytes, then fails as a full disk does (ENOSPC)."""

    def __init__(self, path, budget):
        self._file = open(path, "wb")
        self._left = budget

    def write(self, data):
        if len(data) > self._left:
            self._file.write(bytes(data[:self._left]))
            self._left = 0
            import errno
            import os
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))
        self._left -= len(data)
        return self._file.write(data)

    def __getattr__(self, name):
        return getattr(self._file, name)


def test_a_full_disk_leaves_what_was_written_readable(scenario, tmp_path, monkeypatch):
    import rocketsim.telemetry.writer as writer_module
    out = tmp_path / "full.mcap"
    monkeypatch.setattr(writer_module, "open", lambda path, mode: _FullDisk(path, 600_000), raising=False)
    with pytest.raises(OSError, match="No space left"):
        fly(load(scenario(PROGRAM, duration="300 s")), out)       # ~1 MB: the disk fills mid-flight
    monkeypatch.undo()
    run = read_run(out)
    assert run.problem and "cut short" in run.problem
    assert run.metadata["rocketsim"]["scenario"] == "test"
    assert 200 < run.counts["/probe/state"] < 3001
    assert "marker" in [event["name"] for event in run.events]
    result = replay(out)
    assert result.exit_code == 2 and "marker" in result.output


def test_the_writer_streams_to_disk_with_bounded_memory(tmp_path):
    """Memory held while writing grows by the chunk index only (~a few hundred
    bytes per 256 KiB chunk), not with the messages: a long cruise streams."""
    import tracemalloc
    from rocketsim.telemetry.writer import TelemetryWriter
    state = {"t": 0.0, "position": [6.8e6, 0.0, 0.0], "velocity": [0.0, 7.6e3, 0.0],
             "attitude": [1.0, 0.0, 0.0, 0.0], "body_rates": [0.0, 0.0, 0.0], "latitude_deg": 0.0,
             "longitude_deg": 0.0, "altitude": 4.2e5, "speed": 7.6e3, "orbit": {"eccentricity": 0.0}}
    tracemalloc.start()
    try:
        with TelemetryWriter(tmp_path / "long.mcap", 0) as telemetry:
            telemetry.add_body("probe")
            held = []
            for k in range(8_000):
                telemetry.state("probe", dict(state, t=k / 10))
                if k in (3_000, 7_999):
                    held.append(tracemalloc.get_traced_memory()[0])
    finally:
        tracemalloc.stop()
    written = (tmp_path / "long.mcap").stat().st_size
    grown_per_sample = (held[1] - held[0]) / 5_000
    assert written > 500_000               # several chunks
    assert grown_per_sample < 40, grown_per_sample          # a sample is ~700 bytes of JSON


def test_an_interrupted_flight_is_a_complete_file_that_says_so(scenario, tmp_path):
    out = tmp_path / "stopped.mcap"
    stopped = []

    def ctrl_c(t, phase):
        if t >= 1.5:
            stopped.append(t)
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        fly(load(scenario(PROGRAM, duration="1 h")), out, on_progress=ctrl_c)
    run = read_run(out)
    assert run.problem is None                                 # summary and index were written
    assert run.metadata["outcome"]["status"] == "error"
    assert run.errors[-1]["message"] == "KeyboardInterrupt" and run.errors[-1]["t"] == pytest.approx(stopped[0])
    result = replay(out)
    assert result.exit_code == 0 and "outcome: error (KeyboardInterrupt)" in result.output
