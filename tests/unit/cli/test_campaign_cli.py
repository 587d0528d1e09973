"""Bad campaign files: one paragraph naming the file, line and field, exit status 2,
before anything flies (no campaign directory is created)."""

from __future__ import annotations

import pytest
from click.testing import CliRunner

from rocketsim_cli.main import main
from tests.campaign_files import write_arc

GOOD = """\
name: cli
scenario: arc.yaml
runs: 3
seed: 1
dispersions:
  v_north: {path: "mission.start.site.velocity[1]", kind: normal, sigma: 1 m/s}
  mass: {path: vehicle.rigid_body.mass, kind: uniform, low: 290 kg, high: 310 kg}
"""


def run_campaign(tmp_path, text: str, *extra: str):
    campaign = write_arc(tmp_path, text)
    out = tmp_path / "out"
    result = CliRunner().invoke(main, ["campaign", "run", str(campaign), "-o", str(out), "--workers", "1",
                                       *extra])
    return campaign, out, result


@pytest.mark.parametrize("change, line, expected", [
    # a misspelt field of a path: the nearest valid path
    (("velocity[1]", "velocty[1]"), 6,
     "'velocty'; did you mean 'velocity'?; nearest valid path: 'mission.start.site.velocity[1]'"),
    (("rigid_body.mass", "rigid_bdy.mas"), 7, "nearest valid path: 'vehicle.rigid_body.mass'"),
    # an unknown field of the campaign
    (("runs: 3", "rums: 3"), 3, "unknown field 'rums'; did you mean 'runs'?"),
    (("kind: uniform", "kind: uniformly"), 7, "dispersions.mass"),
    # a unit the field does not take
    (("sigma: 1 m/s", "sigma: 1 kg"), 6, "unknown unit 'kg' for a speed"),
    # a scenario file that is not there
    (("scenario: arc.yaml", "scenario: arcs.yaml"), 2, "scenario file 'arcs.yaml' not found"),
])
def test_a_bad_campaign_is_refused_at_its_line_before_anything_flies(tmp_path, change, line, expected):
    campaign, out, result = run_campaign(tmp_path, GOOD.replace(*change))
    assert result.exit_code == 2, result.output
    assert result.output.startswith(f"error: {campaign}:{line}:")
    assert expected in result.output
    assert "Traceback" not in result.output
    assert not out.exists()


def test_a_value_the_field_refuses_is_reported_at_the_dispersion(tmp_path):
    """A mass centred on a negative value is refused by the scenario's own check, named
    at the dispersion that set it."""
    campaign, out, result = run_campaign(tmp_path, GOOD.replace("low: 290 kg, high: 310 kg",
                                                                "low: -310 kg, high: -290 kg"))
    assert result.exit_code == 2, result.output
    assert result.output.startswith(f"error: {campaign}:7:")
    assert "vehicle.rigid_body.mass" in result.output and "at least 0.0001 kg" in result.output
    assert not out.exists()


def test_correlations_must_name_normal_dispersions(tmp_path):
    text = GOOD + "correlations:\n  - {names: [v_north, mass], correlation: [[1, 0.5], [0.5, 1]]}\n"
    campaign, out, result = run_campaign(tmp_path, text)
    assert result.exit_code == 2
    assert result.output.startswith(f"error: {campaign}:9:")
    assert "'mass' is not a normal dispersion" in result.output
    text = GOOD.replace("kind: uniform, low: 290 kg, high: 310 kg", "kind: normal, sigma: 1 kg") + \
        "correlations:\n  - {names: [v_north, mass], correlation: [[1, 1.5], [1.5, 1]]}\n"
    campaign, out, result = run_campaign(tmp_path, text)
    assert result.exit_code == 2 and "not positive definite" in result.output


def test_a_directory_holds_one_campaign(tmp_path):
    campaign, out, result = run_campaign(tmp_path, GOOD)
    assert result.exit_code == 0, result.output
    assert "3 of 3 runs flew" in result.output
    # flying it again needs --resume; nothing is missing
    _, _, again = run_campaign(tmp_path, GOOD)
    assert again.exit_code == 2 and "--resume" in again.output
    _, _, resumed = run_campaign(tmp_path, GOOD, "--resume")
    assert resumed.exit_code == 0 and "3 of 3 runs flew" in resumed.output
    # another campaign cannot resume it
    _, _, other = run_campaign(tmp_path, GOOD.replace("seed: 1", "seed: 2"), "--resume")
    assert other.exit_code == 2 and "holds another campaign" in other.output and "seed" in other.output


def test_a_scheduler_that_cannot_be_reached_is_refused_before_the_directory_is_written(tmp_path):
    (tmp_path / "scheduler.json").write_text("not a scheduler's file")
    campaign = write_arc(tmp_path, GOOD)
    result = CliRunner().invoke(main, ["campaign", "run", str(campaign), "-o", str(tmp_path / "other"),
                                       "--scheduler-file", str(tmp_path / "scheduler.json")])
    assert result.exit_code == 2, result.output
    assert result.output.startswith("error: --scheduler-file: cannot reach the Dask scheduler")
    assert not (tmp_path / "other").exists()
