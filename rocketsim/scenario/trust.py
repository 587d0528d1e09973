"""The one rule for code that reaches a flight from shared material.

A scenario's programs are Python: flying it executes them. Naming a scenario
or a campaign file of one's own (``rocketsim fly``, ``rocketsim campaign run``,
``rocketsim.fly``) is the approval to run its programs. Material received from
someone else is not: a run's MCAP file re-flown (``replay --verify``,
:func:`rocketsim.api.verify`), a campaign folder re-flown (``campaign rerun``,
``campaign run DIR/campaign.yaml -o DIR --resume``). Whatever way a program
reaches such a flight (an attachment under any name, a scenario or an override
naming a file, a stage's program, a choice among programs), the flight is built
only as far as :func:`approve`, which lists every program it would execute
(read from the loaded scenario: what :mod:`rocketsim.sim.build` would run, not
what a file's names claim) and refuses them unless ``trust`` is given.
Loading a scenario executes nothing (:func:`rocketsim.scenario.load.load`
resolves a program's path; its file is run only when the world is built).
"""

from __future__ import annotations

import os
from collections.abc import Iterable
from pathlib import Path

from rocketsim.errors import InputError
from rocketsim.scenario.load import LoadedScenario


class UntrustedProgram(InputError):
    """Flying shared material would execute programs, and trust was not given;
    ``programs`` names each (its role and file)."""

    def __init__(self, message: str, programs: list[str], **where):
        super().__init__(message, **where)
        self.programs = programs


def programs_of(loaded: LoadedScenario) -> list[str]:
    """Every program flying ``loaded`` executes: ``"<role> (<file>)"``, the file relative
    to the scenario's folder where it lies near it (at most two folders up), else its
    absolute path; a callable given in Python also names its function."""
    found = []
    for role, (main, path) in sorted(loaded.programs().items()):
        try:
            shown = Path(os.path.relpath(path, loaded.path.parent)).as_posix()
        except ValueError:              # another drive
            shown = str(path)
        if shown.startswith("../../../"):
            shown = str(path)
        if main is not None:
            shown += f", function {getattr(main, '__qualname__', repr(main))}"
        found.append(f"{role} ({shown})")
    return found


def approve(scenarios: LoadedScenario | Iterable[LoadedScenario], trust: bool, source: str) -> list[str]:
    """The programs flying ``scenarios`` (built from ``source``: shared material, named as
    the user knows it) would execute; raises :class:`UntrustedProgram` naming them
    unless ``trust``. Nothing to execute is always approved."""
    if isinstance(scenarios, LoadedScenario):
        scenarios = [scenarios]
    programs = list(dict.fromkeys(p for loaded in scenarios for p in programs_of(loaded)))
    if programs and not trust:
        raise UntrustedProgram(
            f"{source} would execute {'the program' if len(programs) == 1 else 'the programs'} "
            f"{'; '.join(programs)}; nothing was run. Pass --trust (trust=True from Python) "
            "if you trust it", programs, field="--trust")
    return programs
