"""Benchmark: start-up of the command line, whole processes, cold and warm kernel cache.

Printed (never asserted), each against ``python -c pass`` measured in the same
run, with the machine's load (``os.getloadavg()``); wall and CPU seconds of the
child process (CPU is steadier on a loaded machine), which keeps its modules'
bytecode as an installed Python does (see :data:`BYTECODE_OFF`):

* ``rocketsim --help``, ``validate``, ``schema``: target <= 0.3 s (``validate`` of a
  scenario from a real site, and of one that starts in orbit, whose start point is
  computed with numpy while it is validated);
* a warm ``rocketsim fly scenarios/iss-coast.yaml --duration 0``: target <= 0.6 s,
  beside the floor of any compiled flight: a fresh process that imports numba and
  loads one trivial kernel from its cache;

and, only with ``ROCKETSIM_BENCH_COLD=1`` in the environment (each compiles
every kernel of a flight from an empty cache, a minute or more on a loaded
machine, too long for every run of the suite):

* a cold ``rocketsim fly scenarios/iss-coast.yaml`` (target <= 8 s) and the ratio
  cold / warm, with the kernels and signatures compiled;
* a cold Falcon 9 mission, ``scenarios/falcon9-leo.yaml`` (target <= 20 s);
* ``rocketsim compile`` of three scenarios, and of the Falcon 9 mission alone, on 1 and
  on 2 processes: the speed-up.

Run: ``ROCKETSIM_BENCH_COLD=1 python -m pytest tests/benchmarks/test_bench_startup.py -s``.

Last figures (2-core machine, load 0.7-1.3): ``--help`` 0.107 s, ``validate``
0.217 s (falcon9-leo; 0.266 s for iss-coast, whose orbit start imports numpy and
the elements' modules), ``schema`` 0.237 s; warm ``fly --duration 0`` 0.78 s
against a floor of 0.58 s (numba's first cached kernel is mostly its registries
and the ``scipy.linalg`` its BLAS check imports, some 0.08 s; a flight imports
scipy's integrator at its first ``fc.predict`` and its hull at its first
touchdown, not at start-up); cold iss-coast 6.1 s (warm 1.9 s: 3.3x); cold
Falcon 9 25.8 s, 102 kernels, 107 signatures; ``rocketsim compile`` 1.12x on 2
processes (an earlier session).
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

import pytest

from tests.benchmarks.timing import load_text, whole_process

ROOT = Path(__file__).resolve().parents[2]
COLD = os.environ.get("ROCKETSIM_BENCH_COLD") == "1"
cold = pytest.mark.skipif(not COLD, reason="cold-cache benchmarks: set ROCKETSIM_BENCH_COLD=1")
ROCKETSIM = [sys.executable, "-m", "rocketsim_cli.main"]


# A Python as a user has it keeps its modules' bytecode (pip compiles it at install, an
# editable install writes it on the first import); an environment that sets
# PYTHONDONTWRITEBYTECODE (as some sandboxes and CI images do) recompiles every module
# from source in every process, some 0.1-0.2 s of each start-up here. The children run
# as a user's Python does; the first, untimed run of each command writes the bytecode.
BYTECODE_OFF = "PYTHONDONTWRITEBYTECODE"


def _user_env(env: dict | None = None) -> dict:
    return {k: v for k, v in (os.environ if env is None else env).items() if k != BYTECODE_OFF}


def _run(command: list[str], env: dict | None = None) -> tuple[float, float]:
    """(wall s, CPU s) of ``command`` run to its end in ROOT with the bytecode cache on
    (:func:`_user_env`); it must succeed."""
    return whole_process(command, ROOT, _user_env(env))[:2]


def _bytecode_note() -> str:
    return (f"bytecode cached as installed ({BYTECODE_OFF} was set here: "
            f"{os.environ.get(BYTECODE_OFF, 'no')})")


def _best(command: list[str], repeats: int = 2, env: dict | None = None) -> tuple[float, float]:
    runs = [_run(command, env) for _ in range(repeats)]
    return min(r[0] for r in runs), min(r[1] for r in runs)


def _cache_env(folder: Path) -> dict:
    env = {k: v for k, v in os.environ.items() if k != "NUMBA_CACHE_DIR"}
    env["ROCKETSIM_CACHE_DIR"] = str(folder)
    return env


def _compiled(folder: Path) -> str:
    """Kernels (index files) and signatures (code files) in a cache folder."""
    return (f"{len(list(folder.rglob('*.nbi')))} kernels, "
            f"{len(list(folder.rglob('*.nbc')))} signatures")


def test_light_commands_against_python():
    base = _best([sys.executable, "-c", "pass"])
    print(f"\n[startup] {load_text()}; {_bytecode_note()}; python -c pass: {base[0]:.3f} s wall, "
          f"{base[1]:.3f} s CPU")
    for args in (["--help"], ["validate", "scenarios/falcon9-leo.yaml"],
                 ["validate", "scenarios/iss-coast.yaml"], ["schema"]):
        _run(ROCKETSIM + args)                               # writes the bytecode
        wall, cpu = _best(ROCKETSIM + args)
        print(f"[startup] rocketsim {' '.join(args)}: {wall:.3f} s wall ({wall / base[0]:.1f}x python), "
              f"{cpu:.3f} s CPU (target <= 0.3 s)")


# One numba kernel loaded from its cache in a fresh process: numba's import, its CPU
# target's registries (which import scipy.linalg for BLAS) and one cached kernel, the
# least any process that runs a compiled step pays.
ONE_KERNEL = """
import numba
@numba.njit(cache=True)
def twice(x):
    return 2.0 * x
