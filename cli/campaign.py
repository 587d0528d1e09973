"""``rocketsim campaign``: Monte Carlo campaigns (run, rerun a case, report)."""

from __future__ import annotations

import signal
import sys
import time
from pathlib import Path

import click

from rocketsim_cli.errors import reports_input_errors


@click.group()
def campaign() -> None:
    """Monte Carlo campaigns: many runs of a scenario with dispersed inputs.

    \b
    Example:
        rocketsim campaign run campaigns/spaceport-ballistic.yaml -o ballistic
        rocketsim campaign report ballistic --plot ballistic/plots
        rocketsim campaign rerun ballistic 17 -o run-17.mcap
    """


class _Progress:
    """Runs done and failed, runs per second and the time left, on stderr: redrawn in
    place on a terminal, a line every tenth of the runs otherwise."""

    def __init__(self):
        self.start = time.perf_counter()
        self.terminal = sys.stderr.isatty()
        self.shown = -1

    def __call__(self, done: int, failed: int, total: int) -> None:
        if done == 0:           # the runs start (after the warm-up)
            self.start = time.perf_counter()
            return
        elapsed = time.perf_counter() - self.start
        rate = done / elapsed if elapsed > 0 else 0.0
        left = (total - done) / rate if rate > 0 else float("nan")
        line = (f"{done}/{total} runs, {failed} failed, {rate:.2f} runs/s, "
                f"{_duration(left)} left")
        if self.terminal:
            sys.stderr.write(f"\r{line}\x1b[K" + ("\n" if done == total else ""))
            sys.stderr.flush()
        elif done * 10 // total != self.shown or done == total:
            self.shown = done * 10 // total
            click.echo(line, err=True)


def _duration(seconds: float) -> str:
    if seconds != seconds:
        return "?"
    minutes, s = divmod(int(round(seconds)), 60)
    hours, minutes = divmod(minutes, 60)
    return f"{hours}h{minutes:02d}m" if hours else f"{minutes}m{s:02d}s" if minutes else f"{s}s"


def _interrupt(signum, frame):
    raise KeyboardInterrupt


@campaign.command("run")
@click.argument("campaign_file", metavar="CAMPAIGN", type=click.Path(dir_okay=False, path_type=Path))
@click.option("-o", "--output", type=click.Path(file_okay=False, path_type=Path), required=True,
              help="The campaign directory to write (results.parquet, inputs.parquet, runs/...).")
@click.option("--workers", type=click.IntRange(min=1), default=None,
              help="Worker processes of the local Dask cluster [default: one per core]; "
                   "1 flies every run in this process, without Dask.")
@click.option("--scheduler", metavar="ADDRESS", default=None,
              help="An existing Dask cluster's scheduler, e.g. tcp://host:8786.")
@click.option("--scheduler-file", type=click.Path(dir_okay=False, exists=True, path_type=Path), default=None,
              help="An existing Dask cluster's scheduler file (dask scheduler --scheduler-file).")
@click.option("--resume", is_flag=True, help="Fly only the runs the directory is missing.")
@click.option("--runs", type=int, default=None,
              help="Fly this many runs in place of the file's (its first N; with --resume, a larger N "
                   "adds runs to a random or Sobol campaign).")
@click.option("--trust", is_flag=True,
              help="Allow resuming a directory with its own campaign.yaml to execute the programs it names.")
