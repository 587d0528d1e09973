"""A program cannot hang a flight: a wake-up past its wall-time limit is stopped with
an error at the program's line, the MCAP finished and readable; a program that is
not a plain function is refused when it is loaded.

Each way of keeping control is tried where the limit claims to stop it: in the
main thread (where ``rocketsim fly`` flies) a sleep, a lock acquired twice, a
busy loop under an hour's CPU budget, a read of a pipe nobody writes; in another
thread (a Dask worker's) a busy loop. A flight whose program always hands back
in time flies the same bytes under a limit of 0.05 s as under the default: the
watchdog changes nothing unless it fires. A condition read after every step of a
vehicle's compiled runs, under a budget and a limit armed once per run, is held to
both all the same.
"""

from __future__ import annotations

import re
import threading
import time

import pytest

from rocketsim.api.telemetry_flight import fly_to_file
from rocketsim.flight.program import ProgramError, ProgramRunner
from rocketsim.scenario.load import load
from rocketsim.telemetry.reader import messages, metadata, read_run
from tests.sounding_peer import scenario as sounding_scenario

BLOCKING = {
    "sleep": "import time\n\n\ndef main(fc):\n    fc.sleep(0.2)\n    time.sleep(10_000)\n",
    "lock": ("import threading\n\n\ndef main(fc):\n    fc.sleep(0.2)\n    lock = threading.Lock()\n"
             "    lock.acquire()\n    lock.acquire()\n"),
    "busy loop": "def main(fc):\n    fc.sleep(0.2)\n    while True:\n        pass\n",
    "pipe": "import os\n\n\ndef main(fc):\n    fc.sleep(0.2)\n    read, write = os.pipe()\n    os.read(read, 1)\n",
}
LINE = {"sleep": 6, "lock": 8, "busy loop": 4, "pipe": 7}
LIMITS = "program_time_limit: 0.5 s\nprogram_cpu_budget: 3600 s\n"     # the CPU budget out of the way


@pytest.mark.parametrize("kind", list(BLOCKING))
def test_a_program_that_keeps_control_is_stopped_at_its_line(kind, scenario, cli, tmp_path):
    path = scenario(BLOCKING[kind], duration="10 s", extra=LIMITS)
    out = tmp_path / "run.mcap"
    result = cli("fly", path, "-o", out)
    assert result.exit_code == 2, result.output
    found = re.search(r"program\.py:(\d+): the program kept control for 0\.5 s of wall time", result.output)
    assert found, result.output
    if kind == "busy loop":
        assert int(found.group(1)) in (3, 4)          # the loop's while or its body
    else:
        assert int(found.group(1)) == LINE[kind]
    run = read_run(out)
    assert run.problem is None and metadata(out)["outcome"]["status"] == "error"
    assert list(messages(out, ["/probe/state"]))[-1][2]["t"] == pytest.approx(0.2)


def test_in_another_thread_a_busy_program_is_stopped_too(scenario, tmp_path):
    loaded = load(scenario(BLOCKING["busy loop"], duration="10 s", extra=LIMITS))
    caught = []

    def fly():
        try:
            fly_to_file(loaded, tmp_path / "run.mcap")
        except ProgramError as error:
            caught.append(error)

    thread = threading.Thread(target=fly)
    thread.start()
    thread.join(120)                    # a hang guard, not a timing: the flight takes ~1 s
    assert not thread.is_alive() and caught
    assert "kept control for 0.5 s of wall time" in str(caught[0])
    assert read_run(tmp_path / "run.mcap").problem is None


def test_the_watchdog_changes_nothing_unless_it_fires(scenario, tmp_path):
    program = ("def main(fc):\n    while fc.time < 2.0:\n        fc.log('t', fc.time)\n        fc.step()\n"
               "    fc.wait_until(lambda: fc.time > 2.5)\n    fc.sleep(0.5)\n")
    runs = []
    for n, limit in enumerate(("0.05 s", "1000 s")):
        out = tmp_path / f"run-{n}.mcap"
        fly_to_file(load(scenario(program, duration="4 s", extra=f"program_time_limit: {limit}\n")), out)
        runs.append([m for m in messages(out)])
    assert runs[0] == runs[1] and len(runs[0]) > 40


@pytest.mark.parametrize("program, kind, line", [
    ("def main(fc):\n    yield\n", "a generator function", 1),
    ("x = 1\n\n\nasync def main(fc):\n    fc.step()\n", "a coroutine function", 4),
    ("class main:\n    def __init__(self, fc):\n        pass\n", "a type object", None),
    ("import functools\n\n\ndef steer(fc, gain):\n    fc.step()\n\n\nmain = functools.partial(steer, gain=2)\n",
     "a partial object", None),
])
def test_a_program_that_is_not_a_plain_function_is_refused_at_load(program, kind, line, scenario, cli, tmp_path):
    out = tmp_path / "run.mcap"
    result = cli("fly", scenario(program, duration="1 s"), "-o", out)
    assert result.exit_code == 2 and "Traceback" not in result.output, result.output
    assert kind in result.output and "not a plain function" in result.output
    assert (f"program.py:{line}:" if line else "program.py: ") in result.output


def _keeps_control(kind: str) -> bool:
    """Never returns: a busy loop, or a sleep of hours."""
    while kind == "busy loop":
        pass
    time.sleep(10_000)
    return True


@pytest.mark.parametrize("kind, limits, said", [
    ("busy loop", {"program_cpu_budget": "0.3 s"}, "ran 0.3 s of CPU time in one step"),
    ("sleep", {"program_time_limit": "0.5 s", "program_cpu_budget": "3600 s"},
     "kept control for 0.5 s of wall time"),
])
def test_a_condition_read_between_compiled_steps_is_held_to_the_budget_and_the_limit(kind, limits, said,
                                                                                     tmp_path, monkeypatch):
    # a lambda condition of a vehicle in the air is read after every step of compiled runs,
    # the budget and the limit armed once around each run: a reading that keeps control
    # is stopped all the same, at the line it keeps control at
    def main(fc):
        fc.ignite()
        fc.wait_until(lambda: fc.time > 3.0 and _keeps_control(kind))

    watched, entered = ProgramRunner.watched, []

    def counted(runner):
        entered.append(runner)
        return watched(runner)

    monkeypatch.setattr(ProgramRunner, "watched", counted)
    out = tmp_path / "run.mcap"
    with pytest.raises(ProgramError) as raised:
        fly_to_file(load({**sounding_scenario(10.0), "program": main, **limits}), out)
    assert entered                      # read inside compiled runs
    assert said in str(raised.value)
    first = _keeps_control.__code__.co_firstlineno
    lines = (first + 2, first + 3) if kind == "busy loop" else (first + 4,)      # the loop, or the sleep
    assert re.search(rf"test_program_leash\.py:({'|'.join(map(str, lines))}): ", str(raised.value))
    assert read_run(out).problem is None
    assert list(messages(out, ["/peer_sounding_rocket/state"]))[-1][2]["t"] == pytest.approx(3.0)
