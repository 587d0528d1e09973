"""``rocketsim fly``: fly a scenario and write its MCAP telemetry."""

from __future__ import annotations

import signal
import sys
from pathlib import Path

import click

from rocketsim.errors import InputError
from rocketsim_cli.errors import check_writable, reports_input_errors
from rocketsim_cli.live import Live, live_options
from rocketsim_cli.progress import flight_progress
from rocketsim_cli.summary import format_summary
from rocketsim_cli.units import Quantity


def overrides(settings: tuple[str, ...]) -> dict:
    """``--set PATH=VALUE`` options as overrides: each value read as a YAML value
    (``3`` a number, ``26 t`` a string with a unit, ``[1, 2]`` a list)."""
    import yaml
    found = {}
    for setting in settings:
        path, equals, text = setting.partition("=")
        if not equals or not path.strip():
            raise InputError(f"expected PATH=VALUE, got {setting!r}", field="--set")
        try:
            found[path.strip()] = yaml.safe_load(text)
        except yaml.YAMLError as error:
            raise InputError(f"cannot read the value {text!r} ({getattr(error, 'problem', error)})",
                             field=f"--set {path.strip()}") from None
    return found


class _Terminated(BaseException):
    """SIGTERM, raised in the main thread so the telemetry file is finished."""


def _raise_terminated(signum, frame):
    raise _Terminated


@click.command()
@click.argument("scenario", type=click.Path(dir_okay=False, path_type=Path))
@click.option("-o", "--output", type=click.Path(dir_okay=False, path_type=Path), default=None,
              help="MCAP file to write (default: the scenario's name with .mcap, here).")
@click.option("--step", type=Quantity("time"), default=None,
              help="Integration step, e.g. 20ms or '0.02 s' (at most 0.1 s; a bare number is s).")
@click.option("--duration", type=Quantity("time"), default=None,
              help="Mission time to fly, e.g. 10s, '3 h', 311d (overrides the mission; a bare number is s).")
@click.option("--set", "settings", multiple=True, metavar="PATH=VALUE",
              help="Change a field before flying, as the file would hold it, e.g. "
                   "--set 'vehicle.stages[booster].structure_mass=26 t' (repeatable; paths: docs/how-to/change-fields.md).")
@click.option("--summary-json", type=click.Path(dir_okay=False, path_type=Path), default=None,
              help="Also write the flight summary as JSON to this file.")
@live_options
@reports_input_errors
def fly(scenario: Path, output: Path | None, step: float | None, duration: float | None,
        settings: tuple[str, ...], summary_json: Path | None, live: Live | None) -> None:
    """Fly SCENARIO and write its telemetry as MCAP.

    Ctrl-C or SIGTERM stops the flight and still finishes the MCAP file
    (exit status 130 or 143). With --live the flight is served to Foxglove as it
    flies, at --warp times real time; the file is the same, byte for byte.

    \b
    Example:
        rocketsim fly scenarios/iss-coast.yaml -o iss.mcap --summary-json iss.json
        rocketsim fly scenarios/falcon9-hop.yaml --duration 30s --set seed=3
        rocketsim fly scenarios/falcon9-hop.yaml --live --warp 10
    """
    from rocketsim.api import fly_live, fly_to_file, load, strict_json
    from rocketsim_cli.compiling import compile_message

    loaded = load(scenario, overrides(settings))
    output = output or Path(f"{scenario.stem}.mcap")
    check_writable(output, "--output")
    if summary_json is not None:
        check_writable(summary_json, "--summary-json")
    previous = signal.signal(signal.SIGTERM, _raise_terminated)
    try:
        with compile_message():
            with flight_progress(duration or loaded.scenario.mission.duration) as on_progress:
                if live is not None:
                    summary = fly_live(loaded, output, live, step=step, duration=duration,
                                       on_progress=on_progress)
                else:
                    summary = fly_to_file(loaded, output, step=step, duration=duration,
                                          on_progress=on_progress)
    except KeyboardInterrupt:
        click.echo(f"\ninterrupted; telemetry so far is in {output}", err=True)
        sys.exit(130)
    except _Terminated:
        click.echo(f"\nterminated; telemetry so far is in {output}", err=True)
        sys.exit(143)
    except OSError as error:
        written = output.is_file() and output.stat().st_size > 0
        click.echo(f"\nerror: {error}; " + (f"what was written to {output} is readable with "
                   f"'rocketsim replay {output}'" if written else f"nothing was written to {output}"),
                   err=True)
        sys.exit(1)
    finally:
        signal.signal(signal.SIGTERM, previous)
    click.echo(format_summary(summary))
    click.echo(f"telemetry: {output}")
    if summary_json is not None:
        summary_json.write_text(strict_json(summary, indent=True) + "\n")
