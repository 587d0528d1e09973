"""``rocketsim atmosphere``: print (and plot) the air of a day or of Mars."""

from __future__ import annotations

from pathlib import Path

import click

from rocketsim.errors import InputError
from rocketsim_cli.errors import output_file, reports_input_errors


def _quantity(text: str, dimension: str, option: str) -> float:
    from rocketsim.api import UnitError, parse_quantity
    try:
        return parse_quantity(text, dimension)
    except UnitError as error:
        raise InputError(str(error), field=option) from None


def _epoch(text: str | None):
    """The ``--epoch`` option as a UTC datetime (None when not given)."""
    import datetime as dt
    if text is None:
        return None
    try:
        value = dt.datetime.fromisoformat(text.strip())
    except ValueError:
        raise InputError(f"not an ISO 8601 instant: {text!r}", field="--epoch") from None
    return value.replace(tzinfo=dt.timezone.utc) if value.tzinfo is None else value


@click.command()
@click.option("--weather", type=click.Path(dir_okay=False, exists=True, path_type=Path),
              help="weather YAML (kind: standard | sounding | random | classic | reanalysis)")
@click.option("--body", type=click.Choice(["earth", "mars"]), default="earth", show_default=True)
@click.option("--latitude", default="45 deg", show_default=True,
              help="site geodetic latitude (gravity, random days, reanalysis)")
@click.option("--longitude", default="0 deg", show_default=True,
              help="site longitude, east positive (reanalysis)")
@click.option("--epoch", help="UTC instant, ISO 8601 (reanalysis), e.g. 2020-02-23T16:00Z")
@click.option("--from", "h_from", default="0 m", show_default=True, help="lowest height")
@click.option("--to", "h_to", default="100 km", show_default=True, help="highest height")
@click.option("--step", "h_step", default="1 km", show_default=True, help="height step")
@click.option("--format", "fmt", type=click.Choice(["table", "csv"]), default="table",
              show_default=True)
@click.option("--plot", type=output_file(),
              help="also draw temperature, pressure, density and wind to this PNG")
@reports_input_errors
def atmosphere(weather, body, latitude, longitude, epoch, h_from, h_to, h_step, fmt, plot):
    """Print the air against height: temperature, pressure, density, speed of sound
    (and wind, when the day has any). Heights are geometric, above the reference
    ellipsoid (Earth) or sphere (Mars); the air above 600 km is not tabulated.

    \b
    Examples:
        rocketsim atmosphere --to 50km --step 5km
        rocketsim atmosphere --weather day.yaml --latitude "28.5 deg" --format csv
        rocketsim atmosphere --body mars --to 150km --plot mars.png
    where day.yaml is a weather section, e.g. "kind: random" and "seed: 7"
    on two lines, or "kind: sounding" and "file: 72357_OUN_20110522_12Z.txt";
    a reanalysis ("kind: reanalysis", "file: era5.nc") also needs --longitude and --epoch.
    """
    import numpy as np

    from rocketsim.api import atmosphere as air_profile

    lat = _quantity(latitude, "angle", "--latitude")
    lo, hi = _quantity(h_from, "length", "--from"), _quantity(h_to, "length", "--to")
    step = _quantity(h_step, "length", "--step")
    if step <= 0 or hi < lo:
        raise InputError("need --step > 0 and --to >= --from", field="--step")
    if hi > 600_000.0:
        raise InputError("the tables stop at 600 km (the flight model sees no air above)",
                         field="--to")
    if (hi - lo) / step > 1_000_000:
        raise InputError("more than a million rows: use a larger --step", field="--step")
    longitude, moment = _quantity(longitude, "angle", "--longitude"), _epoch(epoch)
    if body == "mars" and weather is not None:
        raise InputError("--weather is for Earth; Mars has one mean atmosphere", field="--weather")
    heights = lo + step * np.arange(int(np.floor((hi - lo) / step + 1e-9)) + 1)
    profile = air_profile(heights, weather=weather, body=body, latitude=lat, longitude=longitude,
                          epoch=moment)
    names, rows = list(profile.columns), list(profile.columns.values())
    if fmt == "csv":
        click.echo(",".join(names))
        for values in zip(*rows):
            click.echo(",".join(f"{v:.6g}" for v in values))
    else:
        click.echo("".join(f"{n:>16}" for n in names))
        for values in zip(*rows):
            click.echo("".join(f"{v:>16.6g}" for v in values))
    if plot is not None:
        from rocketsim.plots import atmosphere as plot_air
        plot_air(profile, plot)
        click.echo(f"plot: {plot}", err=True)
