"""Benchmark: a first flight on a cold kernel cache, with and without a second process
compiling beside it (:mod:`rocketsim.jit.beside`, ``ROCKETSIM_COMPILE_BESIDE``).

Whole processes, each on an empty cache of its own: ``rocketsim fly`` of the Falcon 9
mission to its end, of its first 30 s (a short flight: its compiled runs are queued
beside but it may end before they are compiled), and of the station coasting (a
coast's runs). Each pair runs with and without the second process one after the
other, the order alternating from round to round; printed: the wall and CPU seconds
of the flight's own process (the second process's CPU is not counted: it outlives a
short flight), the machine's load before each run, and the ratio with / without.
Nothing is asserted.

Only with ``ROCKETSIM_BENCH_COLD=1`` (each run compiles every kernel of a flight, a
minute or more; the Falcon 9 pair several on a loaded machine); rounds:
``ROCKETSIM_BENCH_ROUNDS`` (default 1).

Run: ``ROCKETSIM_BENCH_COLD=1 python -m pytest tests/benchmarks/test_bench_compiled_beside.py -s``.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

import pytest

from tests.benchmarks.timing import load_text, whole_process
from tests.cold_cache import cold_env

ROOT = Path(__file__).resolve().parents[2]
ROUNDS = int(os.environ.get("ROCKETSIM_BENCH_ROUNDS", "1"))

pytestmark = pytest.mark.skipif(os.environ.get("ROCKETSIM_BENCH_COLD") != "1",
                                reason="cold-cache benchmarks: set ROCKETSIM_BENCH_COLD=1")


def _cold_flight(args: list[str], beside: bool, folder: Path) -> tuple[float, float, str]:
    """(wall s, CPU s, load before) of ``rocketsim fly *args`` on the empty cache ``folder``."""
    folder.mkdir()
    load = load_text()
    env = cold_env(folder, ROCKETSIM_COMPILE_BESIDE="1" if beside else "0")
    env.pop("PYTHONDONTWRITEBYTECODE", None)            # as a user's Python runs
    command = [sys.executable, "-m", "rocketsim_cli.main", "fly", *args, "-o", str(folder / "run.mcap")]
    wall, cpu, _ = whole_process(command, ROOT, env)
    return wall, cpu, load


@pytest.mark.parametrize("args", [["scenarios/falcon9-leo.yaml"],
                                  ["scenarios/falcon9-leo.yaml", "--duration", "30s"],
                                  ["scenarios/iss-coast.yaml"]], ids=["falcon9-leo", "falcon9-leo-30s", "iss-coast"])
def test_a_cold_first_flight_with_and_without_compiling_beside(tmp_path, args):
    ratios = []
    for k in range(ROUNDS):
        times = {}
        for beside in ((True, False) if k % 2 == 0 else (False, True)):
            times[beside] = _cold_flight(args, beside, tmp_path / f"cache-{k}-{beside}")
        for beside in (True, False):
            wall, cpu, load = times[beside]
            print(f"\n[beside] cold rocketsim fly {' '.join(args)} {'with' if beside else 'without'} a second "
                  f"process: {wall:.1f} s wall, {cpu:.1f} s CPU of the flight's process ({load} before)", end="")
        ratios.append(times[True][0] / times[False][0])
        print(f"\n[beside] with / without: {ratios[-1]:.2f}x wall", end="")
    print(f"\n[beside] {' '.join(args)}: with / without over {ROUNDS} round(s): "
          + ", ".join(f"{r:.2f}" for r in ratios) + f" ({load_text()} after)")
