"""``rocketsim windows``: launch windows to Mars or the Moon, porkchop plot, mission fragment."""

from __future__ import annotations

import datetime as _dt
import json
import sys

import click

from rocketsim.errors import InputError
from rocketsim_cli.ephemeris import _utc
from rocketsim_cli.errors import output_file, reports_input_errors
from rocketsim_cli.lazy import LibraryChoice
from rocketsim_cli.units import Quantity

DEFAULTS = {
    # target: (from, to, step) of the departure dates searched by default
    "mars": ("2026-06-01", "2027-06-01", "1 d"),
    "moon": ("2026-12-01", "2026-12-31", "2 h"),
}
MAX_CELLS = 3_000_000
PROGRESS_CELLS = 200_000          # grids at least this large show a progress bar
JSON_KEYS = ("departure_utc", "arrival_utc", "tof_days", "c3_km2_s2", "vinf_arrival_km_s",
             "dv_total_km_s")


def _length(text: str, option: str) -> float:
    from rocketsim.api import UnitError, parse_quantity
    try:
        value = parse_quantity(text, "length")
    except UnitError as error:
        raise InputError(str(error), field=option) from None
    if not value >= 0.0:
        raise InputError(f"an altitude must not be negative, got {text!r}", field=option)
    return value


def _capture(text: str) -> tuple[float, float | None]:
    """'400km' (circular) or '400km x 33000km' (periapsis x apoapsis altitudes)."""
    parts = [p for p in text.lower().split("x") if p.strip()]
    if len(parts) not in (1, 2):
        raise InputError(f"expected '400km' or '400km x 33000km', got {text!r}",
                         field="--capture-orbit")
    periapsis = _length(parts[0], "--capture-orbit")
    apoapsis = _length(parts[1], "--capture-orbit") if len(parts) == 2 else None
    if apoapsis is not None and apoapsis < periapsis:
        raise InputError("the apoapsis altitude is below the periapsis altitude",
                         field="--capture-orbit")
    return periapsis, apoapsis


def _positive(value, option, unit):
    if value is not None and not value > 0.0:
        raise InputError(f"must be positive, got {value:g} {unit}", field=option)
    return value


def _print(rows: list[dict], fmt: str, target: str) -> None:
    if fmt == "json":
        click.echo(json.dumps(rows, indent=2))
        return
    columns = list(rows[0]) if rows else list(JSON_KEYS)
    if fmt == "csv":
        click.echo(",".join(columns))
        for row in rows:
            click.echo(",".join("" if row[c] is None else str(row[c]) for c in columns))
        return
    dec = "dla_deg" if target == "mars" else "moon_dec_deg"
    click.echo(f"{'#':>2} {'departure (UTC)':<20} {'arrival (UTC)':<20} {'tof_d':>8} "
               f"{'C3_km2/s2':>10} {dec:>12} {'vinf_arr_km/s':>13} {'dv_dep':>7} "
               f"{'dv_arr':>7} {'dv_km/s':>8}")
    for k, row in enumerate(rows, 1):
        click.echo(f"{k:>2} {row['departure_utc'][:16].replace('T', ' '):<20} "
                   f"{row['arrival_utc'][:16].replace('T', ' '):<20} {row['tof_days']:8.1f} "
                   f"{row['c3_km2_s2']:10.3f} {row['dla_deg']:12.2f} "
                   f"{row['vinf_arrival_km_s']:13.3f} {row['dv_departure_km_s']:7.3f} "
                   f"{row['dv_arrival_km_s']:7.3f} {row['dv_total_km_s']:8.3f}"
                   + ("  EDGE" if row["edge"] else ""))
    for k, row in enumerate(rows, 1):
        if row["edge"]:
            click.echo(f"EDGE: #{k} lies on {row['edge']}: the best in this range, not an optimum "
                       "(widen the range to find it)")


def _targets() -> list[str]:
    from rocketsim.api import window_targets
    return window_targets()


@click.command()
@click.option("--target", type=LibraryChoice(_targets), required=True,
              help="where to go")
@click.option("--from", "start", default=None,
              help="first departure date, UTC [default: 2026-06-01 (mars), 2026-12-01 (moon)]")
@click.option("--to", "stop", default=None,
              help="last departure date, UTC [default: a year (mars) or a month (moon) later]")
@click.option("--step", default=None, help="grid step [default: 1 d for mars, 2 h for the moon]")
@click.option("--parking-orbit", default="200km", show_default=True,
              help="altitude of the circular parking orbit at Earth")
@click.option("--capture-orbit", default="400km", show_default=True,
              help="capture orbit at the target: '400km' (circular) or '400km x 33000km'")
@click.option("--max-c3", type=Quantity("specific_energy", "20 km2/s2"), default=None,
              help="largest C3 accepted, e.g. '20 km2/s2'")
@click.option("--max-vinf", type=Quantity("speed", "3 km/s"), default=None,
              help="largest arrival v-infinity accepted, e.g. '3 km/s'")
@click.option("--tof", "tof_range", default=None,
              help="time-of-flight range, days or with units, e.g. 120:400 or '2 d:200 h' "
                   "[default: 90:500 mars, 2:8 moon]")
@click.option("--by", "objective", type=click.Choice(["dv", "c3"]), default="dv",
              show_default=True, help="rank windows by total delta-v or by C3")
@click.option("--count", type=click.IntRange(1, 20), default=3, show_default=True,
              help="how many windows to list")
