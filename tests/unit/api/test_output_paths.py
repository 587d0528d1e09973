"""An output path that cannot be created is refused before any work, claiming nothing:
the flight's MCAP and summary, and every other command's plots, tables and files; a
FIFO or a device as well; a disk filling up during the work is one line and exit 2,
keeping what was written."""

import os
import resource
import subprocess
import sys
from pathlib import Path

import pytest

from rocketsim.telemetry.reader import read_run
from tests.fuzz.harness import bounded
from tests.unit.scenario.test_scenario_errors import assert_clean_error


def test_an_output_in_a_missing_folder_is_exit_2_and_claims_nothing(scenario, cli, tmp_path):
    out = tmp_path / "no" / "such" / "dir" / "run.mcap"
    result = cli("fly", scenario(), "-o", out)
    assert_clean_error(result, "--output: cannot create", "No such file or directory", "nothing was written")
    assert "readable" not in result.output and not out.parent.exists()


def test_a_summary_in_a_missing_folder_is_refused_before_the_telemetry_is_written(scenario, cli, tmp_path):
    out = tmp_path / "run.mcap"
    result = cli("fly", scenario(), "-o", out, "--summary-json", tmp_path / "no" / "summary.json")
    assert_clean_error(result, "--summary-json: cannot create", "nothing was written")
    assert not out.exists()                 # the check of --output left nothing behind


def test_an_existing_output_is_still_overwritten_by_the_flight(scenario, cli, tmp_path):
    out = tmp_path / "run.mcap"
    out.write_bytes(b"old")
    result = cli("fly", scenario(duration="0.1 s"), "-o", out)
    assert result.exit_code == 0, result.output
    assert out.read_bytes().startswith(b"\x89MCAP0\r\n")


@pytest.mark.parametrize("command, option", [
    (("replay", "{run}", "--plot", "{bad}/plot.png"), "--plot"),
    (("replay", "{run}", "--export", "csv", "{file}/tables"), "--export"),
    (("windows", "--target", "moon", "--plot", "{bad}/porkchop.png"), "--plot"),
    (("windows", "--target", "moon", "--mission-fragment", "{bad}/moon.yaml"), "--mission-fragment"),
    (("atmosphere", "--plot", "{bad}/air.png"), "--plot"),
    (("classic-range", "-o", "{bad}/site.yaml"), "--output"),
])
def test_every_output_of_every_command_is_checked_before_the_work(command, option, scenario, cli, tmp_path):
    """A file in a folder that does not exist, or a file where the export's folder must
    be (a missing export folder is made, as its parents are): exit 2 naming the option,
    no traceback, nothing created, and no line of the work's output printed."""
    run = tmp_path / "run.mcap"
    assert cli("fly", scenario(duration="0.1 s"), "-o", run).exit_code == 0
    a_file = tmp_path / "a-file"
    a_file.write_text("")
    bad = tmp_path / "no" / "such"
    args = [part.format(run=run, bad=bad, file=a_file) for part in command]
    result = cli(*args)
    assert_clean_error(result, option, "cannot create", "nothing was written")
    assert not (tmp_path / "no").exists() and a_file.read_text() == ""
    assert "exported" not in result.output and "plot:" not in result.output


@pytest.mark.parametrize("kind", ["FIFO", "device"])
@pytest.mark.parametrize("command, option", [
    (("fly", "{scenario}", "-o", "{out}"), "--output"),
    (("fly", "{scenario}", "-o", "{run}", "--summary-json", "{out}"), "--summary-json"),
    (("replay", "{run}", "--plot", "{out}"), "--plot"),
    (("atmosphere", "--plot", "{out}"), "--plot"),
    (("classic-range", "-o", "{out}"), "--output"),
])
def test_a_fifo_or_a_device_as_output_is_refused_before_the_work(kind, command, option, scenario, cli, tmp_path):
    """A FIFO no one reads (opening it to write would wait for a reader forever) and
    /dev/full (every write fails): exit 2 naming the option, within the hang watchdog,
    nothing flown or written."""
    run = tmp_path / "run.mcap"
    if command[0] == "replay":
        assert cli("fly", scenario(duration="0.1 s"), "-o", run).exit_code == 0
    out = Path("/dev/full")
    if kind == "FIFO":
        out = tmp_path / "pipe"
        os.mkfifo(out)
    args = [part.format(scenario=scenario(duration="0.1 s"), run=run, out=out) for part in command]
    with bounded("output"):
        result = cli(*args)
    assert_clean_error(result, option, f"cannot write {out}: it is a {kind}, not a file", "nothing was written")
    assert "telemetry:" not in result.output and "plot:" not in result.output
    assert run.exists() == (command[0] == "replay")


def _rocketsim_with_files_up_to(limit: int, *args) -> subprocess.CompletedProcess:
    """``rocketsim *args`` in a process whose files cannot grow past ``limit`` bytes
    (RLIMIT_FSIZE: a write past it fails with EFBIG, as one on a full disk fails with
    ENOSPC; Python ignores the SIGXFSZ that comes with it)."""
    def limited() -> None:
        resource.setrlimit(resource.RLIMIT_FSIZE, (limit, limit))

    return subprocess.run([str(Path(sys.executable).with_name("rocketsim")), *map(str, args)],
                          preexec_fn=limited, capture_output=True, text=True, timeout=300)


def test_a_disk_filling_up_during_the_work_is_one_line_and_exit_2_keeping_what_was_written(scenario, tmp_path):
    """The MCAP stops growing at 150 kB in a 600 s flight (past its first chunks): exit 2, one line naming the file,
    and what was written is a run replay reads (damaged, cut short); then a plot that
    cannot be written whole: exit 2, one line naming the plot and its option."""
    run = tmp_path / "run.mcap"
    flown = _rocketsim_with_files_up_to(150_000, "fly", scenario(duration="600 s"), "-o", run)
    assert flown.returncode == 2 and "Traceback" not in flown.stderr, flown.stderr
    assert flown.stderr.strip().splitlines()[-1] == (
        f"error: [Errno 27] File too large; what was written to {run} is readable with "
        f"'rocketsim replay {run}'")
    written = read_run(run)
    assert written.problem and written.final, written.problem      # cut short, its states kept
    plotted = _rocketsim_with_files_up_to(2_000, "replay", run, "--plot", tmp_path / "p.png")
    assert plotted.returncode == 2 and "Traceback" not in plotted.stderr, plotted.stderr
    assert plotted.stderr.strip().splitlines()[-1].startswith("error: File too large, while writing ")
    assert plotted.stderr.strip().endswith(f"{tmp_path / 'p.png'} (--plot)")
