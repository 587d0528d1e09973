"""Re-fly a shared run from the files it carries and compare it message by message.

Flying a run executes the programs it would fly, so :func:`verify` refuses a
run whose re-flight would execute any unless called with ``trust=True``
(:func:`rocketsim.scenario.trust.approve`: the programs are read from the
scenario as laid out and loaded with the recorded overrides, whatever the
attachments are named; nothing of the run is executed before). The scenario, vehicle,
site, weather and program are laid out from the run's attachments in their
original folder layout (metadata ``files``), flown at the run's step and
duration with the overrides it was flown with (metadata ``overrides``), and
every message of the new file is compared with the original's
in file order: same topic, same log time, same bytes. A scenario given as a
mapping travels as the YAML file it would be; programs fly in the roles they
flew (a program given in place of the file's, a function not named ``main``).
"""

from __future__ import annotations

import json
import math
import os
import tempfile
from dataclasses import dataclass
from pathlib import Path, PurePosixPath

from rocketsim.api.flying import with_programs
from rocketsim.argument_checks import file_path, switch
from rocketsim.errors import InputError
from rocketsim.flight.program import load_program
from rocketsim.scenario.load import load
from rocketsim.scenario.trust import UntrustedProgram, approve
from rocketsim.api.telemetry_flight import fly_to_file
from rocketsim.telemetry.reader import RunFile, iter_raw_messages, read_run
from rocketsim.telemetry.tables import flat_row

__all__ = ["UntrustedProgram", "Verdict", "lay_out", "verify"]

@dataclass
class Verdict:
    """The re-flight compared with the file: ``identical``, how many messages
    were compared, and the first difference (None when identical)."""

    identical: bool
    compared: int
    difference: dict | None = None
    flight_error: str | None = None


def lay_out(run: RunFile, folder: Path) -> Path:
    """Write the run's attached files into ``folder`` in their original layout
    (metadata ``files``: paths relative to the scenario's folder); return the
    scenario's path. Paths are kept inside ``folder``."""
    layout = run.metadata.get("files")
    if not layout or "scenario" not in layout:
        raise ValueError("the run does not record the layout of its files (written by an older rocketsim)")
    by_role = {name.rsplit("/", 1)[0]: data for name, data in run.attachments.items()}   # role/file name
    depth = 0
    for rel in layout.values():
        level = 0
        for part in PurePosixPath(rel).parts:
            level += -1 if part == ".." else 0 if part == "." else 1
            depth = max(depth, -level)
    home = folder.joinpath(*[f"d{i}" for i in range(depth)])
    root = folder.resolve()
    scenario = None
    for role, rel in layout.items():
        target = Path(os.path.normpath(home / rel))
        if root not in target.resolve().parents or role not in by_role:
            raise ValueError(f"the run's file {rel!r} ({role}) cannot be laid out")
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_bytes(by_role[role])
        if role == "scenario":
            scenario = target
    return scenario


def verify(path: str | Path, trust: bool = False, announce=None) -> Verdict:
    """Fly the run again from its attachments and compare every message.

    Re-flying executes the programs the laid-out scenario and the recorded overrides
    name: without ``trust=True`` a run that would execute any raises
    :class:`UntrustedProgram` naming them, before anything is executed. With it,
    ``announce(programs)`` (if given) is called with their names before the flight.
    """
    file_path(path, "path")
    trust = switch(trust, "trust")
    run = read_run(path)
    info = run.metadata.get("rocketsim", {})
    with tempfile.TemporaryDirectory(prefix="rocketsim-verify-") as folder:
        scenario = lay_out(run, Path(folder) / "files")
        again = Path(folder) / "again.mcap"
        flight_error = None
        overrides = {key: json.loads(value) for key, value in run.metadata.get("overrides", {}).items()}
        overrides.update(_programs(run, scenario))
        try:
            loaded = load(scenario, overrides)
        except InputError as error:     # the original may have ended the same way
            loaded, flight_error = None, f"{type(error).__name__}: {error}"
        if loaded is not None:
            programs = approve(loaded, trust, f"the run {path}")
            if programs and announce is not None:
                announce(programs)
            try:
                fly_to_file(_entries(run, loaded), again, step=float(info["step_s"]),
                            duration=float(info["duration_s"]))
            except Exception as error:      # the original may have ended the same way
                flight_error = f"{type(error).__name__}: {error}"
        return _compare(iter_raw_messages(path), iter_raw_messages(again) if again.is_file() else iter(()),
                        flight_error)


def _programs(run: RunFile, scenario: Path) -> dict:
    """Overrides flying the program files the run carries (laid out beside ``scenario``)
    in the roles they flew, whatever the scenario file names (a program given in place
    of the file's)."""
    found = {}
    for role, rel in run.metadata["files"].items():
        if role != "program" and not role.startswith("program/"):
            continue
        key = "program" if role == "program" else f"programs[{role.split('/', 1)[1]}]"
        found[key] = str(Path(os.path.normpath(scenario.parent / rel)))
    return found


def _entries(run: RunFile, loaded):
    """``loaded`` flying, in each role the run names a function not called ``main``
    (metadata ``entries``), that function of its file (loaded once approved: loading
    runs the file's top level)."""
    entries = {role: entry for role, entry in run.metadata.get("entries", {}).items()
               if entry != "main" and role in loaded.files}
    if not entries:
        return loaded
    functions = {role: load_program(loaded.files[role], entry) for role, entry in entries.items()}
    return with_programs(loaded, functions.pop("program", None),
                         {role.split("/", 1)[1]: main for role, main in functions.items()})


def _compare(original, again, flight_error) -> Verdict:
    n = 0
    end = object()
    while True:
        a, b = next(original, end), next(again, end)
        if a is end and b is end:
            return Verdict(True, n, None, flight_error)
        if a != b:
            return Verdict(False, n, _difference(n, a, b, end), flight_error)
        n += 1


def _difference(index: int, a, b, end) -> dict:
    where = a if a is not end else b
    found = {"index": index, "topic": where[0], "log_time_ns": where[1]}
    if a is end or b is end:
        found["field"] = "(the " + ("file" if a is end else "re-flight") + " has no more messages)"
        return found
    if a[0] != b[0] or a[1] != b[1]:
        found["field"] = f"(topic/time: re-flight has {b[0]} at {b[1]} ns)"
        return found
    try:
        first, second = flat_row(json.loads(a[2])), flat_row(json.loads(b[2]))
    except ValueError:
        found["field"] = "(the message is not JSON)"
        return found
    for key in list(first) + [k for k in second if k not in first]:
        x, y = first.get(key, "(missing)"), second.get(key, "(missing)")
        if x != y and not (isinstance(x, float) and isinstance(y, float) and math.isnan(x) and math.isnan(y)):
            found.update(field=key, file=x, reflight=y)
            return found
    found["field"] = "(same values, different bytes)"
    return found