@click.option("--plot", "plot", type=output_file(), default=None,
              help="write a porkchop plot (PNG) here")
@click.option("--format", "fmt", type=click.Choice(["table", "csv", "json"]), default="table",
              show_default=True)
@click.option("--mission-fragment", type=output_file(),
              default=None, help="write the chosen window as a mission-file fragment (YAML)")
@click.option("--pick", type=click.IntRange(1, 20), default=1, show_default=True,
              help="which listed window --mission-fragment writes")
@click.option("--parking-inclination", type=Quantity("angle", "31 deg"), default=None,
              help="the parking orbit's inclination in the mission fragment, e.g. '31 deg' "
                   "[default: the least that holds the departure asymptote] (Mars)")
@reports_input_errors
def windows(target, start, stop, step, parking_orbit, capture_orbit, max_c3, max_vinf,
            tof_range, objective, count, plot, fmt, mission_fragment, pick, parking_inclination):
    """Search launch windows: Lambert arcs (Izzo) over a grid of departure and
    arrival dates on the project's ephemerides, refined to the optima, priced
    as escape from a circular parking orbit plus capture at the target
    (patched conics). Lists departure, arrival, time of flight, C3, the
    declination of the departure asymptote, arrival v-infinity and delta-v;
    a window whose optimum lies on a bound of the search (its first or last
    date, a time-of-flight limit) is marked EDGE: the best in the range, not
    an optimum.

    --mission-fragment writes the chosen window as a mission file: the
    departure epoch, a start in the parking orbit whose plane holds the
    departure asymptote (the Moon's orbital plane for the Moon), a duration
    to the arrival, n-body gravity; a scenario names it as its mission.

    For the Moon the arc runs from the parking orbit (assumed in the Moon's
    plane, burning 179 deg before arrival) to the Moon's centre; the
    declination column is then the Moon's at arrival.

    \b
    Example:
        rocketsim windows --target mars --plot porkchop.png
        rocketsim windows --target mars --from 2026-09-01 --to 2027-01-31 \\
            --max-c3 '20 km2/s2' --by c3 --format json --mission-fragment mars-2026.yaml
        rocketsim windows --target moon --from 2026-12-01 --to 2026-12-15
    """
    from rocketsim.api import UnitError, days, launch_windows, parse_quantity, window_grid

    default_from, default_to, default_step = DEFAULTS[target]
    first = _utc(start or default_from, "--from")
    if stop is None and start is not None:
        last = first + (_dt.timedelta(days=365) if target == "mars" else _dt.timedelta(days=30))
    else:
        last = _utc(stop or default_to, "--to")
    if last < first:
        raise InputError(f"{last:%Y-%m-%d} is before --from ({first:%Y-%m-%d})", field="--to")
    try:
        step_s = parse_quantity(step or default_step, "time")
    except UnitError as error:
        raise InputError(str(error), field="--step") from None
    if not step_s > 0.0:
        raise InputError(f"the step must be positive, got {step!r}", field="--step")
    tof_days = None
    if tof_range is not None:
        try:
            lo, hi = (days(v) for v in tof_range.split(":"))
        except (ValueError, UnitError):
            raise InputError(f"expected MIN:MAX, in days or with units ('120:400', '2 d:200 h'), "
                             f"got {tof_range!r}", field="--tof") from None
        if not 0.0 < lo < hi:
            raise InputError(f"need 0 < MIN < MAX, got {tof_range!r}", field="--tof")
        tof_days = (lo, hi)
    if target == "mars":
        _positive(max_c3, "--max-c3", "m2/s2")          # lunar C3 is negative (bound orbits)
    _positive(max_vinf, "--max-vinf", "m/s")
    periapsis, apoapsis = _capture(capture_orbit)
    parking = _length(parking_orbit, "--parking-orbit")

    grid = window_grid(target, first, last, step_s, tof_days)
    if grid.cells > MAX_CELLS:
        raise InputError(f"{grid.departure_jd.size} x {grid.arrival_jd.size} = {grid.cells:,} grid cells: "
                         f"at most {MAX_CELLS:,}; use a larger --step or a shorter range", field="--step")

    options = dict(objective=objective, parking_altitude=parking, capture_periapsis_altitude=periapsis,
                   capture_apoapsis_altitude=apoapsis, max_c3=max_c3, max_vinf_arrival=max_vinf,
                   count=count)
    if grid.cells >= PROGRESS_CELLS and sys.stderr.isatty():
        with click.progressbar(length=grid.departure_jd.size, label="searching", file=sys.stderr) as bar:
            done = [0]

            def advance(rows, total):
                bar.update(rows - done[0])
                done[0] = rows
            found = launch_windows(grid, progress=advance, **options)
    else:
        found = launch_windows(grid, **options)

    rows = found.rows()
    if not rows and fmt == "table":
        click.echo("no window within the limits in this range", err=True)
    _print(rows, fmt, target)
    if plot is not None:
        from rocketsim.plots import porkchop
        porkchop(found, plot)
        click.echo(f"porkchop plot written to {plot}", err=True)
    if mission_fragment is not None:
        if pick > len(found.windows):
            raise InputError(f"--pick {pick}: only {len(found.windows)} window(s) found",
                             field="--pick")
        try:
            text = found.fragment(pick - 1, parking_inclination)
        except InputError as error:
            raise InputError(error.message, field="--parking-inclination") from None
        mission_fragment.write_text(text)
        click.echo(f"mission fragment written to {mission_fragment}", err=True)
