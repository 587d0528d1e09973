"""Python scripts run in a fresh process with a kernel cache of their own (empty at first)."""

from __future__ import annotations

import os
import subprocess
import sys


def cold_env(folder, **extra: str) -> dict:
    """This process's environment with ``folder`` as the kernel cache's root (no
    ``NUMBA_CACHE_DIR``), compiling nothing beside (unless ``extra`` says so), and ``extra``
    added."""
    env = {k: v for k, v in os.environ.items() if k not in ("NUMBA_CACHE_DIR", "ROCKETSIM_COMPILE_BESIDE")}
    env["ROCKETSIM_CACHE_DIR"] = str(folder)
    return {**env, **extra}


def on_a_cold_cache(folder, script: str, timeout: float = 300, **extra: str) -> str:
    """The last line printed by Python running ``script`` in ``folder``, its kernel cache's root
    (``extra``: more environment)."""
    path = folder / "script.py"
    path.write_text(script)
    done = subprocess.run([sys.executable, str(path)], capture_output=True, text=True,
                          env=cold_env(folder, **extra), cwd=folder, timeout=timeout)
    assert done.returncode == 0, done.stderr[-3000:]
    return done.stdout.strip().splitlines()[-1]
