"""``rocketsim windows``: launch windows to Mars or the Moon, porkchop plot, mission fragment."""

from __future__ import annotations

import datetime as _dt
import json
import math
import sys
from pathlib import Path

from typing import TYPE_CHECKING

import click

from rocketsim.constants import SECONDS_PER_DAY
from rocketsim.errors import InputError
from rocketsim_cli.ephemeris import _utc
from rocketsim_cli.errors import output_file, reports_input_errors
from rocketsim_cli.lazy import LibraryChoice
from rocketsim_cli.units import Quantity

if TYPE_CHECKING:
    from rocketsim.transfer import windows as transfer_windows

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
    from rocketsim.scenario.units import UnitError, parse_quantity
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


def _days(text: str) -> float:
    """A time of flight in days: a bare number of days, or a time with its unit."""
    try:
        return float(text)
    except ValueError:
        from rocketsim.scenario.units import parse_quantity
        return parse_quantity(text, "time") / SECONDS_PER_DAY


def _positive(value, option, unit):
    if value is not None and not value > 0.0:
        raise InputError(f"must be positive, got {value:g} {unit}", field=option)
    return value


class _Clock:
    """TT Julian dates <-> UTC, anchored at the first departure (Delta T held)."""

    def __init__(self, start: _dt.datetime):
        from rocketsim.timescales import Epoch
        self.epoch = Epoch.from_utc(start)
        self.jd_tt0 = self.epoch.jd_tt()

    def jd_tt(self, moment: _dt.datetime) -> float:
        return self.jd_tt0 + (moment - self.epoch.utc).total_seconds() / SECONDS_PER_DAY

    def utc(self, jd_tt: float) -> _dt.datetime:
        return self.epoch.utc_at((jd_tt - self.jd_tt0) * SECONDS_PER_DAY)


def _row(window: transfer_windows.Window, clock: _Clock) -> dict:
    return {
        "departure_utc": f"{clock.utc(window.departure_jd_tt):%Y-%m-%dT%H:%M:%SZ}",
        "arrival_utc": f"{clock.utc(window.arrival_jd_tt):%Y-%m-%dT%H:%M:%SZ}",
        "tof_days": round(window.tof_days, 3),
        "c3_km2_s2": round(window.c3 / 1e6, 4),
        "dla_deg": round(math.degrees(window.dla), 3),
        "rla_deg": round(math.degrees(window.rla), 3),
        "vinf_arrival_km_s": round(window.vinf_arrival / 1e3, 4),
        "dv_departure_km_s": round(window.dv_departure / 1e3, 4),
        "dv_arrival_km_s": round(window.dv_arrival / 1e3, 4),
        "dv_total_km_s": round(window.dv_total / 1e3, 4),
    }


def _print(rows: list[dict], fmt: str, target: str) -> None:
    if fmt == "json":
        click.echo(json.dumps(rows, indent=2))
        return
    columns = list(rows[0]) if rows else list(JSON_KEYS)
    if fmt == "csv":
        click.echo(",".join(columns))
        for row in rows:
            click.echo(",".join(str(row[c]) for c in columns))
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
                   f"{row['dv_arrival_km_s']:7.3f} {row['dv_total_km_s']:8.3f}")


