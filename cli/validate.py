"""``rocketsim validate`` and ``rocketsim schema``: check files, publish their shapes."""

from __future__ import annotations

import json
import sys
from pathlib import Path

import click

from rocketsim.errors import InputError
from rocketsim_cli.lazy import LibraryChoice

# file kinds by the top-level field only that kind has
_KINDS = {"rigid_body": "vehicle", "stages": "vehicle", "latitude": "site", "start": "mission"}


@click.command()
@click.argument("files", nargs=-1, required=True, type=click.Path(dir_okay=False, path_type=Path))
def validate(files: tuple[Path, ...]) -> None:
    """Check scenario, vehicle, site or mission FILES; exit 2 if any is invalid.

    The kind of each file is recognised from its fields (a scenario has
    'mission', a vehicle 'rigid_body' or 'stages', a site 'latitude', a mission 'start').
    A valid staged vehicle or scenario is then reviewed ('rocketsim vehicle'), and
    each way its design will fail (break up, tumble, not steer, not lift off) is a
    warning line on stderr.

    \b
    Example:
        rocketsim validate scenarios/iss-coast.yaml vehicles/cubesat-6u.yaml
    """
    failed = False
    for path in files:
        try:
            kind = _validate_one(path)
        except InputError as error:
            click.echo(f"error: {error}", err=True)
            failed = True
        else:
            click.echo(f"ok: {path} ({kind})")
            import rocketsim
            for line in rocketsim.design_warnings(path):
                click.echo(f"warning: {path}: {line}", err=True)
    if failed:
        sys.exit(2)


def _validate_one(path: Path) -> str:
    from rocketsim.scenario.load import REFERENCED, load, validate as validate_source
    from rocketsim.scenario.yaml_source import read_yaml

    source = read_yaml(path)
    if isinstance(source.data, dict) and "mission" in source.data:
        load(path)
        return "scenario"
    if isinstance(source.data, dict):
        for field, kind in _KINDS.items():
            if field in source.data:
                validate_source(source, REFERENCED[kind])
                return kind
    raise InputError("not a scenario, vehicle, site or mission file (no 'mission', 'rigid_body', "
                     "'latitude' or 'start' field)", file=path, line=1, column=1)


def _kinds() -> list[str]:
    from rocketsim.scenario.load import REFERENCED
    return ["scenario", *REFERENCED]


@click.command()
@click.option("--kind", type=LibraryChoice(_kinds), default="scenario",
              show_default=True, help="Which file's schema to print.")
def schema(kind: str) -> None:
    """Print the JSON Schema of a scenario file (or a vehicle, site, mission).

    Point your editor's YAML language server at it to validate as you type.

    \b
    Example:
        rocketsim schema > rocketsim-scenario.schema.json
        rocketsim schema --kind vehicle > vehicle.schema.json
    """
    from rocketsim.scenario.load import REFERENCED
    from rocketsim.scenario.models import Scenario

    model = Scenario if kind == "scenario" else REFERENCED[kind]
    click.echo(json.dumps(model.model_json_schema(), indent=2))
