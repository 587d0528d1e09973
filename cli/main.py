"""``rocketsim``: the command group. Each command lives in its own module."""

from __future__ import annotations

import click

from rocketsim.api import __version__


@click.group(context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(__version__, prog_name="rocketsim")
def main() -> None:
    """Six-degree-of-freedom rocket flight and mission simulator.

    \b
    Fly a scenario and write its telemetry:
        rocketsim fly scenarios/iss-coast.yaml -o iss.mcap
    """


def _register() -> None:
    from rocketsim_cli import commands  # noqa: F401  (each module adds its command)
    for command in commands.ALL:
        main.add_command(command)


_register()


if __name__ == "__main__":
    main()
