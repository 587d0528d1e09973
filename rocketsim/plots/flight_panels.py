"""Draw a run from its telemetry: one PNG with a panel per quantity.

Altitude, speed, dynamic pressure, acceleration, throttle (with the
propellant on board on a second axis, dashed), attitude and the ground track
on a latitude/longitude map with the coastlines
(:mod:`rocketsim.telemetry.land`). A quantity the telemetry does
not carry (throttle of a rigid body without engines, q in a vacuum run) gets an
empty panel that says so; throttle is a gap while no engine runs. Reads a run's
file only (nothing it carries is executed), or a run in memory.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from rocketsim.plots.canvas import Picture, pyplot, save
from rocketsim.telemetry.land import draw_coastline
from rocketsim.telemetry.reader import read_run
from rocketsim.telemetry.tables import table


def _column(columns: dict, key: str) -> np.ndarray | None:
    values = columns.get(key)
    if values is None or all(v is None for v in values):
        return None
    return np.array([np.nan if v is None else v for v in values], dtype=float)


def run(run, out: str | Path | None = None) -> Path | Picture:
    """Draw ``run``: a :class:`~rocketsim.api.run.Run` (what :func:`rocketsim.fly` and
    :func:`rocketsim.open_run` return) or the path of a run's MCAP file, read without
    executing anything. To the PNG ``out``, returning its path; without ``out``, a
    :class:`~rocketsim.plots.canvas.Picture`."""
    if isinstance(run, (str, Path)):
        file = read_run(run)
        return draw(file, {body: table(run, body) for body in file.bodies}, out, Path(run).stem)
    tables = {name: _sample_columns(body.samples) for name, body in run.bodies.items()}
    return draw(run.file, tables, out, run.path.stem if run.path else "run")


def _sample_columns(samples) -> dict:
    """A body's samples in memory (:class:`~rocketsim.api.samples.Samples`) as the columns
    a file's table has: a number no sample has is None throughout."""
    return {k: [None] * len(v) if v.dtype.kind == "f" and np.isnan(v).all() else v
            for k, v in samples.columns().items()}


def draw(run, tables: dict, out, title: str) -> Path | Picture:
    """Draw ``run`` (a :class:`~rocketsim.telemetry.reader.RunFile`: its events, logs,
    metadata) with each body's columns ``tables[body]`` (:func:`rocketsim.telemetry.tables.table`'s,
    lists or arrays) to the PNG ``out`` (:func:`rocketsim.plots.canvas.save`); ``title``
    names a run whose metadata does not."""
    plt = pyplot()
    figure, axes = plt.subplots(3, 3, figsize=(15, 11))
    panels = {
        "altitude": (axes[0, 0], "altitude", 1e-3, "altitude, km"),
        "speed": (axes[0, 1], "speed", 1.0, "speed, m/s"),
        "airspeed": (axes[0, 1], "airspeed", 1.0, "speed, m/s"),
        "q": (axes[0, 2], "dynamic_pressure", 1e-3, "dynamic pressure q, kPa"),
        "acceleration": (axes[1, 0], "sensed_acceleration", 1.0, "sensed acceleration, m/s^2"),
        "throttle": (axes[1, 1], "throttle", 1.0, "throttle"),     # flown, mean of the engines running
        "mach": (axes[1, 2], "mach", 1.0, "Mach"),
    }
    drawn = set()
    propellant_axis = None
    for body, columns in tables.items():
        t = _column(columns, "t")
        if t is None:
            continue
        for name, (ax, key, scale, label) in panels.items():
            y = _column(columns, key)
            if y is not None:
                ax.plot(t, y * scale, label={"speed": f"{body} inertial", "airspeed": f"{body} air-relative"}.get(name, body))
                ax.set_ylabel(label)
                drawn.add(id(ax))
        propellant = _column(columns, "propellant")
        if propellant is not None:
            if propellant_axis is None:
                propellant_axis = axes[1, 1].twinx()
                propellant_axis.set_ylabel("propellant on board, t (dashed)")
                axes[1, 1].set_ylabel("throttle")
            propellant_axis.plot(t, propellant * 1e-3, ls="--", lw=0.9, label=f"{body} propellant")
            drawn.add(id(axes[1, 1]))
        quaternion = [_column(columns, f"attitude_{c}") for c in "wxyz"]
        if all(q is not None for q in quaternion):
            for c, q in zip("wxyz", quaternion):
                axes[2, 0].plot(t, q, label=f"{body} q{c}")
            axes[2, 0].set_ylabel("attitude quaternion (body -> ECI)")
            drawn.add(id(axes[2, 0]))
        lat, lon = _column(columns, "latitude_deg"), _column(columns, "longitude_deg")
        if lat is not None and lon is not None:
            # break the line where it wraps at the antimeridian
            lon = lon.copy()
            lon[1:][np.abs(np.diff(lon)) > 180.0] = np.nan
            axes[2, 1].plot(lon, lat, label=body)
            axes[2, 1].plot(lon[:1], lat[:1], "o")
            drawn.add(id(axes[2, 1]))
    for event in run.events:
        axes[0, 0].axvline(event["t"], color="grey", lw=0.6, ls=":")
        axes[0, 0].annotate(event["name"], (event["t"], 1.0), xycoords=("data", "axes fraction"),
                            rotation=90, va="top", fontsize=7)
    track = axes[2, 1]
    lats = [v for c in tables.values() for v in c.get("latitude_deg", []) if v is not None]
    lons = [v for c in tables.values() for v in c.get("longitude_deg", []) if v is not None]
    if lats and max(lats) - min(lats) < 20 and max(lons) - min(lons) < 20:
        # a short track: zoom on it (the frame stays latitude/longitude degrees)
        pad = max(0.05, 0.2 * max(max(lats) - min(lats), max(lons) - min(lons)))
        track.set_xlim(min(lons) - pad, max(lons) + pad)
        track.set_ylim(min(lats) - pad, max(lats) + pad)
    else:
        track.set_xlim(-180, 180)
        track.set_ylim(-90, 90)
        track.set_xticks(range(-180, 181, 60))
        track.set_yticks(range(-90, 91, 30))
    draw_coastline(track, track.get_xlim(), track.get_ylim())
    track.grid(True, lw=0.4)
    track.set_aspect("equal")
    track.set_xlabel("longitude, deg")
    track.set_ylabel("latitude, deg")
    track.set_title("ground track")
    if propellant_axis is not None:
        propellant_axis.legend(fontsize=7, loc="lower right")
    axes[2, 2].axis("off")
    axes[2, 2].text(0, 1, _caption(run), va="top", family="monospace", fontsize=8)
    for ax in axes.flat[:8]:
        if ax is track:
            continue
        if id(ax) in drawn:
            ax.set_xlabel("mission time, s")
            ax.grid(True, lw=0.4)
            ax.legend(fontsize=7)
        else:
            ax.text(0.5, 0.5, "not in this run's telemetry", ha="center", va="center",
                    transform=ax.transAxes, color="grey")
    info = run.metadata.get("rocketsim", {})
    figure.suptitle(f"{info.get('scenario', title)}  (epoch {info.get('epoch_utc', '?')})")
    figure.tight_layout()
    return save(figure, out, dpi=80, format="png")


def _caption(run) -> str:
    lines = [f"{len(run.events)} events, {len(run.logs)} log lines"]
    lines += [f"T+{e['t']:.1f} s {e['body']}: {e['name']}" for e in run.events[:12]]
    if run.problem:
        lines.append("file damaged: partial data")
    return "\n".join(lines)
