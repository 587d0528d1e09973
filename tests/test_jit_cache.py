"""The compiled-kernel cache key covers exactly what a kernel can read.

numba caches a kernel by its own file only; `rocketsim._jit` names the cache
folder for a hash of every kernel module and of the library modules those
import. The key must change when gravity changes (a kernel inlines it) and
must not change when the pure-Python simulation loop changes.
"""

import ast
from pathlib import Path

import numpy as np
import pytest

import rocketsim
from rocketsim._jit import _kernel_sources

PACKAGE = Path(rocketsim.__file__).resolve().parent
ROOT = PACKAGE.parent


def _names():
    return {path.relative_to(PACKAGE).as_posix() for path in _kernel_sources(PACKAGE)}



def _cold_env(tmp_path) -> dict:
    """This process's environment with ``tmp_path`` as the kernel cache (empty at first)."""
    import os
    env = {k: v for k, v in os.environ.items() if k != "NUMBA_CACHE_DIR"}
    env["ROCKETSIM_CACHE_DIR"] = str(tmp_path)
    return env


def _on_a_cold_cache(tmp_path, script: str, timeout: float = 300) -> str:
    """The last line printed by Python running ``script`` in ``tmp_path``, its kernel cache."""
    import subprocess
    import sys
    path = tmp_path / "script.py"
    path.write_text(script)
    done = subprocess.run([sys.executable, str(path)], capture_output=True, text=True,
                          env=_cold_env(tmp_path), check=True, cwd=tmp_path, timeout=timeout)
    return done.stdout.strip().splitlines()[-1]

def test_every_kernel_module_and_its_imports_are_hashed():
    names = _names()
    kernel_modules = {path.relative_to(PACKAGE).as_posix() for path in PACKAGE.rglob("*.py")
                      if "njit" in path.read_text()}
    assert kernel_modules <= names
    # derivative.py inlines gravity and reads the state layout and constants.
    assert {"bodies/gravity.py", "layout.py", "constants.py"} <= names


def test_pure_python_layers_do_not_invalidate_the_cache():
    names = _names()
    for module in ("sim/world.py", "flight/fc.py", "flight/autopilot.py", "scenario/models.py",
                   "telemetry/writer.py"):
        assert module not in names


def test_a_submodule_named_on_a_later_line_of_a_parenthesised_import_is_followed(tmp_path):
    # a kernel module importing a submodule inside "from pkg.x import (a,\n    b)" must
    # still bring b's source into the key
    package = tmp_path / "rocketsim"
    (package / "dynamics").mkdir(parents=True)
    (package / "__init__.py").write_text("")
    (package / "dynamics" / "__init__.py").write_text("")
    (package / "dynamics" / "kernel.py").write_text(
        "from rocketsim._jit import njit\nfrom rocketsim.dynamics import (state,\n    gravity)\n")
    (package / "dynamics" / "state.py").write_text("N = 13\n")
    (package / "dynamics" / "gravity.py").write_text("MU = 3.986e14\n")
    (package / "dynamics" / "unrelated.py").write_text("X = 1\n")
    names = {path.relative_to(package).as_posix() for path in _kernel_sources(package)}
    assert {"dynamics/kernel.py", "dynamics/state.py", "dynamics/gravity.py"} <= names
    assert "dynamics/unrelated.py" not in names


_SAVES_UNDER_THE_LOCK = """
import fcntl, json, os, sys
import numba.core.caching as caching
from rocketsim._jit import njit

held = []
save_index = caching.IndexDataCacheFile._save_index

def checked(self, overloads):
    # another open file description of the lock: it cannot take the lock while it is held
    with open(os.path.join(numba.config.CACHE_DIR, ".lock"), "a") as probe:
        try:
            fcntl.flock(probe, fcntl.LOCK_EX | fcntl.LOCK_NB)
            fcntl.flock(probe, fcntl.LOCK_UN)
            held.append(False)
        except BlockingIOError:
            held.append(True)
    save_index(self, overloads)

import numba
caching.IndexDataCacheFile._save_index = checked

@njit
def twice(x):
    return 2 * x

twice(1.0), twice(1)        # two signatures: two saves of the index
print(json.dumps(held))
"""


