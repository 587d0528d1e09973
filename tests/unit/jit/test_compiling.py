"""A cold kernel cache: announced on a terminal, silent elsewhere, warmed by ``rocketsim compile``;
and a flight compiles only the kernels it flies.

The first flight on a machine compiles its kernels; ``rocketsim fly`` says so on
a terminal, and ``rocketsim compile`` compiles them ahead into the cache. Here the cache of a small flight is copied and one kernel the
flight calls at its end (``orbit_figures``, the summary's orbit) is deleted from
the copy, so that ``rocketsim fly`` over the copy compiles exactly that one
kernel (a few seconds, not the minute of a whole cold cache). stderr is a
pseudo-terminal (the pty module) in one run and a pipe in the other.

The same copy, without the flight model's step instead, shows what compiling the
step brings in: for a body without an n-body field, not the hold of the other
bodies (``third_bodies.hold_field`` and the ephemeris it evaluates, about a third
of a cold coasting flight), which the step's ``nbody=None`` compiles away.

A coasting flight from an empty cache, its compilations counted by numba's
compile events, compiles no more than :data:`COLD_COAST_KERNELS` signatures
(kernels and the numba library routines they call, about 0.1 s each): not the
other bodies' pull (``held_perturbation``, kept out by the derivative's
``nbody=None``), nor the array routines and error messages of ``np.cross``,
``np.dot`` or a broadcast copy (the orbit's elements on components, a loop).
"""

from __future__ import annotations

import json
import os
import pty
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from rocketsim.jit import cache_dir
from rocketsim.scenario.load import load
from rocketsim.api.telemetry_flight import fly_to_file as fly
from rocketsim_cli.compiling import FIRST_RUN
from tests.cold_cache import cold_env

KERNEL = "sample_figures.orbit_figures-*"


def _cache_without(path, tmp_path, *kernels):
    """(environment, cache folder): a copy of the kernel cache after a flight of
    ``path``, without the files of ``kernels`` (file name patterns)."""
    fly(load(path), tmp_path / "warm.mcap")            # every kernel of the flight cached
    warm = Path(cache_dir())
    root = tmp_path / "cache"
    # another test process may be saving a kernel meanwhile: numba writes a temporary
    # file and renames it, and a compiling process removes its marker below .compiling
    # once saved, so a copy that lists either may not find it
    shutil.copytree(warm, root / warm.name,
                    ignore=shutil.ignore_patterns("*.tmp.*", ".lock", ".compiling"))
    for kernel in kernels:
        removed = list((root / warm.name).rglob(kernel))
        assert removed, f"the flight's cache holds {kernel}"
        for file in removed:
            file.unlink()
    return cold_env(root), root / warm.name


@pytest.fixture
def one_cold_kernel(scenario, tmp_path):
    """(scenario, environment) whose kernel cache lacks only ``orbit_figures``."""
    path = scenario(duration="1 s")
    return (path, *_cache_without(path, tmp_path, KERNEL))


def _fly(path, env, tmp_path, stderr):
    return subprocess.Popen([sys.executable, "-m", "rocketsim_cli.main", "fly", str(path),
                             "-o", str(tmp_path / "cold.mcap")],
                            env=env, stdout=subprocess.PIPE, stderr=stderr)


def test_a_terminal_sees_the_kernels_compile(one_cold_kernel, tmp_path):
    path, env, cache = one_cold_kernel
    master, slave = pty.openpty()
    process = _fly(path, env, tmp_path, slave)
    os.close(slave)
    shown = b""
    while True:
        try:
            chunk = os.read(master, 4096)
        except OSError:                                  # EIO: the child closed the terminal
            break
        if not chunk:
            break
        shown += chunk
    os.close(master)
    assert process.wait(timeout=300) == 0
    text = shown.decode()
    assert f"{FIRST_RUN}: 0 compiled stepping.sample_figures.orbit_figures" in text
    assert "compiled 1 flight kernel for this machine in" in text
    assert list(cache.rglob(KERNEL)), "the compiled kernel went back into the cache"


def test_off_a_terminal_nothing_is_said(one_cold_kernel, tmp_path):
    path, env, cache = one_cold_kernel
    process = _fly(path, env, tmp_path, subprocess.PIPE)
    _, errors = process.communicate(timeout=300)
    assert process.returncode == 0
    assert list(cache.rglob(KERNEL)), "the kernel did compile"
    assert errors.decode() == ""


