"""Start-up of the command line: light commands stay light.

``rocketsim --help``, ``validate``, ``schema`` and ``replay`` of a run's summary
read files and print; they must not import numba (half a second and more),
scipy, or the simulator itself (``rocketsim.sim.world`` and the kernels'
callers). Each command runs in a fresh interpreter, which reports the modules
it ended up with.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[3]
HEAVY = ("numba", "llvmlite", "scipy", "rocketsim.sim.world", "rocketsim.telemetry.splice")

_RUN = """
import json, sys
from rocketsim_cli.main import main
try:
    main(sys.argv[2:], prog_name="rocketsim")
except SystemExit as exit:
    code = exit.code
print(json.dumps({"code": code, "heavy": [m for m in json.loads(sys.argv[1]) if m in sys.modules]}))
"""


def _heavy_imports(*args: str, heavy: tuple[str, ...] = HEAVY) -> tuple[int, list[str]]:
    done = subprocess.run([sys.executable, "-c", _RUN, json.dumps(heavy), *map(str, args)],
                          cwd=ROOT, capture_output=True, text=True, check=True)
    result = json.loads(done.stdout.strip().splitlines()[-1])
    return result["code"], result["heavy"]


@pytest.mark.parametrize("args", [
    ["--help"],
    ["fly", "--help"],
    ["validate", "scenarios/iss-coast.yaml", "vehicles/cubesat-6u.yaml"],
    ["schema"],
    ["schema", "--kind", "vehicle"],
    ["windows", "--help"],
    ["ephemeris", "--help"],
])
def test_light_commands_import_neither_numba_nor_scipy_nor_the_simulator(args):
    code, heavy = _heavy_imports(*args)
    assert code in (0, None)
    assert heavy == []


@pytest.mark.parametrize("args", [
    ["--help"],
    ["schema"],
    ["validate", "scenarios/falcon9-leo.yaml", "vehicles/cubesat-6u.yaml", "scenarios/sites/mahia-lc1.yaml"],
    ["validate", "scenarios/electron-sso.yaml", "scenarios/measured/bella-lui.yaml"],
])
def test_commands_that_compute_nothing_do_not_import_numpy(args):
    """numpy alone is a tenth of a second of start-up: validating a real site's scenario,
    its weather and its vehicle computes nothing with arrays (a scenario that starts in
    orbit or on the procedural classic range does: its start point and its pads are
    computed while it is validated)."""
    code, heavy = _heavy_imports(*args, heavy=("numpy",))
    assert code in (0, None)
    assert heavy == []


def test_a_bad_choice_is_still_refused_without_importing_the_library():
    code, heavy = _heavy_imports("schema", "--kind", "rocket")
    assert code == 2
    assert heavy == []


def test_replay_of_a_summary_does_not_load_the_simulator(scenario, tmp_path):
    from rocketsim.scenario.load import load
    from rocketsim.api.telemetry_flight import fly_to_file as fly

    run_file = tmp_path / "run.mcap"
    fly(load(scenario(duration="1 s")), run_file)
    code, heavy = _heavy_imports("replay", run_file)
    assert code == 0
    assert heavy == []


def test_the_command_line_runs_openblas_on_one_thread_unless_told_otherwise():
    """OpenBLAS starts a thread per core beside the main one when numpy is imported;
    the command line asks it for one (its BLAS threads only cost a flight's start).
    The process's OS threads after importing the command line and numpy, read from
    /proc (Linux): one; a user's own OPENBLAS_NUM_THREADS is kept."""
    status = Path("/proc/self/status")
    if not status.exists():
        pytest.skip("threads are read from /proc")
    count = ("import rocketsim_cli.main, numpy, os; "
             "print([l for l in open('/proc/self/status') if l.startswith('Threads:')][0].split()[1], "
             "os.environ['OPENBLAS_NUM_THREADS'])")
    env = {k: v for k, v in os.environ.items() if k != "OPENBLAS_NUM_THREADS"}
    done = subprocess.run([sys.executable, "-c", count], cwd=ROOT, capture_output=True, text=True,
                          check=True, env=env)
    assert done.stdout.split() == ["1", "1"]
    done = subprocess.run([sys.executable, "-c", count], cwd=ROOT, capture_output=True, text=True,
                          check=True, env={**env, "OPENBLAS_NUM_THREADS": "2"})
    assert done.stdout.split() == ["2", "2"]
