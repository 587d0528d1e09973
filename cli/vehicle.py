"""``rocketsim vehicle``: the stack of a vehicle file, its masses, Delta-v and inertia, and
its design review (``rocketsim.review``)."""

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
    import rocketsim

    review = rocketsim.review(file)
    figures = review.summary
    if fmt == "json":
        click.echo(json.dumps({**figures, "review": review.as_dict()}, indent=2))
    else:
        click.echo(_table(figures) + "\n\n" + review.text())
    if plot is not None:
        from rocketsim.vehicle.build import build
        _plot(plot, review.spec, build(review.spec), figures)
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


def _plot(path: Path, spec, model, figures) -> None:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.patches import Rectangle

    fig, ax = plt.subplots(figsize=(4, 10))
    for s, st in enumerate(spec.stages):
        base = model.stage_base[s]
        r = 0.5 * st.diameter
        ax.add_patch(Rectangle((-r, base), 2 * r, st.length, fill=False, lw=1.2))
        ax.text(r + 0.3, base + 0.5 * st.length, st.name, va="center", fontsize=8)
        for tank in st.tanks:
            ax.add_patch(Rectangle((-tank.radius, base + tank.position), 2 * tank.radius, tank.length,
                                   alpha=0.35, color="tab:blue" if "ox" in tank.propellant.lower()
                                   else "tab:orange"))
        for group in st.engines:
            ax.plot([group.layout_radius, -group.layout_radius] if group.layout_radius else [0.0],
                    [base + group.position] * (2 if group.layout_radius else 1), "kv", ms=5)
        for part in st.point_masses:
            ax.plot([part.radius, -part.radius] if part.radius else [0.0],
                    [base + part.position] * (2 if part.radius else 1), "s", color="gray", ms=4)
    top = model.stage_base[-1] + spec.stages[-1].length
    for part, style in ((spec.payload, dict(color="tab:green", alpha=0.5)),
                        (spec.fairing, dict(fill=False, ls="--"))):
        if part is not None:
            ax.add_patch(Rectangle((-0.5 * part.diameter, top), part.diameter, part.length, **style))
    for key, marker in (("full", "ro"), ("empty", "rx")):
        ax.plot([0.0], [figures[key]["centre_of_mass_m"]], marker, label=f"centre of mass, {key}")
    ax.set_aspect("equal")
    ax.set_xlim(-0.5 * model.length / 4 - 2, model.length / 4 + 2)
    ax.set_ylim(-1, model.length + 1)
    ax.set_ylabel("height above the base (m)")
    ax.set_title(spec.name)
    ax.legend(loc="lower right", fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
