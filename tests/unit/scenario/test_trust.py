"""Shared runs and campaign folders never execute a program unless trust is given.

Every path by which code can reach a flight from shared material is tried
with a crafted file or folder whose program writes a marker file when it is
loaded and when it runs: an MCAP re-flown (``replay --verify``,
:func:`rocketsim.api.verify`) carrying the program as an attachment under a
role the scenario names, or named by the run's recorded overrides, or as a
function not called ``main``; a campaign folder re-flown (``campaign rerun``),
resumed with its own ``campaign.yaml``, or offering a choice among programs.
Without trust each is refused (exit status 2 naming the program) and the
marker is absent; reading, exporting, plotting and ``open_run`` never execute
it; with trust the same file does run it (so the refusal is what kept it out).
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest
import yaml

import rocketsim
from rocketsim.api import rerun_campaign, run_campaign, verify
from rocketsim.scenario.trust import UntrustedProgram
from tests.campaign_files import write_arc
from tests.run_files import rewrite_run

EVIL = """\
from pathlib import Path
Path({marker!r}).write_text("loaded")


def {entry}(fc):
    Path({marker!r}).write_text("ran")
"""


@pytest.fixture(scope="module")
def plain(tmp_path_factory):
    """A short run of the conftest probe with no program: (its MCAP, its files' texts)."""
    from tests.conftest import MISSION, VEHICLE
    folder = tmp_path_factory.mktemp("plain")
    (folder / "vehicle.yaml").write_text(VEHICLE)
    (folder / "mission.yaml").write_text(MISSION.format(duration="0.5 s"))
    (folder / "scenario.yaml").write_text("name: plain\nvehicle: vehicle.yaml\nmission: mission.yaml\n")
    out = folder / "plain.mcap"
    rocketsim.fly(folder / "scenario.yaml", out)
    return out, {name: (folder / name).read_bytes() for name in ("vehicle.yaml", "mission.yaml", "scenario.yaml")}


def _files(texts: dict[str, bytes], scenario: bytes, **extra: bytes) -> tuple[dict, dict]:
    """Attachments and the ``files`` layout: the plain run's, its scenario replaced, and
    ``extra`` files each under a role of its own (``role=bytes`` laid out as ``<role>.py``)."""
    attachments = {"scenario/scenario.yaml": scenario, "vehicle/vehicle.yaml": texts["vehicle.yaml"],
                   "mission/mission.yaml": texts["mission.yaml"]}
    layout = {"scenario": "scenario.yaml", "vehicle": "vehicle.yaml", "mission": "mission.yaml"}
    for role, data in extra.items():
        attachments[f"{role}/{role}.py"] = data
        layout[role] = f"{role}.py"
    return attachments, {"files": layout}


def _scenario(texts, line: str) -> bytes:
    return texts["scenario.yaml"] + line.encode()


def crafted_runs(plain, folder: Path, marker: Path) -> dict[str, Path]:
    """Each way a shared run can bring a program, as a crafted file."""
    source, texts = plain
    evil = EVIL.format(marker=str(marker), entry="main").encode()
    ways = {}
    # the program as an attachment of a role the trust check of attachments never named,
    # which the scenario names
    ways["attachment under another name"] = _files(texts, _scenario(texts, "program: notes.py\n"), notes=evil)
    # the scenario names no program: the recorded overrides do
    attachments, metadata = ways["recorded override"] = _files(texts, texts["scenario.yaml"], data=evil)
    metadata["overrides"] = {"program": json.dumps("data.py")}
    # a program file under the program role, flown by a function not named main
    attachments, metadata = ways["function entry"] = _files(texts, texts["scenario.yaml"])
    attachments["program/sneaky.py"] = EVIL.format(marker=str(marker), entry="sneaky").encode()
    metadata["files"]["program"] = "sneaky.py"
    metadata["entries"] = {"program": "sneaky"}
    return {how: rewrite_run(source, folder / f"crafted-{n}.mcap", attachments=attachments, metadata=metadata)
            for n, (how, (attachments, metadata)) in enumerate(ways.items())}


@pytest.mark.parametrize("how", ["attachment under another name", "recorded override", "function entry"])
def test_a_crafted_run_executes_nothing_without_trust(plain, tmp_path, cli, how):
    marker = tmp_path / "marker"
    run = crafted_runs(plain, tmp_path, marker)[how]
    with pytest.raises(UntrustedProgram) as refused:
        verify(run)
    assert "program (" in str(refused.value) and "nothing was run" in str(refused.value)
    result = cli("replay", run, "--verify")
    assert result.exit_code == 2 and "--trust" in result.output, result.output
    assert ".py" in result.output and "Traceback" not in result.output
    # reading, exporting, plotting and opening it never execute it either
    assert cli("replay", run, "--export", "csv", tmp_path / "tables", "--plot", tmp_path / "p.png").exit_code == 0
    rocketsim.open_run(run)
    assert not marker.exists()
    # the same file with trust does run it: the refusal is what kept it out
    trusted = cli("replay", run, "--verify", "--trust")
    assert "--trust: executing program (" in trusted.output, trusted.output
    assert marker.read_text() == "ran"


CAMPAIGN = """\
name: shared
scenario: arc.yaml
runs: 3
seed: 5
dispersions:
  v_north: {path: "mission.start.site.velocity[1]", kind: normal, sigma: 1 %}
"""


@pytest.fixture
def folder(tmp_path):
    """A campaign folder as received: flown by its sender (no program), then edited so
    that its campaign flies the sender's program (an absolute path, a file the receiver
    also has: received beside the folder)."""
    campaign = write_arc(tmp_path / "sender", CAMPAIGN)
    rocketsim.campaign(campaign, tmp_path / "folder", workers=1)
    return tmp_path / "folder"


def _bring(folder: Path, marker: Path, edit) -> Path:
    evil = folder.parent / "evil.py"
    evil.write_text(EVIL.format(marker=str(marker), entry="main"))
    held = folder / "campaign.yaml"
    data = yaml.safe_load(held.read_text())
    edit(data, str(evil))
    held.write_text(yaml.safe_dump(data, sort_keys=False))
    return evil


def test_campaign_rerun_of_a_received_folder_executes_nothing_without_trust(folder, tmp_path, cli):
    marker = tmp_path / "marker"
    _bring(folder, marker, lambda data, evil: data["overrides"].update(program=evil))
    result = cli("campaign", "rerun", folder, "1", "-o", tmp_path / "run.mcap")
    assert result.exit_code == 2 and "evil.py" in result.output and "--trust" in result.output, result.output
    with pytest.raises(UntrustedProgram):
        rerun_campaign(folder, 1, tmp_path / "run.mcap")
    assert not marker.exists() and not (tmp_path / "run.mcap").exists()
    assert cli("campaign", "rerun", folder, "1", "-o", tmp_path / "run.mcap", "--trust").exit_code in (0, 1)
    assert marker.read_text() == "ran"


def test_resuming_a_received_folder_with_its_own_campaign_file_asks_for_trust(folder, tmp_path, cli):
    marker = tmp_path / "marker"
    _bring(folder, marker, lambda data, evil: data["overrides"].update(program=evil))
    (folder / "results.parquet").unlink()          # runs left to fly
    held = folder / "campaign.yaml"
    result = cli("campaign", "run", held, "-o", folder, "--resume", "--workers", "1")
    assert result.exit_code == 2 and "evil.py" in result.output and "--trust" in result.output, result.output
    assert not marker.exists()
    result = cli("campaign", "run", held, "-o", folder, "--resume", "--workers", "1", "--trust")
    assert result.exit_code == 0, result.output
    assert marker.read_text() == "ran"


def test_resuming_with_ones_own_campaign_never_flies_the_folders(folder, tmp_path, cli):
    """The folder's campaign names a program; the user's own file does not: the folder
    is refused as another campaign, and nothing of it runs."""
    marker = tmp_path / "marker"
    _bring(folder, marker, lambda data, evil: data["overrides"].update(program=evil))
    result = cli("campaign", "run", tmp_path / "sender" / "campaign.yaml", "-o", folder, "--resume",
                 "--workers", "1")
    assert result.exit_code == 2 and "another campaign" in result.output, result.output
    assert not marker.exists()


def test_a_choice_among_programs_names_every_one(folder, tmp_path):
    marker = tmp_path / "marker"
    (tmp_path / "good.py").write_text("def main(fc):\n    fc.step()\n")

    def choose(data, evil):
        data["overrides"]["program"] = str(tmp_path / "good.py")
        data["dispersions"]["flown"] = {"path": "program", "kind": "choice",
                                        "values": [str(tmp_path / "good.py"), evil]}

    _bring(folder, marker, choose)
    with pytest.raises(UntrustedProgram) as refused:
        run_campaign(folder / "campaign.yaml", folder, workers=1, resume=True)
    assert "good.py" in str(refused.value) and "evil.py" in str(refused.value)
    assert not marker.exists()
