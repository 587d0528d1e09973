"""The timing helpers of the benchmarks (they print figures, never assert them)."""

import math
import os
import resource
import subprocess
import time


def best_of(repeats, function, clock=time.perf_counter):
    """``(seconds, result)``: the fastest of ``repeats`` calls of ``function()``, timed by
    ``clock`` (wall time by default; ``time.thread_time``, the calling thread's CPU time,
    leaves out the time other processes of a shared machine held the core)."""
    best, result = math.inf, None
    for _ in range(repeats):
        start = clock()
        result = function()
        best = min(best, clock() - start)
    return best, result


def load_text() -> str:
    """The machine's load averages (1, 5, 15 min), printed beside every figure."""
    return "load " + " ".join(f"{x:.1f}" for x in os.getloadavg())


def whole_process(command: list[str], cwd=None, env: dict | None = None,
                  status: int = 0) -> tuple[float, float, str]:
    """``(wall s, CPU s, stderr)`` of ``command`` run to its end as a child process,
    which must exit with ``status``. CPU (user + system of the child) is steadier
    than wall time on a loaded machine."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    done = subprocess.run(command, cwd=cwd, env=env, stdout=subprocess.DEVNULL,
                          stderr=subprocess.PIPE, text=True)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    assert done.returncode == status, (command, done.returncode, done.stderr[-2000:])
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime), done.stderr
