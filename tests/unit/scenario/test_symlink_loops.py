"""A loop of symbolic links among a scenario's files is a located error, exit 2: the
scenario itself, a file it references, a vehicle's motor file."""

from __future__ import annotations

import os

import pytest

from rocketsim.errors import InputError
from rocketsim.scenario.models import VehicleSpec
from rocketsim.scenario.validation import validate
from rocketsim.scenario.yaml_source import read_yaml
from tests.unit.scenario.test_scenario_errors import assert_clean_error


def _loop(folder, name: str):
    """``name`` and ``name``.other in ``folder``, each a symbolic link to the other."""
    first, second = folder / name, folder / f"{name}.other"
    os.symlink(second.name, first)
    os.symlink(first.name, second)
    return first


def test_a_scenario_that_is_a_loop_is_refused(cli, tmp_path):
    result = cli("fly", _loop(tmp_path, "scenario.yaml"), "-o", tmp_path / "run.mcap")
    assert_clean_error(result, "scenario.yaml", "Too many levels of symbolic links")


def test_a_referenced_file_that_is_a_loop_is_located(cli, tmp_path):
    _loop(tmp_path, "vehicle.yaml")
    scenario = tmp_path / "scenario.yaml"
    scenario.write_text("name: loop\nvehicle: vehicle.yaml\nmission: mission.yaml\n")
    result = cli("fly", scenario, "-o", tmp_path / "run.mcap")
    assert_clean_error(result, "scenario.yaml:2:", "vehicle", "a loop of symbolic links")
    assert not (tmp_path / "run.mcap").exists()


def test_a_motor_file_that_is_a_loop_is_located(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    _loop(tmp_path, "motor.eng")
    vehicle = tmp_path / "vehicle.yaml"
    vehicle.write_text("name: x\nstages:\n  - name: s\n    length: 1 m\n    diameter: 0.1 m\n"
                       "    structure_mass: 1 kg\n    motors:\n      - name: m\n        file: motor.eng\n")
    with pytest.raises(InputError) as error:
        validate(read_yaml(vehicle), VehicleSpec)
    assert error.value.line == 9 and error.value.field == "stages.0.motors.0.file", str(error.value)
    assert "symbolic links" in str(error.value)
