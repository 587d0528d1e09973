"""An output path that cannot be created is refused before any work, claiming nothing:
the flight's MCAP and summary, and every other command's plots, tables and files."""

import pytest

from tests.test_scenario_errors import assert_clean_error


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
