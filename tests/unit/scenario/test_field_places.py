"""A field path walked through a loaded scenario reaches the fields the files write, with
their values and the readers of their units; a misspelt path is refused, and its nearest
valid path is the one meant. The reference is the shipped Falcon 9 files' own text
(vehicles/falcon9-block5.yaml: both booster engine groups ``isp_vacuum: 311 s``, the
second stage's ``structure_mass: 1910 kg``; scenarios/sites/cape-canaveral-slc40.yaml:
``latitude: 28.5619 deg``)."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from rocketsim.scenario.field_places import locate, nearest_path
from rocketsim.scenario.load import load
from rocketsim.scenario.models import Scenario
from rocketsim.scenario.paths import PathError, parse
from rocketsim.scenario.units import UnitError

ROOT = Path(__file__).resolve().parents[3]


@pytest.fixture(scope="module")
def scenario():
    return load(ROOT / "scenarios/falcon9-leo.yaml").scenario


def places(scenario, path: str):
    return locate(scenario, Scenario, parse(path), "")


def test_every_item_a_path_selects_is_named_with_its_value_and_unit(scenario):
    found = places(scenario, "vehicle.stages[booster].engines[*].isp_vacuum")
    assert [place.path for place in found] == [
        "vehicle.stages[booster].engines[Merlin 1D centre].isp_vacuum",
        "vehicle.stages[booster].engines[Merlin 1D ring].isp_vacuum"]
    assert [place.nominal for place in found] == [311.0, 311.0]
    assert found[0].read("300 s") == 300.0
    with pytest.raises(UnitError):          # a specific impulse is in seconds, not a mass
        found[0].read("300 kg")
    assert not found[0].angle


def test_an_item_by_index_and_by_name_is_the_same_field(scenario):
    [by_name] = places(scenario, "vehicle.stages[second stage].structure_mass")
    [by_index] = places(scenario, "vehicle.stages[1].structure_mass")
    assert by_name.nominal == by_index.nominal == 1910.0
    assert by_index.path == "vehicle.stages[1].structure_mass"
    assert by_name.read("1.91 t") == pytest.approx(1910.0)


def test_an_angle_is_known_by_its_refusal_of_a_bare_number(scenario):
    [latitude] = places(scenario, "site.latitude")
    assert latitude.angle
    assert latitude.nominal == pytest.approx(math.radians(28.5619), rel=1e-15)
    assert latitude.read("28.5619 deg") == latitude.nominal


@pytest.mark.parametrize("given, meant", [
    ("vehicle.stages[boster].engins[*].isp_vacum", "vehicle.stages[booster].engines[*].isp_vacuum"),
    ("site.latitud", "site.latitude"),
])
def test_a_misspelt_path_is_refused_and_repaired(scenario, given, meant):
    with pytest.raises(PathError):
        places(scenario, given)
    assert nearest_path(scenario, Scenario, parse(given)) == meant
    assert places(scenario, meant)


def test_a_field_that_is_a_value_has_no_field_below_it(scenario):
    with pytest.raises(PathError, match="has no field 'mass'"):
        places(scenario, "vehicle.stages[booster].structure_mass.mass")