def test_a_kernel_is_saved_to_the_cache_under_the_cache_folders_lock(tmp_path):
    """numba picks a saved signature's data file from the index it read: two processes
    saving two signatures of one kernel at once can pick the same file, and the index
    then names the other's machine code. Each save (index and data) holds the cache
    folder's lock: checked in a fresh process with an empty cache, from another file
    description of the lock at every index write."""
    pytest.importorskip("fcntl", reason="POSIX flock: elsewhere numba saves unlocked")
    import json
    assert json.loads(_on_a_cold_cache(tmp_path, _SAVES_UNDER_THE_LOCK)) == [True, True]


_COMPILED_BESIDE = """
import json, os, time
import numpy as np
from rocketsim import _jit
from rocketsim._jit import BESIDE, cached, compile_beside, entry_point, njit
from rocketsim.frames.local import where_and_how_fast
from rocketsim.telemetry import splice, writer
from rocketsim.vehicle.mass_properties import mass_properties

def signature(kernel, args):
    return tuple(kernel.typeof_pyval(a) for a in args)

def taken(kernel, args):
    # wait until the second process has claimed the kernel's item
    name = BESIDE._queued[kernel, signature(kernel, args)]
    while not os.path.exists(os.path.join(BESIDE._folder, "claim-" + name)):
        time.sleep(0.001)

records = writer._RECORDS_ARGUMENTS
cold = cached(splice.records, signature(splice.records, records))
compile_beside(splice.records, records)
started = BESIDE._process is not None
taken(splice.records, records)
writer._records()                     # waits for the second process, then loads the kernel
again = BESIDE.add(splice.records, records)

# while waiting for a kernel the second process compiles, this one compiles the next item
slow = (np.zeros(3), np.ones(3), 0.0, 7.29e-5, 6378137.0, 6356752.3)
quick = (np.zeros(5), np.zeros(1), np.zeros(1), np.ones(1), np.ones(1), np.zeros((0, 6)), np.zeros(0))
compile_beside(where_and_how_fast, slow, 0)
compile_beside(mass_properties, quick, 1)
taken(where_and_how_fast, slow)
entry_point(where_and_how_fast, *slow)
quick_claimed_here = BESIDE._process.poll() is None and sum(mass_properties.stats.cache_misses.values()) == 1

@njit
def twice(x):                         # in __main__: the second process cannot import it
    return 2 * x

compile_beside(twice, (21,))
print(json.dumps({
    "cold": cold, "started": started, "again": again,
    "records": [sum(splice.records.stats.cache_hits.values()), sum(splice.records.stats.cache_misses.values())],
    "slow": [sum(where_and_how_fast.stats.cache_hits.values()), sum(where_and_how_fast.stats.cache_misses.values())],
    "quick_claimed_here": quick_claimed_here, "twice": twice(21)}))
"""


def test_kernels_queued_beside_are_compiled_by_a_second_process(tmp_path):
    """On an empty cache a second process compiles queued kernels while this one goes on:
    the telemetry's framing kernel is then loaded here from the cache (a hit, no miss),
    and queued once only. Waiting for a kernel the second process has taken, this process
    compiles the next queued one itself. A kernel the second process cannot compile (not
    importable there) compiles here as it would have."""
    import json
    assert json.loads(_on_a_cold_cache(tmp_path, _COMPILED_BESIDE)) == {
        "cold": False, "started": True, "again": False, "records": [1, 0], "slow": [1, 0],
        "quick_claimed_here": True, "twice": 42}


