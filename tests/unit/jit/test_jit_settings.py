"""The kernels' settings from the environment (:mod:`rocketsim.jit.settings`): the
defaults, each variable's effect, and a value that names no setting refused as a
user's error (exit status 2, the variable named, no traceback)."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from rocketsim.errors import InputError
from rocketsim.jit import settings
from tests.cold_cache import cold_env

ROOT = Path(__file__).resolve().parents[3]


def test_the_defaults_compile_at_level_one_into_the_users_cache_folder():
    found = settings.read({})
    assert found == settings.Settings(
        mode="compiled", cache_root=os.path.join(os.path.expanduser("~"), ".cache", "rocketsim"),
        numba_cache_dir=None, opt_level="1", opt_from_numba=False, compile_beside=False)
    assert not found.python


def test_each_variable_sets_its_setting():
    found = settings.read({"ROCKETSIM_JIT": "Python", "XDG_CACHE_HOME": "/xdg", "NUMBA_CACHE_DIR": "/numba",
                           "NUMBA_OPT": "3", "ROCKETSIM_COMPILE_BESIDE": "1"})
    assert found == settings.Settings(mode="python", cache_root="/xdg/rocketsim", numba_cache_dir="/numba",
                                      opt_level="3", opt_from_numba=True, compile_beside=True)
    assert found.python
    assert settings.read({"ROCKETSIM_CACHE_DIR": "/shared", "XDG_CACHE_HOME": "/xdg"}).cache_root == "/shared"


@pytest.mark.parametrize("name, value", [("ROCKETSIM_JIT", "fast"), ("ROCKETSIM_COMPILE_BESIDE", "yes")])
def test_a_value_that_names_no_setting_is_refused_naming_the_variable(name, value):
    with pytest.raises(InputError, match=rf"^{name}: '{value}' is not"):
        settings.read({name: value})


def test_a_flight_with_a_wrong_setting_exits_2_with_one_line(tmp_path):
    done = subprocess.run([sys.executable, "-m", "rocketsim_cli.main", "fly", "scenarios/iss-coast.yaml",
                           "--duration", "1s", "-o", str(tmp_path / "run.mcap")], capture_output=True, text=True,
                          cwd=ROOT, env={**cold_env(tmp_path), "ROCKETSIM_JIT": "fast"}, timeout=300)
    assert done.returncode == 2
    assert done.stderr.startswith("error: ROCKETSIM_JIT: 'fast' is not a way to run the kernels")
    assert "Traceback" not in done.stderr