def _porkchop(path: Path, found: transfer_windows.Search, clock: _Clock) -> None:
    """Contours of C3 and arrival v_inf over departure x arrival dates."""
    import matplotlib
    import numpy as np
    matplotlib.use("Agg")
    import matplotlib.dates as mdates
    import matplotlib.pyplot as plt

    grid = found.grid
    departures = [clock.utc(jd) for jd in grid.departure_jd[:, 0]]
    arrivals = [clock.utc(jd) for jd in grid.arrival_jd[0, :]]
    x = mdates.date2num(departures)
    y = mdates.date2num(arrivals)
    c3 = grid.c3.T / 1e6
    vinf = grid.vinf_arrival.T / 1e3
    fig, ax = plt.subplots(figsize=(10, 8))
    if np.isfinite(c3).any():
        low = float(np.nanmin(c3))
        span = max(1.0, abs(low))
        c3_levels = low + span * np.array([0.02, 0.1, 0.25, 0.5, 1.0, 2.0, 4.0])
        lines = ax.contour(x, y, c3, levels=c3_levels, colors="tab:red", linewidths=1.0)
        ax.clabel(lines, fmt="%.1f", fontsize=8)
        low_v = float(np.nanmin(vinf))
        v_levels = low_v + np.array([0.1, 0.5, 1.0, 2.0, 3.0])
        lines = ax.contour(x, y, vinf, levels=v_levels, colors="tab:blue", linewidths=0.8,
                           linestyles="dashed")
        ax.clabel(lines, fmt="%.1f", fontsize=8)
    for k, window in enumerate(found.windows, 1):
        ax.plot(mdates.date2num(clock.utc(window.departure_jd_tt)),
                mdates.date2num(clock.utc(window.arrival_jd_tt)), "k*", markersize=10)
        ax.annotate(str(k), (mdates.date2num(clock.utc(window.departure_jd_tt)),
                             mdates.date2num(clock.utc(window.arrival_jd_tt))),
                    textcoords="offset points", xytext=(6, 6))
    ax.xaxis_date()
    ax.yaxis_date()
    ax.xaxis.set_major_formatter(mdates.DateFormatter("%Y-%m-%d"))
    ax.yaxis.set_major_formatter(mdates.DateFormatter("%Y-%m-%d"))
    fig.autofmt_xdate()
    ax.set_xlabel("departure (UTC)")
    ax.set_ylabel("arrival (UTC)")
    ax.set_title(f"Earth to {found.target.name}: C3 (km²/s², red) and arrival v∞ "
                 "(km/s, blue dashed); * windows")
    ax.grid(alpha=0.3)
    fig.savefig(path, dpi=120)
    plt.close(fig)


def _fragment(window: transfer_windows.Window, clock: _Clock, target: str,
              orbits: transfer_windows.Orbits) -> str:
    departure = clock.utc(window.departure_jd_tt)
    arrival = clock.utc(window.arrival_jd_tt)
    vector = [round(c / 1e3, 6) for c in window.vinf_departure]
    capture = {"periapsis_altitude": f"{orbits.capture_periapsis_altitude / 1e3:g} km",
               "apoapsis_altitude": f"{(orbits.capture_apoapsis_altitude if orbits.capture_apoapsis_altitude is not None else orbits.capture_periapsis_altitude) / 1e3:g} km"}
    burn = {
        "epoch": f"{departure:%Y-%m-%dT%H:%M:%SZ}",
        "parking_orbit_altitude": f"{orbits.parking_altitude / 1e3:g} km",
        "c3_km2_s2": round(window.c3 / 1e6, 4),
        ("v_infinity_km_s" if target == "mars" else "burn_vector_km_s"): vector,
        "rla_deg": round(math.degrees(window.rla), 4),
        "dla_deg": round(math.degrees(window.dla), 4),
        "dv": f"{window.dv_departure / 1e3:.4f} km/s",
    }
    data = {
        "mission": {"name": f"earth-{target}-{departure:%Y-%m-%d}",
                    "epoch": f"{departure:%Y-%m-%dT%H:%M:%SZ}"},
        "departure_burn": burn,
        "arrival": {"body": target, "epoch": f"{arrival:%Y-%m-%dT%H:%M:%SZ}",
                    "tof": f"{window.tof_days:.4f} d",
                    "v_infinity": f"{window.vinf_arrival / 1e3:.4f} km/s",
                    "capture_orbit": capture,
                    "dv": f"{window.dv_arrival / 1e3:.4f} km/s"},
    }
    note = (f"# Launch window to {target} from `rocketsim windows` (patched conics: Izzo's\n"
            "# Lambert solver between the bodies' centres on the project's VSOP87D/ELP2000\n"
            "# ephemerides). `mission` goes into a scenario's mission; `departure_burn` is\n"
            "# the target of the departure burn (J2000 mean equatorial frame; for the Moon\n"
            "# the burn vector itself, from a parking orbit in the Moon's plane).\n")
    import yaml
    return note + yaml.safe_dump(data, sort_keys=False)


