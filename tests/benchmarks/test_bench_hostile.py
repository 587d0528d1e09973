"""Benchmark: how long a careless or hostile input takes to be refused, whole processes.

The five inputs that once hung, crashed or passed silently (a "billion laughs"
YAML given to ``validate``; a program calling ``fc.cruise(1e30)``, pointing at
NaN or 1e300 degrees, sleeping 1e30 s, waiting on a predicate that returns
None, or calling ``sys.exit(3)``; ``fly -o`` into a folder that does not exist)
are each run as a fresh ``rocketsim`` process, warm kernel cache, and must
exit 2 with the file and line (or the option) named. Printed, never asserted:
each one's wall and CPU time (target: none over 5 s), against the same
command on a valid input of the same size measured in the same run (the
coasting probe flying 1 s with a program that sleeps; ``validate`` of that
scenario), with the machine's load.
"""

from __future__ import annotations

import sys

import pytest

from tests.benchmarks.timing import load_text, whole_process
from tests.conftest import MISSION, VEHICLE

ROCKETSIM = [sys.executable, "-m", "rocketsim_cli.main"]

LAUGHS = "\n".join(['a: &a ["lol","lol","lol","lol","lol","lol","lol","lol","lol"]']
                   + [f'{chr(98 + k)}: &{chr(98 + k)} [*{chr(97 + k)},*{chr(97 + k)},*{chr(97 + k)},'
                      f'*{chr(97 + k)},*{chr(97 + k)},*{chr(97 + k)},*{chr(97 + k)},*{chr(97 + k)},'
                      f'*{chr(97 + k)}]' for k in range(8)]) + "\n"

PROGRAMS = {
    "fc.cruise(1e30)": "def main(fc):\n    fc.cruise(1e30)\n",
    "fc.point(nan, 0)": "def main(fc):\n    fc.point(float('nan'), 0.0)\n",
    "fc.point(1e300, 0)": "def main(fc):\n    fc.point(1e300, 0.0)\n",
    "fc.sleep(1e30)": "def main(fc):\n    fc.sleep(1e30)\n",
    "fc.wait_until(lambda: None)": "def main(fc):\n    fc.wait_until(lambda: None)\n",
    "sys.exit(3)": "import sys\n\n\ndef main(fc):\n    sys.exit(3)\n",
}
VALID = "def main(fc):\n    fc.sleep(0.5)\n"


@pytest.fixture(scope="module")
def valid(tmp_path_factory):
    """The valid input's scenario, and the whole-process times of flying it for 1 s and
    of validating it (measured once, in this run)."""
    folder = tmp_path_factory.mktemp("valid")
    (folder / "vehicle.yaml").write_text(VEHICLE)
    (folder / "mission.yaml").write_text(MISSION.format(duration="1 s"))
    (folder / "program.py").write_text(VALID)
    path = folder / "scenario.yaml"
    path.write_text("name: test\nvehicle: vehicle.yaml\nmission: mission.yaml\nprogram: program.py\n")
    fly = whole_process(ROCKETSIM + ["fly", str(path), "-o", str(folder / "valid.mcap")])
    validate = whole_process(ROCKETSIM + ["validate", str(path)])
    print(f"\n[hostile] {load_text()}; the valid input: fly {fly[0]:.2f} s wall, {fly[1]:.2f} s CPU; "
          f"validate {validate[0]:.2f} s wall, {validate[1]:.2f} s CPU")
    return path, {"fly": fly, "validate": validate}


def _report(name: str, timing: tuple, base: tuple) -> None:
    wall, cpu, _ = timing
    print(f"\n[hostile] {load_text()}; {name}: {wall:.2f} s wall, {cpu:.2f} s CPU (target <= 5 s; "
          f"{wall / base[0]:.2f}x the valid input's {base[0]:.2f} s wall)")


@pytest.mark.parametrize("program", list(PROGRAMS))
def test_a_hostile_program_is_refused_as_fast_as_a_valid_one_flies(program, valid, scenario, tmp_path):
    path = scenario(PROGRAMS[program], duration="1 s")
    timing = whole_process(ROCKETSIM + ["fly", str(path), "-o", str(tmp_path / "run.mcap")], status=2)
    line = 5 if program == "sys.exit(3)" else 2
    assert f"program.py:{line}" in timing[2] and "Traceback" not in timing[2], timing[2]
    _report(program, timing, valid[1]["fly"])


def test_a_billion_laughs_and_a_missing_folder_are_refused_at_once(valid, write, tmp_path):
    laughs = write("laughs.yaml", LAUGHS)
    refused = whole_process(ROCKETSIM + ["validate", str(laughs)], status=2)
    assert "laughs.yaml:" in refused[2] and "Traceback" not in refused[2], refused[2]
    _report("billion laughs (validate)", refused, valid[1]["validate"])
    missing = whole_process(ROCKETSIM + ["fly", str(valid[0]), "-o", str(tmp_path / "no" / "run.mcap")],
                            status=2)
    assert "--output" in missing[2] and "nothing was written" in missing[2], missing[2]
    _report("fly -o into a missing folder", missing, valid[1]["fly"])