def test_compile_flies_the_scenarios_into_the_cache(one_cold_kernel, tmp_path):
    path, env, cache = one_cold_kernel
    done = subprocess.run([sys.executable, "-m", "rocketsim_cli.main", "compile", str(path), "-j", "2"],
                          env=env, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    assert f"{path}: flown in " in done.stderr                  # one line per scenario off a terminal
    assert "1 kernel compiled in its process" in done.stderr
    assert "compiled 1 kernel for 1 scenario in" in done.stdout
    # one process per scenario, the spare core compiling its runs beside it
    assert "with 1 process and 1 more compiling beside into" in done.stdout
    assert str(cache) in done.stdout
    assert list(cache.rglob(KERNEL))


def test_compile_names_a_bad_scenario_and_exits_2(write, tmp_path):
    bad = write("bad.yaml", "name: bad\nvehicle: missing.yaml\nmission: missing.yaml\n")
    done = subprocess.run([sys.executable, "-m", "rocketsim_cli.main", "compile", str(bad)],
                          capture_output=True, text=True, timeout=300)
    assert done.returncode == 2
    assert "error:" in done.stderr and "bad.yaml" in done.stderr
    assert "Traceback" not in done.stderr


_COMPILED = """
import json, sys
from rocketsim.dynamics import rk4, third_bodies
from rocketsim.scenario.load import load
from rocketsim.api.telemetry_flight import fly_to_file as fly
fly(load(sys.argv[1]), sys.argv[2])
print(json.dumps({k.__name__: len(k.signatures) for k in (rk4.step_into, third_bodies.hold_field)}))
"""


def test_a_flight_without_an_n_body_field_does_not_compile_its_hold(scenario, tmp_path):
    # a coasting body about Earth alone: its step (and advance, and the coast runs that
    # call them) compiled afresh in a fresh process, the rest from the cache
    path = scenario(duration="1 s")
    env, _ = _cache_without(path, tmp_path, "rk4.step_into-*", "rk4.advance-*", "runs.coast_run-*")
    done = subprocess.run([sys.executable, "-c", _COMPILED, str(path), str(tmp_path / "cold.mcap")],
                          env=env, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    compiled = json.loads(done.stdout.strip().splitlines()[-1])
    assert compiled["step_into"] >= 1, "the flight compiled its step"
    assert compiled["hold_field"] == 0


# signatures a cold one-second coast about Earth compiles, telemetry written (41 measured:
# the flight's kernels and their numba routines, the readings of a state in one call and the
# drag a body senses in its figures among them); with np.cross, np.dot, a broadcast copy,
# the n-body pull and the small helpers as kernels of their own, 85 with telemetry off
COLD_COAST_KERNELS = 41

_CENSUS = """
import collections, json, sys
from numba.core import event

compiled = collections.Counter()


class Census(event.Listener):
    def on_start(self, ev):
        f = ev.data["dispatcher"].py_func
        compiled[f"{f.__module__}.{f.__qualname__}"] += 1

    def on_end(self, ev):
        pass


event.register("numba:compile", Census())
from rocketsim.scenario.load import load
from rocketsim.api.telemetry_flight import fly_to_file as fly
fly(load(sys.argv[1]), sys.argv[2])
print(json.dumps(compiled))
"""


def test_a_cold_coast_compiles_only_the_kernels_it_flies(scenario, tmp_path):
    path = scenario(duration="1 s")           # a coasting body about Earth alone
    done = subprocess.run([sys.executable, "-c", _CENSUS, str(path), str(tmp_path / "cold.mcap")],
                          env=cold_env(tmp_path / "empty"), capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr
    compiled = json.loads(done.stdout.strip().splitlines()[-1])
    assert compiled["rocketsim.dynamics.rk4.step_into"] == 1, "the flight compiled its step"
    assert compiled["rocketsim.stepping.sample_figures.figures"] == 1, "and its telemetry"
    for name in compiled:
        assert "third_bodies" not in name, f"{name}: no n-body field, no pull of other bodies"
        assert "cross" not in name and "unicode" not in name, f"{name}: an array routine's error path"
    twice = {k: n for k, n in compiled.items() if k.startswith("rocketsim.") and n > 1}
    assert not twice, f"one signature per kernel of the flight: {twice}"
    assert sum(compiled.values()) <= COLD_COAST_KERNELS, sorted(compiled)
