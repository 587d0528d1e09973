"""A YAML file's bytes are parsed once per process, and every read still reads what the file
holds now: the parse is found by the bytes themselves, not by the file's name, size or times,
and each caller gets data of its own (a campaign changes its runs' data with overrides)."""

import os

import pytest

from rocketsim.errors import InputError
from rocketsim.scenario import yaml_source
from rocketsim.scenario.load import load
from rocketsim.scenario.yaml_source import read_yaml
from tests.conftest import ROOT


def test_a_file_changed_in_place_with_the_same_size_and_times_is_read_anew(tmp_path):
    path = tmp_path / "part.yaml"
    path.write_text("mass: 100\nname: a\n")
    stat = path.stat()
    assert read_yaml(path).data == {"mass": 100, "name": "a"}
    path.write_text("mass: 900\nname: b\n")         # the same number of bytes
    os.utime(path, ns=(stat.st_atime_ns, stat.st_mtime_ns))
    assert path.stat().st_size == stat.st_size and path.stat().st_mtime_ns == stat.st_mtime_ns
    assert read_yaml(path).data == {"mass": 900, "name": "b"}


def test_the_same_bytes_are_parsed_once_and_each_reader_gets_its_own_data(tmp_path, monkeypatch):
    parsed = []
    parse = yaml_source._parse
    monkeypatch.setattr(yaml_source, "_parse", lambda raw, path: parsed.append(path) or parse(raw, path))
    text = "stages:\n  - name: booster\n    engines: [{thrust: 1.0}]\nwhen: 2026-12-06T17:00:00Z\n"
    a, b = tmp_path / "a.yaml", tmp_path / "b.yaml"
    a.write_text(text)
    b.write_text(text)
    first = read_yaml(a)
    first.data["stages"][0]["engines"][0]["thrust"] = 2.0
    first.data["stages"].append("more")
    first.positions.clear()
    second = read_yaml(b)
    assert parsed == [a]            # the second file's bytes are the first's: not parsed again
    assert second.path == b
    assert second.data["stages"] == [{"name": "booster", "engines": [{"thrust": 1.0}]}]
    assert second.position(("stages", 0, "engines")) == (3, 5)      # the key, third line, fifth column
    assert read_yaml(a).data == second.data


def test_a_file_that_does_not_parse_names_itself_each_time(tmp_path):
    bad = "a: [1, 2\n"
    for name in ("one.yaml", "two.yaml"):
        path = tmp_path / name
        path.write_text(bad)
        with pytest.raises(InputError) as raised:
            read_yaml(path)
        assert str(raised.value.file) == str(path) and raised.value.line is not None


def test_a_scenario_loaded_twice_with_overrides_is_the_same_as_loaded_once():
    scenario = ROOT / "scenarios" / "falcon9-leo.yaml"
    override = {"vehicle.stages[booster].structure_mass": "9 t"}
    changed = load(scenario, override).scenario
    plain = load(scenario).scenario
    assert load(scenario, override).scenario == changed
    assert plain != changed
    assert load(scenario).scenario == plain


def test_the_parsed_files_kept_are_bounded_in_bytes(tmp_path, monkeypatch):
    monkeypatch.setattr(yaml_source, "PARSED_BYTES", 100)
    monkeypatch.setattr(yaml_source, "_PARSED", {})
    for k in range(6):
        path = tmp_path / f"f{k}.yaml"
        path.write_text(f"name: file number {k}\nvalue: {k}\n" + "# padding\n" * 3)
        assert read_yaml(path).data == {"name": f"file number {k}", "value": k}
        assert 0 < sum(map(len, yaml_source._PARSED)) <= 100
