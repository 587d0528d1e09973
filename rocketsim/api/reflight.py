"""Re-fly a shared run from the files it carries and compare it message by message.

Flying a run executes the program it carries, so :func:`verify` refuses a run
with a program unless called with ``trust=True``. The scenario, vehicle,
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

from rocketsim.flight.program import load_program
from rocketsim.scenario.load import load
from rocketsim.api.telemetry_flight import fly_to_file
from rocketsim.telemetry.reader import RunFile, iter_raw_messages, read_run
from rocketsim.telemetry.tables import flat_row


class UntrustedProgram(Exception):
    """Re-flying would execute the program the run carries, and trust was not given."""


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


def verify(path: str | Path, trust: bool = False) -> Verdict:
    """Fly the run again from its attachments and compare every message.

    A run that carries a program is flown only with ``trust=True``: flying
    executes that program. Raises :class:`UntrustedProgram` otherwise.
    """
    run = read_run(path)
    if run.program and not trust:
        raise UntrustedProgram(run.program)
    info = run.metadata.get("rocketsim", {})
    with tempfile.TemporaryDirectory(prefix="rocketsim-verify-") as folder:
        scenario = lay_out(run, Path(folder) / "files")
        again = Path(folder) / "again.mcap"
        flight_error = None
        try:
            overrides = {path: json.loads(value) for path, value in run.metadata.get("overrides", {}).items()}
            overrides.update(_programs(run, scenario))
            fly_to_file(load(scenario, overrides), again, step=float(info["step_s"]),
                duration=float(info["duration_s"]))
        except Exception as error:      # the original may have ended the same way
            flight_error = f"{type(error).__name__}: {error}"
        return _compare(iter_raw_messages(path), iter_raw_messages(again), flight_error)


def _programs(run: RunFile, scenario: Path) -> dict:
    """Overrides flying the programs the run carries (laid out beside ``scenario``) in
    the roles they flew, whatever the scenario file names: a program given in place
    of the file's, or a function not named ``main`` (metadata ``entries``)."""
    entries = run.metadata.get("entries", {})
    found = {}
    for role, rel in run.metadata["files"].items():
        if role != "program" and not role.startswith("program/"):
            continue
        path = Path(os.path.normpath(scenario.parent / rel))
        entry = entries.get(role, "main")
        found["program" if role == "program" else f"programs[{role.split('/', 1)[1]}]"] = (
            str(path) if entry == "main" else load_program(path, entry))
    return found


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
