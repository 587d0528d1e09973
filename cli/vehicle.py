"""``rocketsim vehicle``: the stack of a vehicle file, its masses, Delta-v and inertia, and
its design review (``rocketsim.api.vehicle_report``)."""

from __future__ import annotations

import json
from pathlib import Path

import click

from rocketsim_cli.errors import output_file, reports_input_errors


@click.command()
@click.argument("file", type=click.Path(dir_okay=False, path_type=Path))
@click.option("--format", "fmt", type=click.Choice(["table", "json"]), default="table",
              show_default=True)
@click.option("--plot", type=output_file(),
              help="also draw the stack to scale to this PNG")
@reports_input_errors
def vehicle(file, fmt, plot):
    """Print a staged vehicle's stack: masses per stage, Delta-v per stage (rocket
    equation, vacuum and sea level, 1 % of each stage's propellant unusable, the
    stages above carried along), thrust-to-weight at liftoff, and the centre of
    mass (above the base) and inertia (roll, pitch, yaw about the centre of mass)
    full and empty; then its design review: where the nose sits, the centre of
    pressure and static margin at liftoff and burnout, each stage's peak axial load
    against the structural limit and how it steers, and warnings. FILE is a vehicle
    file, or a scenario (then also the rail-exit speed off its rail). SI units.

    \b
    Examples:
        rocketsim vehicle vehicles/falcon9-block5.yaml
        rocketsim vehicle scenarios/hobby-rocket.yaml
        rocketsim vehicle vehicles/falcon9-block5.yaml --format json --plot f9.png
    """
    from rocketsim.api import vehicle_report

    report = vehicle_report(file)
    if fmt == "json":
        click.echo(json.dumps({**report.figures, "review": report.review.as_dict()}, indent=2))
    else:
        click.echo(_table(report.figures) + "\n\n" + report.review.text())
    if plot is not None:
        from rocketsim.plots import vehicle as plot_vehicle
        plot_vehicle(report, plot)
        click.echo(f"plot: {plot}", err=True)


def _table(f: dict) -> str:
    lines = [f"{f['name']}: {f['length_m']:.1f} m, liftoff {f['liftoff_mass_kg']:,.0f} kg, "
             f"thrust {f['liftoff_thrust_N'] / 1e3:,.0f} kN at sea level, "
             f"T/W {f['liftoff_thrust_to_weight']:.2f}",
             f"payload {f['payload_mass_kg']:,.0f} kg, fairing {f['fairing_mass_kg']:,.0f} kg",
             "",
             f"{'stage':<16}{'wet kg':>12}{'dry kg':>10}{'prop kg':>12}{'eng':>5}{'T vac kN':>10}"
             f"{'Isp vac':>9}{'Isp SL':>8}{'burn s':>8}{'dv vac':>9}{'dv SL':>9}"]
    for s in f["stages"]:
        lines.append(f"{s['name'][:15]:<16}{s['wet_mass_kg']:>12,.0f}{s['dry_mass_kg']:>10,.0f}"
                     f"{s['propellant_mass_kg']:>12,.0f}{s['engines']:>5d}"
                     f"{s['thrust_vacuum_N'] / 1e3:>10,.0f}{s['isp_vacuum_s']:>9.1f}"
                     f"{s['isp_sea_level_s']:>8.1f}{s['burn_time_s']:>8.1f}"
                     f"{s['delta_v_vacuum_m_s']:>9,.0f}{s['delta_v_sea_level_m_s']:>9,.0f}")
    lines.append(f"{'total':<16}{'':>12}{'':>10}{'':>12}{'':>5}{'':>10}{'':>9}{'':>8}{'':>8}"
                 f"{f['delta_v_vacuum_m_s']:>9,.0f}{f['delta_v_sea_level_m_s']:>9,.0f}")
    lines.append("")
    for key in ("full", "empty"):
        p = f[key]
        ixx, iyy, izz = p["inertia_kg_m2"]
        lines.append(f"{key:<6} mass {p['mass_kg']:>12,.0f} kg  centre of mass {p['centre_of_mass_m']:6.2f} m"
                     f"  inertia roll {ixx:.4g}, pitch {iyy:.4g}, yaw {izz:.4g} kg m2")
    return "\n".join(lines)

