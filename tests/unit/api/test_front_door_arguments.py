"""The front door names its own arguments: a bad argument of a Python call is an
ArgumentError naming the argument as the call wrote it (``duration``, ``runs``,
``scheduler_file``), never a TypeError from deep inside nor a command-line option;
the same error reached through ``rocketsim`` names the option that gave it
(``--output``, ``K``). Nothing here flies: each call is refused before it would."""

from __future__ import annotations

import pytest

from rocketsim import api
from rocketsim.errors import ArgumentError
from tests.campaign_files import write_arc

CAMPAIGN = "name: x\nscenario: arc.yaml\nruns: 2\nseed: 1\n"


@pytest.fixture
def files(tmp_path):
    return write_arc(tmp_path, CAMPAIGN), tmp_path / "arc.yaml"


@pytest.mark.parametrize("call, argument", [
    (lambda c, s, d: api.fly(str(s), duration=-1.0), "duration"),
    (lambda c, s, d: api.fly(str(s), live={"port": -5}), "live.port"),
    (lambda c, s, d: api.fly(str(s), live={"port": "8765"}), "live.port"),
    (lambda c, s, d: api.fly(str(s), live={"host": 127}), "live.host"),
    (lambda c, s, d: api.fly(str(s), live={"paused": "no"}), "live.paused"),
    (lambda c, s, d: api.fly(str(s), live={"speed": 2}), "live"),
    (lambda c, s, d: api.fly(str(s), live="yes"), "live"),
    (lambda c, s, d: api.ephemeris("venus", []), "body"),
    (lambda c, s, d: api.ephemeris("mars", [], center="pluto"), "center"),
    (lambda c, s, d: api.ephemeris("mars", "2026-01-01"), "utc"),
    (lambda c, s, d: api.ephemeris("mars", ["2026-01-01"]), "utc"),
    (lambda c, s, d: api.vehicle_report(42), "path"),
    (lambda c, s, d: api.open_run(42), "path"),
    (lambda c, s, d: api.review(42), "source"),
    (lambda c, s, d: api.export_tables(42, d), "path"),
    (lambda c, s, d: api.export_tables(d / "run.mcap", None), "out_dir"),
    (lambda c, s, d: api.export_tables(d / "run.mcap", d, kind="xlsx"), "kind"),
    (lambda c, s, d: api.verify(None), "path"),
    (lambda c, s, d: api.verify(d / "run.mcap", trust="yes"), "trust"),
    (lambda c, s, d: api.telemetry_size(api.load(str(s)), duration="x"), "duration"),
    (lambda c, s, d: api.campaign(c, runs=0, workers=1), "runs"),
    (lambda c, s, d: api.campaign(c, runs="3", workers=1), "runs"),
    (lambda c, s, d: api.campaign(c, runs=True, workers=1), "runs"),
    (lambda c, s, d: api.campaign(c, workers=0), "workers"),
    (lambda c, s, d: api.campaign(c, scheduler=8786), "scheduler"),
    (lambda c, s, d: api.run_campaign(c, s, workers=1), "directory"),
    (lambda c, s, d: api.run_campaign(c, d, workers=1), "resume"),        # it holds the campaign
    (lambda c, s, d: api.run_campaign(c, d / "none", workers=1, resume=True), "resume"),
    (lambda c, s, d: api.run_campaign(c, d / "none", workers=1, resume="yes"), "resume"),
    (lambda c, s, d: api.run_campaign(c, d / "none", workers=1, trust=1), "trust"),
    (lambda c, s, d: api.rerun_campaign(d / "none", 0, d / "r.mcap"), "directory"),
    (lambda c, s, d: api.rerun_campaign(d, "1", d / "r.mcap"), "k"),
    (lambda c, s, d: api.rerun_campaign(d, 0, None), "telemetry"),
])
def test_a_python_call_names_its_own_argument(files, tmp_path, call, argument):
    campaign, scenario = files
    with pytest.raises(ArgumentError) as error:
        call(campaign, scenario, tmp_path)
    assert error.value.field == argument
    assert str(error.value).startswith(f"{argument}: ") and "--" not in str(error.value)


def test_the_command_line_names_the_option_that_gave_the_argument(files, tmp_path, cli):
    campaign, scenario = files
    (tmp_path / "held").mkdir()
    (tmp_path / "held" / "campaign.yaml").write_text(CAMPAIGN)
    held = cli("campaign", "run", campaign, "-o", tmp_path / "held", "--workers", "1")
    assert held.exit_code == 2 and "error: --resume: " in held.output, held.output
    nothing = cli("campaign", "run", campaign, "-o", tmp_path / "none", "--workers", "1", "--resume")
    assert nothing.exit_code == 2 and "error: --resume: " in nothing.output, nothing.output
    (tmp_path / "empty").mkdir()
    not_a_campaign = cli("campaign", "rerun", tmp_path / "empty", "0", "-o", tmp_path / "r.mcap")
    assert not_a_campaign.exit_code == 2 and "error: DIR: " in not_a_campaign.output, not_a_campaign.output
    assert "Traceback" not in held.output + nothing.output + not_a_campaign.output