@reports_input_errors
def run(campaign_file: Path, output: Path, workers: int | None, scheduler: str | None,
        scheduler_file: Path | None, resume: bool, runs: int | None, trust: bool) -> None:
    """Fly every run of CAMPAIGN into the directory -o.

    Every run's inputs derive from the campaign's seed and the run's number
    alone, so the results are the same with any number of workers, on a
    cluster, and resumed. Ctrl-C stops, keeping every finished run; --resume
    then flies the rest. Exit status 0 when every run flew, 1 when some
    failed (listed), 2 for a bad campaign file (nothing flown), 130 on Ctrl-C.

    \b
    Example:
        rocketsim campaign run campaigns/falcon9-landing.yaml -o f9 --runs 20
        rocketsim campaign run campaigns/falcon9-landing.yaml -o f9 --runs 200 --resume
        rocketsim campaign run campaigns/falcon9-landing.yaml -o f9 --scheduler tcp://head:8786
    """
    from rocketsim.api import CampaignInterrupted, run_campaign

    if scheduler is not None and scheduler_file is not None:
        from rocketsim.errors import InputError
        raise InputError("give --scheduler or --scheduler-file, not both", field="--scheduler")
    previous = signal.signal(signal.SIGTERM, _interrupt)
    try:
        results = run_campaign(campaign_file, output, workers=workers, scheduler=scheduler,
                               scheduler_file=scheduler_file, resume=resume, runs=runs, trust=trust,
                               progress=_Progress(),
                               log=lambda message: click.echo(message, err=True))
    except CampaignInterrupted as stopped:
        click.echo(f"\n{stopped}; 'rocketsim campaign run {campaign_file} -o {output} --resume' "
                   "flies the rest", err=True)
        sys.exit(130)
    finally:
        signal.signal(signal.SIGTERM, previous)
    failed = results[results["status"] != "ok"]
    click.echo(f"{len(results) - len(failed)} of {len(results)} runs flew; results: {output / 'results.parquet'}")
    for _, row in failed.iterrows():
        click.echo(f"run {row['run']}: {row['status']}: {row['error']}")
    if len(failed):
        sys.exit(1)


@campaign.command("rerun")
@click.argument("directory", metavar="DIR", type=click.Path(file_okay=False, exists=True, path_type=Path))
@click.argument("k", metavar="K", type=click.IntRange(min=0))
@click.option("-o", "--output", type=click.Path(dir_okay=False, path_type=Path), default=None,
              help="MCAP file to write [default: run-K.mcap here].")
@click.option("--trust", is_flag=True, help="Allow the run to execute the programs DIR's campaign names.")
@reports_input_errors
def rerun(directory: Path, k: int, output: Path | None, trust: bool) -> None:
    """Fly run K of the campaign in DIR alone, with its full telemetry.

    Its outputs are checked against its row in DIR's results: they are the
    same bit for bit (exit status 1 if not). The MCAP replays with
    'rocketsim replay'. A folder may come from someone else: a run that
    executes a program flies only with --trust (without it, the programs are
    named and nothing runs).

    \b
    Example:
        rocketsim campaign rerun f9 17 -o run-17.mcap --trust && rocketsim replay run-17.mcap
    """
    from rocketsim.api import rerun_campaign, same_row
    from rocketsim_cli.errors import check_writable

    output = output or Path(f"run-{k}.mcap")
    check_writable(output, "--output")
    row, recorded = rerun_campaign(directory, k, output, trust=trust)
    click.echo(f"run {k}: {row['status'].iloc[0]}, outcome {row['outcome'].iloc[0]}; telemetry: {output}")
    if recorded is None:
        click.echo(f"run {k} has no row in {directory / 'results.parquet'} to compare with")
        return
    differ = same_row(row, recorded)
    if differ:
        click.echo(f"run {k} differs from its row in the results in: {', '.join(differ)}", err=True)
        sys.exit(1)
    click.echo(f"run {k} reproduces its row in {directory / 'results.parquet'} bit for bit")


@campaign.command("report")
@click.argument("directory", metavar="DIR", type=click.Path(file_okay=False, exists=True, path_type=Path))
@click.option("--plot", "plot_dir", type=click.Path(file_okay=False, path_type=Path), default=None,
              help="Also draw the plots and landing.geojson into this directory.")
@reports_input_errors
def report(directory: Path, plot_dir: Path | None) -> None:
    """Statistics of the campaign in DIR: outcomes, margins, the landing ellipse.

    Exit status 1 when any run failed (error or timeout).

    \b
    Example:
        rocketsim campaign report f9 --plot f9/plots
    """
    from rocketsim.api import campaign_report
    found = campaign_report(directory, plot_dir)
    click.echo(found.text)
    if found.exit_status:
        sys.exit(found.exit_status)
