"""A staged vehicle's stack drawn to scale: each stage's outline and name, its tanks
(oxidiser blue, fuel orange), engines (triangles) and point masses (grey squares), the
payload and the fairing (dashed), and the centre of mass full and empty; heights above
the vehicle's base, m."""

from __future__ import annotations

from pathlib import Path

from rocketsim.plots.canvas import Picture, pyplot, save


def vehicle(report, out: str | Path | None = None) -> Path | Picture:
    """Draw the stack of ``report`` (a :class:`~rocketsim.api.vehicle_figures.VehicleReport`)
    to the PNG ``out`` and return its path, or without ``out`` return the picture."""
    from matplotlib.patches import Rectangle

    spec, model, figures = report.spec, report.model, report.figures
    plt = pyplot()
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
    return save(fig, out, dpi=120)
