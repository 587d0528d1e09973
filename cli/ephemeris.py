"""``rocketsim ephemeris``: where the Sun, Earth, Moon or Mars is, date by date."""

from __future__ import annotations

import datetime as _dt
import math

import click

from rocketsim.errors import InputError
from rocketsim_cli.errors import reports_input_errors
from rocketsim_cli.lazy import LibraryChoice

MAX_ROWS = 200_000
CSV_COLUMNS = "utc,tt_jd,x_km,y_km,z_km,vx_km_s,vy_km_s,vz_km_s"


def _utc(text: str, option: str) -> _dt.datetime:
    """An ISO 8601 date or date-time, read as UTC unless it names a zone."""
    try:
        moment = _dt.datetime.fromisoformat(text.strip())
    except ValueError:
        raise InputError(f"{text!r} is not a date: expected e.g. 2026-01-01 or "
                         "2026-01-01T12:00:00Z", field=option) from None
    if moment.tzinfo is None:
        moment = moment.replace(tzinfo=_dt.timezone.utc)
    return moment.astimezone(_dt.timezone.utc)


def _instants(start: _dt.datetime, stop: _dt.datetime, step_text: str) -> list[_dt.datetime]:
    from rocketsim.api import UnitError, parse_quantity
    try:
        step = parse_quantity(step_text, "time")
    except UnitError as error:
        raise InputError(str(error), field="--step") from None
    if not step > 0.0:
        raise InputError(f"the step must be positive, got {step_text!r}", field="--step")
    if stop < start:
        raise InputError(f"--to ({stop:%Y-%m-%d %H:%M:%S}) is before --from "
                         f"({start:%Y-%m-%d %H:%M:%S})", field="--to")
    count = math.floor((stop - start).total_seconds() / step + 1e-9) + 1
    if count > MAX_ROWS:
        raise InputError(f"{count} rows: at most {MAX_ROWS}; use a larger step",
                         field="--step")
    return [start + _dt.timedelta(seconds=k * step) for k in range(count)]


def _bodies() -> tuple[str, ...]:
    from rocketsim.api import EPHEMERIS_BODIES
    return EPHEMERIS_BODIES


@click.command()
@click.option("--body", type=LibraryChoice(_bodies), required=True, help="the body to place")
@click.option("--center", type=LibraryChoice(_bodies), default=None,
              help="origin of the vectors [default: the Sun for the planets, the Earth "
                   "for the Moon and the Sun]")
@click.option("--from", "start", required=True, help="first UTC date, e.g. 2026-01-01")
@click.option("--to", "stop", required=True, help="last UTC date (included when on a step)")
@click.option("--step", default="1 d", show_default=True, help="time step, e.g. 10d, 6 h, 30 min")
@click.option("--format", "fmt", type=click.Choice(["table", "csv"]), default="table",
              show_default=True)
@reports_input_errors
def ephemeris(body, center, start, stop, step, fmt):
    """Print where a body is: position and velocity (csv) or distances and
    elongation (table), J2000 mean equatorial frame, from the truncated
    VSOP87D / ELP2000-82B series. Dates are UTC; the series run on TT
    (TT = UTC + Delta T, Espenak & Meeus).

    \b
    Example:
        rocketsim ephemeris --body mars --from 2026-01-01 --to 2027-01-01 --step 10d
        rocketsim ephemeris --body moon --from 2026-03-01 --to 2026-04-01 --format csv
    """
    from rocketsim.api import ephemeris as positions

    utc = _instants(_utc(start, "--from"), _utc(stop, "--to"), step)
    found = positions(body, utc, center)
    if fmt == "csv":
        click.echo(CSV_COLUMNS)
        for moment, jd, pos, vel in zip(utc, found.jd_tt, found.position / 1e3, found.velocity / 1e3):
            click.echo(f"{moment:%Y-%m-%dT%H:%M:%SZ},{jd:.6f},{pos[0]:.3f},{pos[1]:.3f},"
                       f"{pos[2]:.3f},{vel[0]:.6f},{vel[1]:.6f},{vel[2]:.6f}")
        return
    elongation = found.elongation_deg
    click.echo(f"# {body} from {found.center}, J2000 equatorial; elongation = angle Sun-Earth-{body}")
    click.echo(f"{'utc':<20} {'tt_jd':>15} {'distance_km':>16} {'distance_au':>12} "
               f"{'from_earth_km':>16} {'speed_km_s':>10} {'elongation_deg':>14}")
    speed = found.speed / 1e3
    for k, moment in enumerate(utc):
        elong = f"{elongation[k]:14.3f}" if elongation is not None else f"{'-':>14}"
        click.echo(f"{moment:%Y-%m-%d %H:%M:%S} {found.jd_tt[k]:15.6f} {found.distance[k] / 1e3:16.1f} "
                   f"{found.distance_au[k]:12.6f} {found.from_earth[k] / 1e3:16.1f} {speed[k]:10.4f} {elong}")
