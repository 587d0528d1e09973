"""``rocketsim replay``: summarise, export, plot or re-verify a run's MCAP file.

Nothing here runs a program a shared file carries, except ``--verify
--trust``, which names each before it flies (without ``--trust`` it names
them and refuses, exit status 2).
"""

from __future__ import annotations

import sys
from datetime import datetime, timezone
from pathlib import Path
from typing import TYPE_CHECKING

import click

from rocketsim.errors import InputError
from rocketsim_cli.errors import output_file, output_folder, reports_input_errors
from rocketsim_cli.live import Live, live_options

if TYPE_CHECKING:
    from rocketsim.api import RunFile


@click.command()
@click.argument("run_file", metavar="RUN.mcap", type=click.Path(dir_okay=False, path_type=Path))
@click.option("--export", "export_to", type=(click.Choice(["csv", "parquet"]),
                                             output_folder()),
              default=None, metavar="csv|parquet DIR",
              help="Write one table per body (and events.csv) into DIR.")
@click.option("--plot", type=output_file(), default=None,
              help="Draw the flight to this PNG (altitude, speed, q, acceleration, attitude, track...).")
@click.option("--verify", "check", is_flag=True,
              help="Fly the run again from its attachments and compare every message.")
@click.option("--trust", is_flag=True,
              help="Allow --verify to execute the program the file carries.")
@live_options
@reports_input_errors
def replay(run_file: Path, export_to, plot: Path | None, check: bool, trust: bool, live: Live | None) -> None:
    """Summarise the run in RUN.mcap: its flight summary, events and errors.

    Reading, exporting and plotting never execute the program inside the
    file; --verify executes it only with --trust. A truncated or damaged
    file exits with status 2 after summarising what is readable.

    With --live the run is served to Foxglove again, at --warp times real time.

    \b
    Examples:
        rocketsim replay iss.mcap
        rocketsim replay iss.mcap --export csv tables/ --plot iss.png
        rocketsim replay iss.mcap --verify --trust
        rocketsim replay iss.mcap --live --warp 100
    """
    from rocketsim.api import export_tables, read_run

    if not run_file.is_file():
        raise InputError(f"no such file: {run_file}", file=run_file)
    run = read_run(run_file)
    click.echo(describe(run))
    if export_to is not None:
        kind, folder = export_to
        try:
            written = export_tables(run_file, folder, kind)
        except ImportError as error:
            raise InputError(str(error), field="--export") from None
        click.echo("exported: " + ", ".join(str(p) for p in written))
    if plot is not None:
        from rocketsim.plots import run as plot_run
        click.echo(f"plot: {plot_run(run_file, plot)}")
    status = 0
    if live is not None:
        from rocketsim.api import replay_live
        try:
            replay_live(run_file, live)
        except KeyboardInterrupt:
            sys.exit(130)
    if check:
        status = _verify(run_file, trust)
    if run.problem:
        click.echo(f"error: {run_file} is damaged: {run.problem}; the summary above is what is readable",
                   err=True)
        status = 2
    sys.exit(status)


def _verify(run_file: Path, trust: bool) -> int:
    from rocketsim.api import verify

    def announce(programs: list[str]) -> None:
        click.echo(f"--trust: executing {'; '.join(programs)} carried by {run_file}", err=True)

    try:
        verdict = verify(run_file, trust=trust, announce=announce)
    except (ValueError, KeyError) as error:
        raise InputError(f"cannot re-fly {run_file}: {error}", file=run_file) from None
    if verdict.flight_error:
        click.echo(f"re-flight ended with {verdict.flight_error}")
    if verdict.identical:
        click.echo(f"verify: bit-identical ({verdict.compared} messages)")
        return 0
    d = verdict.difference
    detail = f"field {d['field']}" + (f": file {d['file']!r}, re-flight {d['reflight']!r}" if "file" in d else "")
    click.echo(f"verify: DIFFERS at message {d['index']} ({d['topic']}, {_utc(d['log_time_ns'])}): {detail}")
    return 1


def describe(run: RunFile) -> str:
    """The run as a person reads it: what, when, outcome, bodies, events, errors."""
    info = run.metadata.get("rocketsim", {})
    outcome = run.metadata.get("outcome", {})
    lines = [f"run {run.path.name}: scenario {info.get('scenario', '?')}, rocketsim {info.get('version', '?')}",
             f"epoch {info.get('epoch_utc', '?')}, step {info.get('step_s', '?')} s, "
             f"seed {info.get('seed', '?')}"]
    if run.start_ns is not None:
        lines.append(f"telemetry {_utc(run.start_ns)} .. {_utc(run.end_ns)} "
                     f"({(run.end_ns - run.start_ns) / 1e9:.2f} s), {sum(run.counts.values())} messages")
    lines.append("outcome: " + (outcome.get("status", "unknown (no outcome record)")
                                + (f" ({outcome['error']})" if "error" in outcome else "")))
    if run.attachments:
        lines.append("files: " + ", ".join(run.attachments)
                     + ("  (the program is not executed)" if run.program else ""))
    for body in run.bodies:
        final = run.final.get(body)
        lines.append(f"{body}: {run.counts[f'/{body}/state']} states")
        if final:
            over = (f", {_number(final['surface_speed'], 1, 2)} m/s over the ground"
                    if "surface_speed" in final else "")
            lines.append(f"  last: T+{final['t']:.2f} s, altitude {_number(final['altitude'], 1e3, 3)} km, "
                         f"lat {_number(final['latitude_deg'], 1, 4)} deg, "
                         f"lon {_number(final['longitude_deg'], 1, 4)} deg, "
                         f"inertial speed {_number(final['inertial_speed'], 1, 2)} m/s{over}")
    lines.append(f"events ({len(run.events)}):")
    for event in run.events:
        figures = ", ".join(f"{k} {v:.6g}" if isinstance(v, float) else f"{k} {v}"
                            for k, v in event["figures"].items())
        lines.append(f"  T+{event['t']:.2f} s  {event['body']}: {event['name']}"
                     + (f"  ({figures})" if figures else ""))
    for error in run.errors:
        lines.append(f"error at T+{error.get('t', float('nan')):.2f} s: {error['message']}")
    lines.append(f"program log: {len(run.logs)} lines" + (f", last: {run.logs[-1]['message']}" if run.logs else ""))
    return "\n".join(lines)


def _number(value, scale: float, digits: int) -> str:
    """``value / scale`` to ``digits`` decimals; a non-finite number (JSON null) reads "nan"."""
    return "nan" if value is None else f"{value / scale:.{digits}f}"


def _utc(ns: int) -> str:
    return datetime.fromtimestamp(ns / 1e9, timezone.utc).isoformat(timespec="milliseconds")
