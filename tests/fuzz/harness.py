"""What every fuzzed input runs under: a hang watchdog, a memory bound, a count.

Each input runs in this process (click's CliRunner, no subprocess per input)
inside :func:`bounded`, which fails it as a hang after :data:`HANG_SECONDS` of
the process's CPU time (user and system: a busy loop), or after
:data:`BLOCKED_SECONDS` of wall time (an input blocked, using no CPU), and when
the process's peak resident memory during the input rose more than
:data:`MEMORY_BOUND` above what it held before (Linux's VmHWM, reset before
each input through /proc/self/clear_refs). Both watchdogs are far above the
milliseconds an input takes: not timing assertions. The busy one counts CPU
time, not wall time, so a machine loaded by other processes (seven on two
cores stretch wall time tenfold) cannot turn a slow input into a "hang": the
verdict on an input does not depend on the load.
"""

from __future__ import annotations

import collections
import contextlib
import re
import signal
import traceback

from click.testing import CliRunner
from hypothesis import settings

HANG_SECONDS = 60.0          # s of this process's CPU time
BLOCKED_SECONDS = 600.0      # s of wall time
MEMORY_BOUND = 1 << 30          # bytes: 1 GiB more than before the input

# an error names the file and line: "<folder>/vehicle.yaml:12:3: ..."
AT_LINE = re.compile(r"error: \S+\.(yaml|csv|txt|py):\d+")

COUNTS: collections.Counter = collections.Counter()     # inputs run, by kind
PEAKS: dict[str, int] = {}                               # largest rise of resident memory, by kind


def examples(weight: float) -> int:
    """The number of examples of a fuzz test: ``weight`` times the profile's unit
    (tests/conftest.py: 100 in "ci", 1700 in "long")."""
    return max(1, round(settings.default.max_examples * weight))


class Hang(BaseException):
    """Raised by the watchdog; a BaseException, so no ``except Exception`` swallows it."""


def _on_alarm(signum, frame):
    raise Hang


def _status(field: str) -> int | None:
    try:
        with open("/proc/self/status") as status:
            found = re.search(rf"^{field}:\s+(\d+) kB", status.read(), re.M)
    except OSError:
        return None
    return int(found.group(1)) * 1024 if found else None


def _reset_peak() -> bool:
    try:
        with open("/proc/self/clear_refs", "w") as clear:
            clear.write("5")            # resets VmHWM to the current resident size
        return True
    except OSError:
        return False


@contextlib.contextmanager
def bounded(kind: str):
    """Run one input of ``kind``: counted, watched for hangs, its memory bounded."""
    COUNTS[kind] += 1
    measured = _reset_peak()
    before = _status("VmRSS")
    previous = {number: signal.signal(number, _on_alarm) for number in (signal.SIGPROF, signal.SIGALRM)}
    signal.setitimer(signal.ITIMER_PROF, HANG_SECONDS)
    signal.setitimer(signal.ITIMER_REAL, BLOCKED_SECONDS)
    try:
        yield
    except Hang:
        raise AssertionError(f"hang: the input ran more than {HANG_SECONDS:g} s of CPU time or "
                             f"{BLOCKED_SECONDS:g} s of wall time") from None
    finally:
        signal.setitimer(signal.ITIMER_PROF, 0.0)
        signal.setitimer(signal.ITIMER_REAL, 0.0)
        for number, handler in previous.items():
            signal.signal(number, handler)
    if measured and before is not None:
        rise = _status("VmHWM") - before
        PEAKS[kind] = max(PEAKS.get(kind, 0), rise)
        assert rise < MEMORY_BOUND, f"the input took {rise / 2**20:.0f} MiB more resident memory"


def invoke(*args) -> tuple[int, str]:
    """``rocketsim *args`` in this process: (exit status, output). Fails with the
    traceback when the command raised anything but SystemExit, or printed one."""
    from rocketsim_cli.main import main
    result = CliRunner().invoke(main, [str(a) for a in args], catch_exceptions=True)
    if result.exception is not None and not isinstance(result.exception, SystemExit):
        raise AssertionError("a traceback reached the user:\n"
                             + "".join(traceback.format_exception(*result.exc_info)) + result.output)
    assert "Traceback" not in result.output, result.output
    return result.exit_code, result.output


def write_files(folder, files: dict[str, str]) -> None:
    """Write each of ``files`` (name: text) into ``folder``."""
    for name, text in files.items():
        (folder / name).write_text(text)
