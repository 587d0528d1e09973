"""Kernels run as the plain Python they are written in (``ROCKETSIM_JIT=python``), to debug
one: a debugger steps through its lines, an error inside it is a Python exception with
a traceback into its source, and a shipped scenario flies so, computing the telemetry
the compiled kernels compute. Each in a fresh process with the switch set."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np

import rocketsim
from tests.cold_cache import cold_env

ROOT = Path(__file__).resolve().parents[3]

_KERNELS = '''\
from rocketsim.jit import njit


@njit
def first_sum(a, n):
    total = 0.0
    for i in range(n):
        total += a[i]
    return total
'''
SUMMING_LINE = 8        # "total += a[i]" in _KERNELS

_STEPPED = """
import json, os, sys, traceback
import numpy as np
from kernels import first_sum

lines = []

def trace(frame, event, arg):
    if frame.f_code is first_sum.py_func.__code__ and event == "line":
        lines.append(frame.f_lineno)
    return trace

sys.settrace(trace)
total = first_sum(np.arange(3.0), 3)
sys.settrace(None)
raised = None
if os.environ.get("ROCKETSIM_JIT") == "python":
    try:
        first_sum(np.arange(3.0), 4)        # past the end: numba checks no bounds
    except IndexError as error:
        last = traceback.extract_tb(error.__traceback__)[-1]
        raised = [os.path.basename(last.filename), last.lineno, last.name, last.line]
print(json.dumps({"total": total, "lines": sorted(set(lines)), "raised": raised}))
"""


def _run(tmp_path, script: str, *args: str, **env: str) -> dict:
    (tmp_path / "kernels.py").write_text(_KERNELS)
    done = subprocess.run([sys.executable, "-c", script, *args], capture_output=True, text=True, cwd=tmp_path,
                          env={**cold_env(tmp_path / "cache"), "PYTHONPATH": str(tmp_path), **env}, timeout=600)
    assert done.returncode == 0, done.stderr[-3000:]
    return json.loads(done.stdout.strip().splitlines()[-1])


def test_a_kernel_run_as_python_is_stepped_line_by_line_and_raises_into_its_source(tmp_path):
    python = _run(tmp_path, _STEPPED, ROCKETSIM_JIT="python")
    assert python["total"] == 3.0
    assert SUMMING_LINE in python["lines"]          # a tracer (a debugger) sees its lines run
    assert python["raised"] == ["kernels.py", SUMMING_LINE, "first_sum", "total += a[i]"]
    compiled = _run(tmp_path, _STEPPED)
    assert compiled == {"total": 3.0, "lines": [], "raised": None}      # machine code: no lines to see


_FLIGHT = """
import json, sys, threading
from numba.core import event
import rocketsim
from rocketsim.jit import Kernel

compiled = []

class Compiles(event.Listener):
    def on_start(self, ev):
        func = ev.data["dispatcher"].py_func
        compiled.append(f"{func.__module__}.{func.__qualname__}")

    def on_end(self, ev):
        pass

called = set()

def profile(frame, what, arg):
    if what == "call":
        called.add(frame.f_code)

event.register("numba:compile", Compiles())
sys.setprofile(profile)
threading.setprofile(profile)           # the telemetry's writing thread too
rocketsim.fly("scenarios/hobby-rocket.yaml", sys.argv[1], duration=1.0)
sys.setprofile(None)
kernels = {value for name, module in list(sys.modules.items()) if name.startswith("rocketsim.")
           for value in vars(module).values() if isinstance(value, Kernel)}
ran = sorted(f"{k.__module__}.{k.__qualname__}" for k in kernels if k.py_func.__code__ in called)
print(json.dumps({"ran": ran, "compiled": sorted({name for name in compiled if name.startswith("rocketsim.")})}))
"""


def test_a_shipped_scenario_flies_with_its_kernels_as_python(tmp_path):
    """The hobby rocket's first second (rail, motor, aerodynamics, telemetry): its kernels
    run as Python, and the only kernel compiled is the telemetry's block copy, which calls
    a machine-code intrinsic; its telemetry is the compiled flight's."""
    done = subprocess.run([sys.executable, "-c", _FLIGHT, str(tmp_path / "python.mcap")], capture_output=True,
                          text=True, cwd=ROOT, env={**cold_env(tmp_path / "cache"), "ROCKETSIM_JIT": "python"},
                          timeout=900)
    assert done.returncode == 0, done.stderr[-3000:]
    found = json.loads(done.stdout.strip().splitlines()[-1])
    assert {"rocketsim.dynamics.rk4.step_into", "rocketsim.dynamics.derivative.held_derivative",
            "rocketsim.vehicle.aero.body_aero", "rocketsim.telemetry.splice.records"} <= set(found["ran"])
    assert found["compiled"] == ["rocketsim.telemetry.splice._copy"]
    rocketsim.fly(ROOT / "scenarios" / "hobby-rocket.yaml", tmp_path / "compiled.mcap", duration=1.0)
    python, compiled = (rocketsim.open_run(tmp_path / f"{how}.mcap").bodies["hobby-rocket"].table(units=False)
                        for how in ("python", "compiled"))
    assert python.shape == compiled.shape == (11, 42)
    numbers = python.select_dtypes("number").columns
    np.testing.assert_allclose(python[numbers].to_numpy(float), compiled[numbers].to_numpy(float),
                               rtol=1e-12, atol=1e-9)
