"""An output path that cannot be created is refused before the flight, claiming nothing."""

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