twice(1.0)
"""


def test_warm_fly_to_its_first_step(tmp_path):
    command = ROCKETSIM + ["fly", "scenarios/iss-coast.yaml", "--duration", "0", "-o",
                           str(tmp_path / "zero.mcap")]
    (tmp_path / "one_kernel.py").write_text(ONE_KERNEL)
    one_kernel = [sys.executable, str(tmp_path / "one_kernel.py")]
    _run(command)                                            # warm the caches
    _run(one_kernel)
    base = _best([sys.executable, "-c", "pass"])
    floor = _best(one_kernel)
    wall, cpu = _best(command)
    print(f"\n[startup] {load_text()}; {_bytecode_note()}; warm rocketsim fly iss-coast --duration 0: "
          f"{wall:.2f} s wall, "
          f"{cpu:.2f} s CPU (target <= 0.6 s); python -c pass {base[0]:.3f} s; one cached numba "
          f"kernel in a fresh process {floor[0]:.2f} s wall, {floor[1]:.2f} s CPU: the flight "
          f"{wall / floor[0]:.1f}x that floor")


def _cold_and_warm(scenario: str, tmp_path: Path, target: float) -> None:
    folder = tmp_path / "cache"
    env = _cache_env(folder)
    command = ROCKETSIM + ["fly", scenario, "-o", str(tmp_path / "run.mcap")]
    cold_wall, cold_cpu = _run(command, env)
    warm_wall, warm_cpu = _run(command, env)
    print(f"\n[startup] {load_text()}; cold rocketsim fly {scenario}: {cold_wall:.1f} s wall, "
          f"{cold_cpu:.1f} s CPU (target <= {target:g} s), {_compiled(folder)}; warm "
          f"{warm_wall:.1f} s wall, {warm_cpu:.1f} s CPU; cold / warm {cold_wall / warm_wall:.1f}x wall, "
          f"{cold_cpu / warm_cpu:.1f}x CPU")


@cold
def test_cold_coasting_flight(tmp_path):
    _cold_and_warm("scenarios/iss-coast.yaml", tmp_path, 8.0)


@cold
def test_cold_falcon9_mission(tmp_path):
    _cold_and_warm("scenarios/falcon9-leo.yaml", tmp_path, 20.0)


@cold
@pytest.mark.parametrize("scenarios", [
    ["scenarios/iss-coast.yaml", "scenarios/spaceport-ballistic.yaml", "scenarios/falcon9-hop.yaml"],
    ["scenarios/falcon9-leo.yaml"]])     # one scenario: on 2 cores its runs compile beside it
def test_compile_on_one_and_two_processes(tmp_path, scenarios):
    times = {}
    for jobs in (1, 2):
        folder = tmp_path / f"cache-{jobs}"
        times[jobs] = _run(ROCKETSIM + ["compile", "-j", str(jobs), *scenarios], _cache_env(folder))
        print(f"\n[startup] {load_text()}; rocketsim compile -j {jobs} ({len(scenarios)} scenarios): "
              f"{times[jobs][0]:.1f} s wall, {times[jobs][1]:.1f} s CPU, {_compiled(folder)}")
    print(f"[startup] compile speed-up on 2 processes: {times[1][0] / times[2][0]:.2f}x wall "
          f"(CPU spent {times[2][1] / times[1][1]:.2f}x that of one process)")