def _targets() -> list[str]:
    from rocketsim.transfer import windows as transfer_windows
    return sorted(transfer_windows.TARGETS)


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
@reports_input_errors
def windows(target, start, stop, step, parking_orbit, capture_orbit, max_c3, max_vinf,
            tof_range, objective, count, plot, fmt, mission_fragment, pick):
    """Search launch windows: Lambert arcs (Izzo) over a grid of departure and
    arrival dates on the project's ephemerides, refined to the optima, priced
    as escape from a circular parking orbit plus capture at the target
    (patched conics). Lists departure, arrival, time of flight, C3, the
    declination of the departure asymptote, arrival v-infinity and delta-v.

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
    import numpy as np

    from rocketsim.scenario.units import UnitError, parse_quantity
    from rocketsim.transfer import windows as transfer_windows

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
    tgt = transfer_windows.target(target)
    if tof_range is not None:
        try:
            lo, hi = (_days(v) for v in tof_range.split(":"))
        except (ValueError, UnitError):
            raise InputError(f"expected MIN:MAX, in days or with units ('120:400', '2 d:200 h'), "
                             f"got {tof_range!r}", field="--tof") from None
        if not 0.0 < lo < hi:
            raise InputError(f"need 0 < MIN < MAX, got {tof_range!r}", field="--tof")
    else:
        lo, hi = tgt.tof_days
    if target == "mars":
        _positive(max_c3, "--max-c3", "m2/s2")          # lunar C3 is negative (bound orbits)
    _positive(max_vinf, "--max-vinf", "m/s")
    periapsis, apoapsis = _capture(capture_orbit)
    orbits = transfer_windows.Orbits(parking_altitude=_length(parking_orbit, "--parking-orbit"),
                                     capture_periapsis_altitude=periapsis,
                                     capture_apoapsis_altitude=apoapsis)

    clock = _Clock(first)
    step_days = step_s / SECONDS_PER_DAY
    jd_first, jd_last = clock.jd_tt(first), clock.jd_tt(last)
    departure = jd_first + step_days * np.arange(math.floor((jd_last - jd_first) / step_days + 1e-9) + 1)
    arrival_first = departure[0] + lo
    arrival = arrival_first + step_days * np.arange(
        math.floor((departure[-1] + hi - arrival_first) / step_days + 1e-9) + 1)
    cells = departure.size * arrival.size
    if cells > MAX_CELLS:
        raise InputError(f"{departure.size} x {arrival.size} = {cells:,} grid cells: at most "
                         f"{MAX_CELLS:,}; use a larger --step or a shorter range", field="--step")

    options = dict(target_name=target, objective=objective, orbits=orbits,
                   max_c3=max_c3, max_vinf_arrival=max_vinf,
                   tof_days=(lo, hi), count=count)
    if cells >= PROGRESS_CELLS and sys.stderr.isatty():
        with click.progressbar(length=departure.size, label="searching", file=sys.stderr) as bar:
            done = [0]

            def advance(rows, total):
                bar.update(rows - done[0])
                done[0] = rows
            found = transfer_windows.search(departure, arrival, progress=advance, **options)
    else:
        found = transfer_windows.search(departure, arrival, **options)

    rows = [_row(w, clock) for w in found.windows]
    if not rows and fmt == "table":
        click.echo("no window within the limits in this range", err=True)
    _print(rows, fmt, target)
    if plot is not None:
        _porkchop(plot, found, clock)
        click.echo(f"porkchop plot written to {plot}", err=True)
    if mission_fragment is not None:
        if pick > len(found.windows):
            raise InputError(f"--pick {pick}: only {len(found.windows)} window(s) found",
                             field="--pick")
        mission_fragment.write_text(_fragment(found.windows[pick - 1], clock, target, orbits))
        click.echo(f"mission fragment written to {mission_fragment}", err=True)
