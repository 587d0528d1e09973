"""Benchmark: peak memory of the Mars mission flown in memory, against the same flight
writing its MCAP file.

``rocketsim.fly(scenario)`` keeps every sample of every body in memory (float64
blocks, :mod:`rocketsim.api.samples`); ``rocketsim.fly(scenario, "run.mcap")`` streams
them to a file in 256 KiB chunks and keeps none. Each flight runs in a subprocess of
its own, the only child of a small parent process that reads its peak resident set
from ``resource.getrusage(RUSAGE_CHILDREN).ru_maxrss`` once it has ended. Printed (``pytest -s``): both peaks, the difference, the samples kept and the
bytes their numbers take, and the machine's load.

In the suite it flies the first ARC seconds of ``scenarios/mars-from-pad.yaml`` (the
ascent, the staging and the parking orbit: a few seconds of CPU each); with
``ROCKETSIM_BENCH_FULL=1`` the whole 311-day mission to Mars orbit (about 89 000
samples of the orbiter at the scenario's 1 Hz, where it is awake, and 4 000 of the
spent stages). Measured (2026-12-01, load 5.8, the whole mission): peak RSS 243 MB
writing the MCAP, 269 MB in memory (ratio 1.11): 93 000 samples in 32.7 MB of
numbers, 368 bytes a sample; the first 1500 s (load 6.5): 234 and 232 MB.
Nothing asserts a size: the checks are that
both flights end with the same final state and that the in-memory run holds every
sample the file holds.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
MISSION = ROOT / "scenarios" / "mars-from-pad.yaml"
ARC = 1500.0        # s: the ascent, staging and part of the first parking orbit

_CHILD = """
import json, sys
import rocketsim
scenario, out, duration = sys.argv[1], sys.argv[2] or None, float(sys.argv[3]) or None
run = rocketsim.fly(scenario, out, duration=duration)
kept = {name: len(body.samples) for name, body in run.bodies.items()}
numbers = sum(body.samples.nbytes for body in run.bodies.values())
final = {name: body.final for name, body in run.bodies.items()}
print(json.dumps({"samples": kept, "bytes": numbers, "final": final}))
"""


_PARENT = """
import json, resource, subprocess, sys
done = subprocess.run(sys.argv[1:], capture_output=True, text=True, check=True)
print(json.dumps({"peak_kb": resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss,
                  **json.loads(done.stdout.strip().splitlines()[-1])}))
"""


def _peak_of(out: str, duration: float) -> dict:
    """What the flight's subprocess printed, with its peak RSS (kB, ``peak_kb``): the
    flight runs as the only child of a parent process that reads it."""
    done = subprocess.run([sys.executable, "-c", _PARENT, sys.executable, "-c", _CHILD, str(MISSION),
                           out, repr(duration)], capture_output=True, text=True, check=True, cwd=ROOT)
    return json.loads(done.stdout.strip().splitlines()[-1])


def test_memory_of_the_mars_mission_in_memory_against_the_file(tmp_path):
    full = os.environ.get("ROCKETSIM_BENCH_FULL") == "1"
    duration = 0.0 if full else ARC
    load = os.getloadavg()[0]
    on_file = _peak_of(str(tmp_path / "run.mcap"), duration)
    in_memory = _peak_of("", duration)
    assert in_memory["final"] == on_file["final"]
    assert in_memory["samples"] == on_file["samples"]
    arc = "the whole mission" if full else f"the first {ARC:g} s"
    kept = sum(in_memory["samples"].values())
    print(f"\nMars mission from the pad, {arc} (load {load:.1f}): peak RSS writing the MCAP "
          f"{on_file['peak_kb'] / 1024:.0f} MB, in memory {in_memory['peak_kb'] / 1024:.0f} MB "
          f"(ratio {in_memory['peak_kb'] / on_file['peak_kb']:.2f}); {kept} samples kept in memory in "
          f"{in_memory['bytes'] / 2 ** 20:.1f} MB of numbers ({in_memory['bytes'] / max(kept, 1):.0f} "
          "bytes a sample)")