def _array_slice_assignments(tree: ast.AST) -> list[str]:
    """``a[i:j] = b`` (an array into a slice) inside the kernels (``@njit`` functions) of
    ``tree``, as text; a number into a slice (``a[i:j] = 0.0``) is a fill and not listed."""
    found = []
    for function in ast.walk(tree):
        if not isinstance(function, ast.FunctionDef) or \
                not any("njit" in ast.unparse(d) for d in function.decorator_list):
            continue
        for node in ast.walk(function):
            if not isinstance(node, ast.Assign) or isinstance(node.value, (ast.Constant, ast.UnaryOp)):
                continue
            for target in node.targets:
                for item in target.elts if isinstance(target, ast.Tuple) else [target]:
                    if isinstance(item, ast.Subscript) and any(isinstance(n, ast.Slice)
                                                               for n in ast.walk(item.slice)):
                        found.append(f"{function.name}: {ast.unparse(node)}")
    return found


def test_kernels_copy_arrays_into_slices_without_numbas_shape_check():
    # numba compiles an array assigned into a slice with a check of the two shapes whose
    # error message takes 2-3 s to compile on a cold cache, in each process that first
    # needs it (measured in a cold Falcon 9 flight: 2.3-2.7 s); kernels use copy_into
    found = [f"{path.relative_to(PACKAGE)}: {line}" for path in sorted(PACKAGE.rglob("*.py"))
             for line in _array_slice_assignments(ast.parse(path.read_text()))]
    assert found == []
    # the scan sees the form it forbids
    assert _array_slice_assignments(ast.parse("@njit\ndef f(a, b):\n    a[1:3] = b\n    a[:] = 0.0\n")) == \
        ["f: a[1:3] = b"]


def test_copy_into_writes_the_array_from_the_slot():
    from rocketsim._jit import copy_into, njit

    @njit(cache=False)
    def into_column(dst, src):
        copy_into(dst[:, 1], 1, src)
        return dst

    out = into_column(np.zeros((4, 2)), np.array((1.0, 2.0, 3.0)))
    np.testing.assert_array_equal(out, [[0.0, 0.0], [0.0, 1.0], [0.0, 2.0], [0.0, 3.0]])


class _Offered:
    """What a flight queues for the second process: (kernel, numba signature) pairs."""

    def __init__(self):
        self.kernels = set()
        self.offered = []

    def add(self, kernel, args, priority=0):
        self.offered.append((kernel, tuple(kernel.typeof_pyval(a) for a in args)))
        return True

    def compiling_elsewhere(self, kernel):
        return False        # nothing is compiled beside here: each queued kernel is called


