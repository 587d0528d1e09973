"""A second process compiles queued kernels into the cache beside a first flight on a cold
cache (:mod:`rocketsim.jit.beside`, switched on here: it is off by default)."""

from pathlib import Path

import pytest

from rocketsim.jit import beside
from rocketsim.jit.numba_internals import numba_types
from tests.cold_cache import on_a_cold_cache

ROOT = Path(__file__).resolve().parents[3]
ON = {"ROCKETSIM_COMPILE_BESIDE": "1"}


_COMPILED_BESIDE = """
import json, os, time
import numpy as np
from rocketsim.jit import compile_beside, entry_point, njit
from rocketsim.jit.beside import BESIDE
from rocketsim.jit.numba_internals import cached, numba_types
from rocketsim.frames.local import where_and_how_fast
from rocketsim.telemetry import splice, writer
from rocketsim.vehicle.mass_properties import mass_properties

def signature(kernel, args):
    return numba_types(kernel, args)

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
    assert json.loads(on_a_cold_cache(tmp_path, _COMPILED_BESIDE, **ON)) == {
        "cold": False, "started": True, "again": False, "records": [1, 0], "slow": [1, 0],
        "quick_claimed_here": True, "twice": 42}


class _Offered:
    """What a flight queues for the second process: (kernel, numba signature) pairs."""

    def __init__(self):
        self.kernels = set()
        self.offered = []

    def add(self, kernel, args, priority=0):
        self.offered.append((kernel, numba_types(kernel, args)))
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
    from rocketsim.jit import entries, kernel as kernels
    from rocketsim.scenario.load import load
    from rocketsim.stepping import checked_step, runs
    from rocketsim.api.telemetry_flight import fly_to_file as fly
    from rocketsim.telemetry import writer
    from tests.sounding_peer import scenario as sounding

    offered = _Offered()
    monkeypatch.setattr(beside, "COMPILE_BESIDE", True)
    monkeypatch.setattr(beside, "BESIDE", offered)
    monkeypatch.setattr(kernels, "BESIDE", offered)
    called = set()
    entry_point = entries.entry_point

    def recorded(kernel, *args):
        called.add((kernel, numba_types(kernel, args)))
        return entry_point(kernel, *args)

    monkeypatch.setattr(entries, "entry_point", recorded)
    monkeypatch.setattr(writer, "entry_point", recorded)
    call = kernels.Kernel.__call__

    def recorded_call(kernel, *args):
        called.add((kernel, numba_types(kernel, args)))
        return call(kernel, *args)

    monkeypatch.setattr(kernels.Kernel, "__call__", recorded_call)
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


def test_a_forked_child_leaves_the_queue_to_the_process_that_made_it(tmp_path):
    import os
    from rocketsim.jit.beside import CompiledBeside

    queue = CompiledBeside()
    queue._folder, queue._owner = str(tmp_path), os.getpid() + 1      # made by another process
    queue.close()
    assert tmp_path.is_dir()
    queue._owner = os.getpid()
    queue.close()
    assert not tmp_path.exists() and queue._folder is None


def test_a_kernel_compiles_elsewhere_while_the_second_process_holds_its_item(tmp_path):
    # what a flight asks before choosing a compiled run (else it flies one step at a time)
    from rocketsim.jit.beside import CompiledBeside

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
from rocketsim.jit import compile_beside
from rocketsim.jit.beside import BESIDE
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
    second = int(on_a_cold_cache(tmp_path, _ENDS_WHILE_COMPILING, **ON))
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline:
        try:
            os.kill(second, 0)
        except ProcessLookupError:
            break
        time.sleep(0.05)
    else:
        raise AssertionError("the second process did not end")
    check = ("import numpy as np; from rocketsim.jit.numba_internals import cached, numba_types; "
             "from rocketsim.frames.local import where_and_how_fast as k; "
             "a = (np.zeros(3), np.ones(3), 0.0, 7.29e-5, 6378137.0, 6356752.3); "
             "print(cached(k, numba_types(k, a)))")
    assert on_a_cold_cache(tmp_path, check) == "True"     # the same cache, now holding it


_FINISHED = """
import json, os
import numpy as np
from rocketsim.jit import compile_beside, finish_beside
from rocketsim.jit.beside import BESIDE
from rocketsim.jit.numba_internals import cached, numba_types
from rocketsim.frames.local import where_and_how_fast as kernel
args = (np.zeros(3), np.ones(3), 0.0, 7.29e-5, 6378137.0, 6356752.3)
compile_beside(kernel, args)
folder = BESIDE._folder
finish_beside()
print(json.dumps([cached(kernel, numba_types(kernel, args)), os.path.exists(folder)]))
"""


def test_finishing_the_queue_leaves_every_queued_kernel_in_the_cache(tmp_path):
    # rocketsim compile's workers: their flights may end before the runs compiled beside
    # them are done, and a pool's worker ends without its exit handlers
    import json
    assert json.loads(on_a_cold_cache(tmp_path, _FINISHED, **ON)) == [True, False]
