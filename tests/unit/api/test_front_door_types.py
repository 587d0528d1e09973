"""The Python front door checks its arguments' types as the files' fields are checked:
a wrong type is an InputError naming the argument and saying what was expected (never
a TypeError from deep inside), and a time given as the files write it (``"10 s"``)
is read as the files read it."""

from __future__ import annotations

import pytest

import rocketsim
from rocketsim.errors import InputError


@pytest.mark.parametrize("arguments, field, expected", [
    ({"program": 42}, "program", "expected a function main(fc) or a program file's path, got int 42"),
    ({"programs": {"core": 4.5}}, "program/core", "got float 4.5"),
    ({"programs": ["main.py"]}, "programs", "expected a mapping of stage names to programs, got list"),
    ({"telemetry": 3}, "telemetry", "expected a file's path or None, got int 3"),
    ({"progress": "yes"}, "progress", "expected True, False or a callable progress(t, phase)"),
    ({"duration": "ten"}, "duration", "expected '<number> <unit>' for a time, got 'ten'"),
    ({"duration": [10]}, "duration", "expected a time as a number or a string with a unit"),
    ({"step": float("nan")}, "step", "expected a finite time"),
])
def test_a_wrong_type_is_an_input_error_naming_the_argument(arguments, field, expected, scenario):
    with pytest.raises(InputError) as raised:
        rocketsim.fly(scenario(duration="0.1 s"), **arguments)
    assert raised.value.field == field and expected in raised.value.message, str(raised.value)


def test_a_time_written_as_in_the_files_is_read_as_they_read_it(scenario):
    """``duration="0.2 s"`` and ``step="20 ms"`` fly the same as 0.2 and 0.02."""
    path = scenario(duration="10 s")
    written = rocketsim.fly(path, duration="0.2 s", step="20 ms")
    numbers = rocketsim.fly(path, duration=0.2, step=0.02)
    assert written.summary == numbers.summary
    assert (written.summary["mission_time_s"], written.summary["step_s"]) == (pytest.approx(0.2), 0.02)
