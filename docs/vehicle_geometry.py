"""Draws docs/vehicle-geometry.png: where a vehicle file puts each part, to scale.

Two shipped vehicles lying on their sides, base on the left: Notre Dame 2020's
single stage, whose length reaches to the nose's tip (the nose is the top 0.61 m
of the stage it caps), with its boattail, fins, motor, parachute attachment and
the design review's centres of mass and pressure; and the top of the Electron,
whose nose is the top 1.5 m of its fairing. Outlines are the aerodynamics'
own (:func:`rocketsim.vehicle.outline.outline`). Run from the repository:

    python docs/vehicle_geometry.py [out.png]
"""

from __future__ import annotations

import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from rocketsim.scenario.load import validate  # noqa: E402
from rocketsim.scenario.models import VehicleSpec  # noqa: E402
from rocketsim.scenario.yaml_source import read_yaml  # noqa: E402
from rocketsim.vehicle.outline import outline  # noqa: E402
from rocketsim.vehicle.review import review  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]


def _vehicle(name: str) -> VehicleSpec:
    return validate(read_yaml(ROOT / "vehicles" / name), VehicleSpec)


def _body(ax, spec, first: int = 0):
    """Draw the outline of ``spec``'s stages from ``first`` up (base at 0) and return the
    stations of the stages' bases, the length and the nose's base."""
    stages, base = [], 0.0
    for st in spec.stages[first:]:
        stages.append((base, st.length, st.diameter))
        base += st.length
    top = [(p.length, p.diameter) for p in (spec.fairing or spec.payload,) if p is not None]
    tail = spec.aero.boattail
    diameter, total, nose_base, _ = outline(stages, top, spec.aero.nose.length, spec.aero.nose.shape,
                                            None if tail is None or first else (tail.length, tail.diameter))
    x = np.linspace(0.0, total, 1200)
    r = 0.5 * np.array([diameter(v) for v in x])
    ax.fill_between(x, -r, r, color="0.92", zorder=0)
    ax.plot(x, r, "k", x, -r, "k", lw=1.0)
    ax.plot([0, 0], [-r[0], r[0]], "k", lw=1.0)
    for b, _, d in stages[1:]:
        ax.plot([b, b], [-d / 2, d / 2], "k:", lw=0.8)
    return [b for b, _, _ in stages], total, nose_base


def _span(ax, x0, x1, y, text, above=True):
    ax.annotate("", xy=(x1, y), xytext=(x0, y), arrowprops=dict(arrowstyle="<->", lw=0.8))
    ax.text(0.5 * (x0 + x1), y + (0.012 if above else -0.012), text, ha="center",
            va="bottom" if above else "top", fontsize=8)


def _ndrt(ax):
    spec = _vehicle("ndrt-2020.yaml")
    stage = spec.stages[0]
    _, total, nose_base = _body(ax, spec)
    d = stage.diameter
    _span(ax, 0.0, total, 0.225, f"stage 'rocket': length {stage.length:g} m, from its base to the "
          "nose's tip (the nose included)")
    _span(ax, nose_base, total, 0.125, f"aero.nose: length {spec.aero.nose.length:g} m,\nthe top of "
          "the stage it caps")
    tail = spec.aero.boattail
    _span(ax, 0.0, tail.length, -0.14, f"aero.boattail\n{tail.length:g} m, to {tail.diameter * 1e3:g} mm",
          above=False)
    fins = spec.aero.fins[0]
    # stations are of the root's leading (upper) edge: the fin reaches down from it
    root_le, root_te = fins.position, fins.position - fins.root_chord
    tip_le = root_le - fins.sweep
    tip_te = tip_le - fins.tip_chord
    span = d / 2 + fins.span
    ax.fill([root_te, root_le, tip_le, tip_te], [d / 2, d / 2, span, span], color="0.75", ec="k", lw=0.8)
    ax.annotate(f"aero.fins[0].position: {fins.position:g} m\n(the root's leading edge above the base)",
                xy=(root_le, span), xytext=(0.42, 0.29), fontsize=8,
                arrowprops=dict(arrowstyle="->", lw=0.6))
    motor = stage.motors[0]
    ax.add_patch(plt.Rectangle((motor.position, -motor.diameter / 2), motor.length, motor.diameter,
                               fill=False, hatch="///", lw=0.8))
    ax.annotate(f"motors[0].position: {motor.position:g} m (its nozzle exit)", xy=(motor.position, -0.02),
                xytext=(0.35, -0.27), fontsize=8, arrowprops=dict(arrowstyle="->", lw=0.6))
    chute = stage.parachutes[0].attachment
    ax.plot([chute], [0.0], "kD", ms=4)
    ax.annotate(f"parachutes' attachment: {chute:g} m", xy=(chute, 0.0), xytext=(1.75, -0.27), fontsize=8,
                arrowprops=dict(arrowstyle="->", lw=0.6))
    liftoff = review(spec).phases[0]
    ax.plot([liftoff.centre_of_mass_m], [0.0], "o", mfc="white", mec="tab:blue", ms=8, mew=1.5)
    ax.plot([liftoff.centre_of_pressure_m], [0.0], "x", color="tab:red", ms=8, mew=1.5)
    ax.text(liftoff.centre_of_mass_m, 0.045, "CM", color="tab:blue", ha="center", fontsize=8)
    ax.text(liftoff.centre_of_pressure_m, -0.06, "CP", color="tab:red", ha="center", fontsize=8)
    ax.set_title(f"vehicles/ndrt-2020.yaml: one stage capped by its nose; at liftoff the centre of "
                 f"pressure (Barrowman) is {liftoff.static_margin_cal:.2f} calibres behind the centre "
                 "of mass", fontsize=9)
    ax.set_ylim(-0.34, 0.38)
    ax.set_xlim(-0.1, total + 0.1)


def _electron(ax):
    spec = _vehicle("electron.yaml")
    bases, total, nose_base = _body(ax, spec, first=1)
    stage = spec.stages[1]
    top = bases[0] + stage.length
    ax.plot([top, top], [-spec.fairing.diameter / 2, spec.fairing.diameter / 2], "k:", lw=0.8)
    payload = spec.payload
    ax.add_patch(plt.Rectangle((top, -payload.diameter / 2), payload.length, payload.diameter,
                               color="tab:green", alpha=0.35))
    ax.text(top + 0.5 * payload.length, 0.0, "payload", ha="center", va="center", fontsize=8)
    _span(ax, 0.0, top, 0.9, f"second stage: length {stage.length:g} m, positions above its base")
    _span(ax, top, total, 1.2, f"fairing: length {spec.fairing.length:g} m, the nose included")
    _span(ax, nose_base, total, 0.75, f"aero.nose: {spec.aero.nose.length:g} m,\nthe top of the fairing")
    ax.set_title("vehicles/electron.yaml, second stage up: the nose caps the fairing (else the payload, "
                 "else the top stage)", fontsize=9)
    ax.set_ylim(-1.0, 1.6)
    ax.set_xlim(-0.2, total + 0.2)


def main(out: Path) -> None:
    fig, axes = plt.subplots(2, 1, figsize=(11, 7.2), gridspec_kw={"height_ratios": [1.1, 1]})
    _ndrt(axes[0])
    _electron(axes[1])
    for ax in axes:
        ax.set_aspect("equal")
        ax.set_xlabel("station: height above the vehicle's base (m)", fontsize=8)
        ax.tick_params(labelsize=7)
        ax.set_yticks([])
    fig.tight_layout()
    fig.savefig(out, dpi=130)
    plt.close(fig)


if __name__ == "__main__":
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else ROOT / "docs" / "vehicle-geometry.png")
