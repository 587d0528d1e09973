"""The compiled-kernel cache key covers exactly what a kernel can read.

numba caches a kernel by its own file only; :mod:`rocketsim.jit.cache` names the
cache folder for a hash of every kernel module and of the library modules those
import. The key must change when gravity changes (a kernel inlines it) and
must not change when the pure-Python simulation loop changes. Processes sharing
the folder save under its lock and compile each kernel once between them.
"""

import ast
from pathlib import Path

import numpy as np
import pytest

import rocketsim
from rocketsim.jit.cache import held, kernel_sources, take
from tests.cold_cache import cold_env, on_a_cold_cache

PACKAGE = Path(rocketsim.__file__).resolve().parent
ROOT = PACKAGE.parent


def _names():
    return {path.relative_to(PACKAGE).as_posix() for path in kernel_sources(PACKAGE)}



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
        "from rocketsim.jit import njit\nfrom rocketsim.dynamics import (state,\n    gravity)\n")
    (package / "dynamics" / "state.py").write_text("N = 13\n")
    (package / "dynamics" / "gravity.py").write_text("MU = 3.986e14\n")
    (package / "dynamics" / "unrelated.py").write_text("X = 1\n")
    names = {path.relative_to(package).as_posix() for path in kernel_sources(package)}
    assert {"dynamics/kernel.py", "dynamics/state.py", "dynamics/gravity.py"} <= names
    assert "dynamics/unrelated.py" not in names


_SAVES_UNDER_THE_LOCK = """
import fcntl, json, os, sys
import numba.core.caching as caching
from rocketsim.jit import njit

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
    assert json.loads(on_a_cold_cache(tmp_path, _SAVES_UNDER_THE_LOCK)) == [True, True]


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
                             env=cold_env(tmp_path), cwd=tmp_path) for _ in range(2)]
    counts = [json.loads(process.communicate(timeout=300)[0].strip().splitlines()[-1]) for process in both]
    assert sorted(counts) == [[0, 1], [1, 0]]
    assert os.listdir(next(tmp_path.glob("numba-*")) / ".compiling") == []     # markers removed


def test_a_compiling_marker_of_an_ended_process_is_taken_over(tmp_path):
    import os
    import socket
    import subprocess
    import sys

    host = socket.gethostname()
    ended = subprocess.run([sys.executable, "-c", "import os; print(os.getpid())"], capture_output=True,
                           text=True, check=True)
    marker = tmp_path / "marker"
    marker.write_text(f"{host} {int(ended.stdout)}")
    assert not held(str(marker), host)
    assert take(str(marker))
    assert marker.read_text() == f"{host} {os.getpid()}"
    # a living process's marker, and one of another host (which cannot be asked), are held
    assert held(str(marker), host)
    marker.write_text(f"elsewhere {os.getpid()}")
    assert held(str(marker), host)


_INTO_ITS_FOLDER = """
import json, os
import numba
from rocketsim.jit import cache_dir, njit

@njit
def twice(x):
    return 2 * x

twice(1.0)
print(json.dumps([numba.config.CACHE_DIR == cache_dir(),
                  [name for _, _, names in os.walk(cache_dir()) for name in names]]))
"""


def test_kernels_are_saved_in_the_folder_of_this_source_below_the_cache_root(tmp_path):
    import json
    import re
    pointed, files = json.loads(on_a_cold_cache(tmp_path, _INTO_ITS_FOLDER))
    assert pointed
    # numba's index and data files of the script's kernel, in numba-<source hash>
    assert any(f.startswith("script.twice") and f.endswith(".nbi") for f in files)    # numba's index
    assert any(f.startswith("script.twice") and f.endswith(".nbc") for f in files)    # the machine code
    folders = [p.name for p in tmp_path.iterdir() if p.is_dir()]
    assert len(folders) == 1 and re.fullmatch(r"numba-[0-9a-f]{16}", folders[0])
