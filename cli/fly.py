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


def _terminal() -> tuple[bool, bool]:
    """Whether standard error and standard input are a terminal."""
    return sys.stderr.isatty(), sys.stdin.isatty()


def _check_size(size, output: Path, large_ok: bool) -> None:
    """Say the telemetry's estimated ``size`` on a terminal; above 2 GB ask (a terminal) or
    stop with exit status 2 unless ``large_ok``."""
    shown, asked = _terminal()
    if shown:
        click.echo(f"telemetry: {size} to {output}", err=True)
    if not size.large or large_ok:
        return
    if shown and asked and click.confirm(f"write about {size.bytes / 1e9:.3g} GB?", err=True):
        return
    raise InputError(f"the telemetry would be {size}: fly with a lower --rate, thin its coasts with "
                     "--coast-rate, or pass --yes to write it", field="--rate")


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
@click.option("--rate", type=Quantity("frequency", "1 Hz"), default=None,
              help="Telemetry samples per second, e.g. '1 Hz' or 0.01Hz (the scenario's telemetry.rate).")
@click.option("--coast-rate", type=Quantity("frequency", "0.01 Hz"), default=None,
              help="Samples per second while a body coasts: no engine running, under 1 Pa of dynamic "
                   "pressure (the scenario's telemetry.coast_rate; see docs/reference/telemetry.md).")
@click.option("--yes", "large_ok", is_flag=True,
              help="Write the telemetry even if it is estimated above 2 GB.")
@live_options
@reports_input_errors
def fly(scenario: Path, output: Path | None, step: float | None, duration: float | None,
        settings: tuple[str, ...], summary_json: Path | None, rate: float | None,
        coast_rate: float | None, large_ok: bool, live: Live | None) -> None:
    """Fly SCENARIO and write its telemetry as MCAP.

    Before flying, the telemetry file's size is estimated (shown on a
    terminal); above 2 GB the flight asks first (a terminal) or stops with
    exit status 2 unless --yes: a lower --rate, or --coast-rate for long
    coasts, writes less. Ctrl-C or SIGTERM stops the flight and still
    finishes the MCAP file (exit status 130 or 143). With --live the flight is
    served to Foxglove as it flies, at --warp times real time; the file is the
    same, byte for byte.

    \b
    Example:
        rocketsim fly scenarios/iss-coast.yaml -o iss.mcap --summary-json iss.json
        rocketsim fly scenarios/falcon9-hop.yaml --duration 30s --set seed=3
        rocketsim fly scenarios/iss-coast.yaml --duration 60d --rate 1Hz --coast-rate 0.01Hz
        rocketsim fly scenarios/falcon9-hop.yaml --live --warp 10
    """
    from rocketsim.api import design_warnings, fly_live, fly_to_file, load, strict_json, telemetry_size
    from rocketsim_cli.compiling import compile_message

    given = overrides(settings)
    for path, value in (("telemetry.rate", rate), ("telemetry.coast_rate", coast_rate)):
        if value is not None:
            given[path] = f"{value!r} Hz"
    loaded = load(scenario, given)
    for line in design_warnings(loaded):
        click.echo(f"warning: {scenario}: {line}", err=True)
    output = output or Path(f"{scenario.stem}.mcap")
    check_writable(output, "--output")
    _check_size(telemetry_size(loaded, duration), output, large_ok)
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
        sys.exit(2)
    finally:
        signal.signal(signal.SIGTERM, previous)
    click.echo(format_summary(summary))
    click.echo(f"telemetry: {output}")
    if summary_json is not None:
        summary_json.write_text(strict_json(summary, indent=True) + "\n")
