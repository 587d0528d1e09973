"""Check a scenario, vehicle, site or mission file, and publish each kind's JSON Schema.

A file's kind is recognised from its top-level fields: a scenario has ``mission``, a
vehicle ``rigid_body`` or ``stages``, a site ``latitude``, a mission ``start``. A
scenario is loaded whole (every file it references, its overrides' paths); the other
kinds are validated alone. Nothing is flown and no array is computed, except where a
scenario's start point is (a start in orbit, the procedural classic range).
"""

from __future__ import annotations

from pathlib import Path

from rocketsim.errors import InputError
from rocketsim.scenario.load import REFERENCED, load, validate
from rocketsim.scenario.models import Scenario
from rocketsim.scenario.yaml_source import read_yaml

# file kinds by the top-level field only that kind has
_KINDS = {"rigid_body": "vehicle", "stages": "vehicle", "latitude": "site", "start": "mission"}


def validate_file(path: str | Path) -> str:
    """The kind of the file at ``path`` (``"scenario"``, ``"vehicle"``, ``"site"`` or
    ``"mission"``) once it is found valid; an :class:`~rocketsim.errors.InputError` naming
    the file, line, column and field of the first problem otherwise."""
    path = Path(path)
    source = read_yaml(path)
    if isinstance(source.data, dict) and "mission" in source.data:
        load(path)
        return "scenario"
    if isinstance(source.data, dict):
        for field, kind in _KINDS.items():
            if field in source.data:
                validate(source, REFERENCED[kind])
                return kind
    raise InputError("not a scenario, vehicle, site or mission file (no 'mission', 'rigid_body', "
                     "'latitude' or 'start' field)", file=path, line=1, column=1)


def schema_kinds() -> list[str]:
    """The kinds of file :func:`schema` describes: ``scenario`` and those a scenario references."""
    return ["scenario", *REFERENCED]


def schema(kind: str = "scenario") -> dict:
    """The JSON Schema of a file of ``kind`` (one of :func:`schema_kinds`), for an editor's
    YAML language server to validate against as one types."""
    if kind != "scenario" and kind not in REFERENCED:
        raise ValueError(f"no such kind of file: {kind!r}; expected one of {', '.join(schema_kinds())}")
    model = Scenario if kind == "scenario" else REFERENCED[kind]
    return model.model_json_schema()