@pytest.mark.parametrize("scenario", ["sounding", "hobby-rocket", "iss-coast", "falcon9-leo"])
def test_a_flight_queues_the_signatures_its_runs_are_called_with(monkeypatch, tmp_path, scenario):
    """On a cold cache a flight queues its compiled runs' kernels for a second process
    before its first sample; the signatures it queues must be the ones it then calls (a
    signature no call uses would be compiled beside for nothing): a vehicle's compiled
    runs (the sounding rocket), a vehicle's one-step advance (the hobby rocket, under
    parachutes at the end: no compiled runs queued), a coast's runs (the station), the
    runs of a fairing's halves (the Falcon 9's first 260 s: dropped above 110 km)."""
    from rocketsim import _jit
    from rocketsim.scenario.load import load
    from rocketsim.stepping import checked_step, runs
    from rocketsim.api.telemetry_flight import fly_to_file as fly
    from rocketsim.telemetry import writer
    from tests.sounding_peer import scenario as sounding

    offered = _Offered()
    monkeypatch.setattr(_jit, "COMPILE_BESIDE", True)
    monkeypatch.setattr(_jit, "BESIDE", offered)
    called = set()
    entry_point = _jit.entry_point

    def recorded(kernel, *args):
        called.add((kernel, tuple(kernel.typeof_pyval(a) for a in args)))
        return entry_point(kernel, *args)

    monkeypatch.setattr(_jit, "entry_point", recorded)
    monkeypatch.setattr(writer, "entry_point", recorded)
    call = _jit.Kernel.__call__

    def recorded_call(kernel, *args):
        called.add((kernel, tuple(kernel.typeof_pyval(a) for a in args)))
        return call(kernel, *args)

    monkeypatch.setattr(_jit.Kernel, "__call__", recorded_call)
    if scenario == "sounding":
        fly(load(sounding(20.0)), tmp_path / "run.mcap")
        expected = {runs.fly_run, writer.splice.records}
    elif scenario == "hobby-rocket":
        fly(load(ROOT / "scenarios" / "hobby-rocket.yaml"), tmp_path / "run.mcap")
        expected = {checked_step.advance_checked, writer.splice.records}
        assert runs.fly_run not in {kernel for kernel, _ in offered.offered}
    elif scenario == "iss-coast":
        fly(load(ROOT / "scenarios" / "iss-coast.yaml"), tmp_path / "run.mcap", duration=200.0)
        expected = {runs.coast_run, writer.splice.records}
    else:
        fly(load(ROOT / "scenarios" / "falcon9-leo.yaml"), tmp_path / "run.mcap", duration=260.0)
        expected = {runs.fly_run, runs.fly_part, writer.splice.records}
    # each is queued (records: unless this process has bound it already) and called as queued
    queued = {kernel for kernel, _ in offered.offered}
    assert expected - {writer.splice.records} <= queued
    for item in offered.offered:
        if item[0] in expected:
            assert item in called


_COMPILE_ONCE = """
import json, sys, time
import numpy as np
from rocketsim.frames.local import where_and_how_fast
start = float(sys.argv[1])
while time.time() < start:             # both processes compile at once
    time.sleep(0.001)
where_and_how_fast(np.zeros(3), np.ones(3), 0.0, 7.29e-5, 6378137.0, 6356752.3)
stats = where_and_how_fast.stats
print(json.dumps([sum(stats.cache_hits.values()), sum(stats.cache_misses.values())]))
"""


def test_two_processes_on_one_cold_cache_compile_a_kernel_once(tmp_path):
    """Two processes needing the same kernel at once on an empty cache: one compiles it, the
    other waits for its marker and loads it from the cache (one miss between them)."""
    import json
    import os
    import subprocess
    import sys
    import time
    script = tmp_path / "once.py"
    script.write_text(_COMPILE_ONCE)
    start = str(time.time() + 3.0)     # after both have imported numba
    both = [subprocess.Popen([sys.executable, str(script), start], stdout=subprocess.PIPE, text=True,
                             env=_cold_env(tmp_path), cwd=tmp_path) for _ in range(2)]
    counts = [json.loads(process.communicate(timeout=300)[0].strip().splitlines()[-1]) for process in both]
    assert sorted(counts) == [[0, 1], [1, 0]]
    assert os.listdir(next(tmp_path.glob("numba-*")) / ".compiling") == []     # markers removed


def test_a_compiling_marker_of_an_ended_process_is_taken_over(tmp_path):
    import os
    import socket
    import subprocess
    import sys
    from rocketsim._jit import _held, _take

    host = socket.gethostname()
    ended = subprocess.run([sys.executable, "-c", "import os; print(os.getpid())"], capture_output=True,
                           text=True, check=True)
    marker = tmp_path / "marker"
    marker.write_text(f"{host} {int(ended.stdout)}")
    assert not _held(str(marker), host)
    assert _take(str(marker))
    assert marker.read_text() == f"{host} {os.getpid()}"
    # a living process's marker, and one of another host (which cannot be asked), are held
    assert _held(str(marker), host)
    marker.write_text(f"elsewhere {os.getpid()}")
    assert _held(str(marker), host)


