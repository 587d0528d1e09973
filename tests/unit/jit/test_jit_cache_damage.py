"""A damaged or unwritable kernel cache never stops a flight: a cache file cut short or
overwritten is compiled again and written anew, said in one line; a cache folder that
cannot be written is said in one line and the kernels compiled for the process.

Each case runs a small kernel in fresh processes on a cache of their own: a first
process compiles and saves it, the file is damaged, a second process computes the
same value, saying so once, and a third loads it from the healed cache in silence.
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from tests.cold_cache import cold_env

KERNEL = """
import json
from rocketsim.jit import njit

@njit(cache=True)
def twice(x):
    return 2.0 * x

value = twice(1.25)
print(json.dumps([value, sum(twice.dispatcher.stats.cache_hits.values())]))
"""


def _run(root: Path, folder: Path) -> tuple[list, list[str]]:
    """(the kernel's value and cache hits, stderr's lines) of the script in a fresh process
    with ``root`` as its cache root."""
    script = folder / "script.py"
    script.write_text(KERNEL)
    done = subprocess.run([sys.executable, str(script)], capture_output=True, text=True,
                          env=cold_env(root), cwd=folder, timeout=300)
    assert done.returncode == 0 and "Traceback" not in done.stderr, done.stderr[-3000:]
    return json.loads(done.stdout.strip().splitlines()[-1]), done.stderr.strip().splitlines()


def _cut(path: Path) -> None:
    path.write_bytes(path.read_bytes()[:len(path.read_bytes()) // 2])


def _overwritten(path: Path) -> None:
    path.write_bytes(b"\x80\x04not a pickle at all" + bytes(64))


@pytest.mark.parametrize("file, damage", [("nbi", _cut), ("nbc", _cut), ("nbc", _overwritten),
                                          ("nbi", _overwritten)])
def test_a_damaged_cache_file_is_compiled_again_said_once_and_healed(file, damage, tmp_path):
    root = tmp_path / "cache"
    assert _run(root, tmp_path) == ([2.5, 0], [])
    [damaged] = root.rglob(f"script.twice-*.{file}")
    damage(damaged)
    value, said = _run(root, tmp_path)
    assert value == [2.5, 0]                                      # compiled again
    assert len(said) == 1 and f"the kernel cache file {damaged} is damaged" in said[0], said
    assert _run(root, tmp_path) == ([2.5, 1], [])               # loaded from the healed cache


def test_a_cache_folder_that_cannot_be_written_is_said_and_the_kernels_compiled(tmp_path):
    """The cache root below a file: its folder cannot be made (as one on a read-only
    disk cannot be written), in every process."""
    root = tmp_path / "a-file"
    root.write_text("")
    for _ in range(2):
        value, said = _run(root / "cache", tmp_path)
        assert value == [2.5, 0]
        assert len(said) == 1 and "the kernel cache folder" in said[0] and "cannot be written" in said[0], said
