"""Mutated designs under review: ``rocketsim vehicle`` reviews them or exits 2 at file:line.

Hypothesis starts from the hobby rocket (its scenario: the rail and the site;
its vehicle file: the airframe's geometry, the motor's grains, the parachutes,
the nose and fins, and structural limits ``aero.limits``) and changes one to
four things in them as :mod:`tests.fuzz.test_fuzz_files` does (a field dropped,
renamed or duplicated, a value replaced by a hostile one or scaled, the text
edited). The design review (centre of pressure and static margin, thrust to
weight, rail exit, peak loads against the limits) must then print, or the
command exit 2 naming a file and line: never a traceback, a hang or a gigabyte.
Nothing flies, so each input takes milliseconds.
"""

from __future__ import annotations

import tempfile
from pathlib import Path

import yaml
from hypothesis import given, settings, strategies as st

from tests.conftest import ROOT
from tests.fuzz.harness import AT_LINE, bounded, examples, invoke, write_files
from tests.fuzz.test_fuzz_files import mutate

_SCENARIO = yaml.safe_load((ROOT / "scenarios" / "hobby-rocket.yaml").read_text())
_VEHICLE = yaml.safe_load((ROOT / "vehicles" / "hobby-rocket.yaml").read_text())
_VEHICLE["stages"][0]["motors"][0]["file"] = str(ROOT / "motors" / "Cesaroni_4895L1395-P.eng")
_VEHICLE["aero"]["limits"] = {"q_alpha": 500000, "axial_load": "40 g"}
DESIGN = {"scenario.yaml": {**_SCENARIO, "vehicle": "rocket.yaml"}, "rocket.yaml": _VEHICLE}


@st.composite
def designs(draw) -> dict[str, str]:
    return mutate(draw, DESIGN)


def test_the_unmutated_design_is_reviewed(tmp_path):
    for name, data in DESIGN.items():
        (tmp_path / name).write_text(yaml.safe_dump(data, sort_keys=False))
    code, output = invoke("vehicle", tmp_path / "scenario.yaml")
    assert code == 0 and "structural limits 40 g axial" in output, output


@settings(max_examples=examples(0.5))
@given(designs())
def test_a_mutated_design_is_reviewed_or_refused_at_its_line(files):
    with tempfile.TemporaryDirectory() as folder:
        folder = Path(folder)
        write_files(folder, files)
        with bounded("designs"):
            code, output = invoke("vehicle", folder / "scenario.yaml")
    assert code == 0 or (code == 2 and AT_LINE.search(output)), output
