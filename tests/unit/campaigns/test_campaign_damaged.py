"""A campaign folder with a damaged file: ``--resume`` recovers what can be recovered
(a results file that is not a results table is set aside, renamed, never deleted, and
its runs flown again; ``inputs.parquet`` and ``meta.json``, which the campaign
determines, written again), ``rerun`` names the damaged file; a damaged
``campaign.yaml`` is a located error for both. Never a traceback.

One small campaign (4 runs of the arc, in this process) is flown once and copied
for each damage.
"""

from __future__ import annotations

import json
import shutil

import pandas as pd
import pytest

from tests.campaign_files import write_arc
from tests.unit.scenario.test_scenario_errors import assert_clean_error

CAMPAIGN = """\
name: damaged
scenario: arc.yaml
runs: 4
seed: 1
dispersions:
  v_north: {path: "mission.start.site.velocity[1]", kind: normal, sigma: 1 %}
"""


@pytest.fixture(scope="module")
def flown(tmp_path_factory):
    """(the campaign file, its folder flown whole, its results)."""
    from click.testing import CliRunner
    from rocketsim_cli.main import main
    folder = tmp_path_factory.mktemp("campaign")
    campaign = write_arc(folder, CAMPAIGN)
    done = CliRunner().invoke(main, ["campaign", "run", str(campaign), "-o", str(folder / "out"),
                                     "--workers", "1"], catch_exceptions=False)
    assert done.exit_code == 0, done.output
    return campaign, folder / "out", pd.read_parquet(folder / "out" / "results.parquet")


def _cut(path):
    path.write_bytes(path.read_bytes()[:100])


def _not_parquet(path):
    path.write_text("not parquet\n")


def _no_run_column(path):
    pd.DataFrame({"x": [1.0]}).to_parquet(path)


def _fractional_runs(path):
    pd.DataFrame({"run": [0.5], "status": ["ok"]}).to_parquet(path)


@pytest.mark.parametrize("damage, says", [(_cut, "not a readable Parquet file"),
                                          (_not_parquet, "not a readable Parquet file"),
                                          (_no_run_column, "run: missing column"),
                                          (_fractional_runs, "expected whole run numbers")])
@pytest.mark.parametrize("name", ["results.parquet", "results/part-000007.parquet"])
def test_a_damaged_results_file_is_named_by_rerun_and_set_aside_by_resume(name, damage, says, flown, cli,
                                                                           tmp_path):
    campaign, out, results = flown
    folder = tmp_path / "out"
    shutil.copytree(out, folder)
    damaged = folder / name
    if not damaged.exists():            # a part file: a copy of the results, as a crash leaves one
        shutil.copy(folder / "results.parquet", damaged)
    damage(damaged)
    kept = damaged.read_bytes()
    rerun = cli("campaign", "rerun", folder, "1", "-o", tmp_path / "run.mcap", "--trust")
    assert_clean_error(rerun, f"{damaged}", says)
    resumed = cli("campaign", "run", campaign, "-o", folder, "--resume", "--workers", "1")
    assert resumed.exit_code == 0 and "Traceback" not in resumed.output, resumed.output
    assert f"{damaged}" in resumed.output and f"set aside as {damaged.name}.damaged" in resumed.output
    assert damaged.with_name(damaged.name + ".damaged").read_bytes() == kept      # nothing deleted
    again = pd.read_parquet(folder / "results.parquet").drop(columns="wall_time_s")
    pd.testing.assert_frame_equal(again, results.drop(columns="wall_time_s"))     # the same runs, flown again


@pytest.mark.parametrize("text, says", [("runs: [\n", "campaign.yaml:2:1: YAML syntax error"),
                                        ("[1, 2]\n", "campaign.yaml:1:1: expected a YAML mapping")])
def test_a_damaged_campaign_file_is_a_located_error(text, says, flown, cli, tmp_path):
    campaign, out, _ = flown
    folder = tmp_path / "out"
    shutil.copytree(out, folder)
    (folder / "campaign.yaml").write_text(text)
    rerun = cli("campaign", "rerun", folder, "1", "-o", tmp_path / "run.mcap", "--trust")
    assert_clean_error(rerun, says)
    resumed = cli("campaign", "run", folder / "campaign.yaml", "-o", folder, "--resume", "--workers", "1",
                  "--trust")
    assert_clean_error(resumed, says)


@pytest.mark.parametrize("name, damage", [("inputs.parquet", _cut), ("inputs.parquet", None),
                                          ("meta.json", _not_parquet), ("meta.json", None)])
def test_resume_writes_a_damaged_or_missing_plan_file_again(name, damage, flown, cli, tmp_path):
    """inputs.parquet and meta.json are what the campaign determines: a resume sets a
    damaged one aside and writes both again, equal to the campaign's own."""
    campaign, out, _ = flown
    folder = tmp_path / "out"
    shutil.copytree(out, folder)
    path = folder / name
    if damage is None:
        path.unlink()
    else:
        damage(path)
    resumed = cli("campaign", "run", campaign, "-o", folder, "--resume", "--workers", "1")
    assert resumed.exit_code == 0 and "Traceback" not in resumed.output, resumed.output
    assert f"{path}: " in resumed.output and "written again from the campaign" in resumed.output
    assert path.with_name(name + ".damaged").exists() == (damage is not None)
    if name == "meta.json":
        assert json.loads(path.read_text()) == json.loads((out / name).read_text())
    else:
        pd.testing.assert_frame_equal(pd.read_parquet(path), pd.read_parquet(out / name))
    report = cli("campaign", "report", folder)
    assert report.exit_code == 0, report.output
