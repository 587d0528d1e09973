"""``rocketsim classic-range``: the classic range of a seed, written as a site file."""

from __future__ import annotations

import math

import click
from rocketsim_cli.errors import output_file


@click.command("classic-range")
@click.option("--seed", type=int, default=0, show_default=True,
              help="the scenario's seed (site: classic generates its range from it)")
@click.option("-o", "--output", type=output_file(),
              help="write the site file here instead of printing it")
def classic_range(seed, output):
    """Print the classic range that 'site: classic' flies from with SEED: the pad on
    the equator, launching due east, its landing zone and drone ship downrange, as a
    site file (angles in radians, exactly as generated; degrees in the comments).
    A scenario naming the file instead of 'classic' flies the same range.

    \b
    Example:
        rocketsim classic-range --seed 11 -o scenarios/sites/classic-11.yaml
    """
    import yaml

    from rocketsim.api import classic_site

    site = classic_site(seed)
    degrees = ", ".join(f"{pad['name']} {_deg(pad['longitude']):.4f} deg E" for pad in site["pads"])
    note = (f"# The classic range of seed {seed}: pad {_deg(site['longitude']):.4f} deg E on the "
            f"equator;\n# {degrees}.\n")
    text = note + yaml.safe_dump(site, sort_keys=False, width=100)
    if output is None:
        click.echo(text, nl=False)
    else:
        output.write_text(text)
        click.echo(f"site: {output}")


def _deg(angle: str) -> float:
    """Degrees of an angle written ``"<radians> rad"``."""
    return math.degrees(float(angle.split()[0]))
