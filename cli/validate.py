"""``rocketsim validate`` and ``rocketsim schema``: check files, publish their shapes."""

from __future__ import annotations

import json
import sys
from pathlib import Path

import click

from rocketsim.errors import InputError
from rocketsim_cli.lazy import LibraryChoice


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
    from rocketsim.api import design_warnings, validate_file

    failed = False
    for path in files:
        try:
            kind = validate_file(path)
        except InputError as error:
            click.echo(f"error: {error}", err=True)
            failed = True
        else:
            click.echo(f"ok: {path} ({kind})")
            for line in design_warnings(path):
                click.echo(f"warning: {path}: {line}", err=True)
    if failed:
        sys.exit(2)


def _kinds() -> list[str]:
    from rocketsim.api import schema_kinds
    return schema_kinds()


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
    from rocketsim.api import schema as schema_of

    click.echo(json.dumps(schema_of(kind), indent=2))