def test_a_forked_child_leaves_the_queue_to_the_process_that_made_it(tmp_path):
    import os
    from rocketsim._jit import CompiledBeside

    queue = CompiledBeside()
    queue._folder, queue._owner = str(tmp_path), os.getpid() + 1      # made by another process
    queue.close()
    assert tmp_path.is_dir()
    queue._owner = os.getpid()
    queue.close()
    assert not tmp_path.exists() and queue._folder is None


def test_a_kernel_compiles_elsewhere_while_the_second_process_holds_its_item(tmp_path):
    # what a flight asks before choosing a compiled run (else it flies one step at a time)
    from rocketsim._jit import CompiledBeside

    import subprocess
    import sys

    queue = CompiledBeside()
    queue._folder = str(tmp_path)
    kernel, other = object(), object()
    assert not queue.compiling_elsewhere(kernel)                  # never queued
    queue._queued[kernel, ("signature",)] = "item-00-0000"
    queue.kernels.add(kernel)
    assert not queue.compiling_elsewhere(kernel)                  # no second process
    queue._process = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(60)"])
    try:
        assert queue.compiling_elsewhere(kernel) and not queue.compiling_elsewhere(other)
        (tmp_path / "claim-item-00-0000").touch()
        assert queue.compiling_elsewhere(kernel)                  # taken there, under way
        (tmp_path / "done-item-00-0000").touch()
        assert not queue.compiling_elsewhere(kernel)              # compiled: in the cache
        (tmp_path / "done-item-00-0000").unlink()
    finally:
        queue._process.kill()
        queue._process.wait()
    assert not queue.compiling_elsewhere(kernel)                  # the process ended without it


_ENDS_WHILE_COMPILING = """
import os, sys, time
import numpy as np
from rocketsim._jit import BESIDE, compile_beside
from rocketsim.frames.local import where_and_how_fast

slow = (np.zeros(3), np.ones(3), 0.0, 7.29e-5, 6378137.0, 6356752.3)
compile_beside(where_and_how_fast, slow)
name = next(iter(BESIDE._queued.values()))
while not os.path.exists(os.path.join(BESIDE._folder, "claim-" + name)):
    time.sleep(0.001)
print(BESIDE._process.pid)            # and end, the kernel half compiled there
"""


def test_a_kernel_compiling_beside_when_the_flight_ends_is_finished_into_the_cache(tmp_path):
    # a flight shorter than its runs' compiling (flown one step at a time meanwhile) leaves
    # them compiled for the next flight: the second process finishes the kernel it has taken
    import os
    import time
    second = int(_on_a_cold_cache(tmp_path, _ENDS_WHILE_COMPILING))
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline:
        try:
            os.kill(second, 0)
        except ProcessLookupError:
            break
        time.sleep(0.05)
    else:
        raise AssertionError("the second process did not end")
    check = ("import numpy as np; from rocketsim._jit import cached; "
             "from rocketsim.frames.local import where_and_how_fast as k; "
             "a = (np.zeros(3), np.ones(3), 0.0, 7.29e-5, 6378137.0, 6356752.3); "
             "print(cached(k, tuple(k.typeof_pyval(x) for x in a)))")
    assert _on_a_cold_cache(tmp_path, check) == "True"     # the same cache, now holding it


_FINISHED = """
import json, os
import numpy as np
from rocketsim._jit import BESIDE, cached, compile_beside, finish_beside
from rocketsim.frames.local import where_and_how_fast as kernel
args = (np.zeros(3), np.ones(3), 0.0, 7.29e-5, 6378137.0, 6356752.3)
compile_beside(kernel, args)
folder = BESIDE._folder
finish_beside()
print(json.dumps([cached(kernel, tuple(kernel.typeof_pyval(a) for a in args)), os.path.exists(folder)]))
"""


def test_finishing_the_queue_leaves_every_queued_kernel_in_the_cache(tmp_path):
    # rocketsim compile's workers: their flights may end before the runs compiled beside
    # them are done, and a pool's worker ends without its exit handlers
    import json
    assert json.loads(_on_a_cold_cache(tmp_path, _FINISHED)) == [True, False]
