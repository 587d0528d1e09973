"""The pictures of a campaign report: the landing map, the output histograms, the tornado
of sensitivities. PNG files, drawn the way :mod:`rocketsim.plots.flight_panels` draws a
run (80 dpi).

- ``landing.png``: a row per body that came down: the landing points about the target
  (east/north on the target's tangent plane, m or km) over the land and coastline of
  :mod:`rocketsim.telemetry.land` (its 0.1 degree grid, sampled at each map point), the
  50/90/99 % covariance ellipses (2-D probability), the target and the mean; on the left
  framed on the target with the R50/R90/R99 circles about it, on the right zoomed on the
  scatter with the circles about the mean.
- ``histograms.png``: a panel per output chosen for the campaign (:func:`histogram_columns`:
  its own outputs, then per body that came down the miss distance, the impact speed,
  the touchdown's speeds and tilt, the apogee and the largest speed and load in flight,
  per body that stayed in orbit its orbit), each with its mean and 5-95 % range, plain
  tick labels (no offset) and a title saying what it is.
- ``sensitivities.png``: a tornado per main output: Spearman's rho and the SRC of each
  input, largest |rho| on top, with the fit's R².
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from rocketsim.campaigns.landing import geodetic_of
from rocketsim.campaigns.outputs import BODY_SECTIONS
from rocketsim.plots.canvas import pyplot, save
from rocketsim.telemetry.land import land_fraction

KM_ABOVE = 5000.0                # m: a map wider than this is drawn in km
LAND_GRID = 100                  # samples of the land grid per map axis
_LAND = "#efe6d2"                # land fill; the coastline is telemetry.land's grey
_STYLES = ("-", "--", ":")


def campaign(report, folder: str | Path) -> list[Path]:
    """Draw what ``report`` (a :class:`~rocketsim.campaigns.report.Report`) has to show into
    ``folder`` (made if need be): ``landing.png`` when a body came down, the histograms of
    its main outputs over the ok runs and their sensitivities; return the paths."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    title, main = report.name, report.main
    files = []
    if report.dispersions:
        files.append(landing_map(report.dispersions, report.target, folder / "landing.png", title))
    chosen = histogram_columns(report)
    if chosen:
        files.append(histograms(report.flown, chosen, folder / "histograms.png", title))
    if main:
        table = report.tables["sensitivities"]
        if len(table[table["output"].isin(main)]):
            files.append(tornado(table, main, folder / "sensitivities.png", title))
    return files


def _grid(count: int, columns: int):
    ncols = max(1, min(count, columns))
    return ncols, math.ceil(count / ncols)


def _finish(figure, axes, used: int, out: Path, title: str, spacing: dict | None) -> Path:
    """Blank the panels past the ``used`` ones, title, lay out (``spacing`` for
    ``subplots_adjust``: a grid of many panels, where ``tight_layout`` costs seconds; None
    for ``tight_layout``), write the PNG ``out`` and close the figure."""
    for ax in list(axes.flat)[used:]:
        ax.axis("off")
    height = figure.get_size_inches()[1]
    figure.suptitle(title, y=1.0 - 0.12 / height, va="top")
    if spacing is None:
        figure.tight_layout(rect=(0.0, 0.0, 1.0, 1.0 - 0.4 / height))
    else:       # the title's line, then the panels' titles (two lines at most) under it
        figure.subplots_adjust(**{"right": 0.98, "bottom": 0.06, "top": 1.0 - 0.75 / height, **spacing})
    return save(figure, out, dpi=80, format="png")


def _draw_land(ax, target: dict, east_limits, north_limits, scale: float) -> None:
    """Shade the land and draw the coastline on the map of ``target`` (limits in m)."""
    east = np.linspace(*east_limits, LAND_GRID)
    north = np.linspace(*north_limits, LAND_GRID)
    e, n = np.meshgrid(east, north)
    lat, lon = geodetic_of(e, n, target["latitude_deg"], target["longitude_deg"])
    land = np.array([land_fraction(a, b) for a, b in zip(lat.ravel(), lon.ravel())]).reshape(e.shape)
    if land.min() > 0.5:
        ax.set_facecolor(_LAND)
    elif land.max() >= 0.5:
        ax.contourf(east / scale, north / scale, land, levels=[0.5, 1.5], colors=[_LAND])
        ax.contour(east / scale, north / scale, land, levels=[0.5], colors="0.55", linewidths=0.6)


def landing_map(dispersions: dict, target: dict, out: Path, title: str) -> Path:
    """Draw the landing map of ``dispersions`` (by body) about ``target`` to ``out``: a row
    per body, the scatter about the target (with the circles about it) on the left, zoomed
    on the scatter (with the circles about the mean) on the right."""
    plt = pyplot()
    figure, axes = plt.subplots(len(dispersions), 2, figsize=(19.0, 6.5 * len(dispersions)), squeeze=False)
    for row, (body, d) in zip(axes, dispersions.items()):
        for ax, about in zip(row, ("target", "mean")):
            _landing_panel(ax, body, d, target, about)
    return _finish(figure, axes, axes.size, out,
                   f"{title}: landing dispersion about {target.get('name') or 'the target'}", None)


def _landing_panel(ax, body: str, d, target: dict, about: str) -> None:
    """One panel of :func:`landing_map`: the points, ellipses, mean and target of the
    dispersion ``d`` with its circles about ``about`` (``target`` or ``mean``), framed on
    them (the target too when about it)."""
    circles = [c for c in d.circles if c.about == about]
    shapes = [e.outline() for e in d.ellipses] + [c.outline() for c in circles]
    origin = [0.0] if about == "target" else []
    xs = np.concatenate([d.east_m, origin, *[s[0] for s in shapes]])
    ys = np.concatenate([d.north_m, origin, *[s[1] for s in shapes]])
    half = 0.55 * max(xs.max() - xs.min(), ys.max() - ys.min(), 1.0)
    cx, cy = 0.5 * (xs.max() + xs.min()), 0.5 * (ys.max() + ys.min())
    east_limits, north_limits = (cx - 1.1 * half, cx + 1.1 * half), (cy - half, cy + half)
    scale, unit = (1e3, "km") if 2.0 * half > KM_ABOVE else (1.0, "m")
    _draw_land(ax, target, east_limits, north_limits, scale)
    kinds = np.array(d.kinds)
    for kind, marker, colour in (("touchdown", "o", "C0"), ("impact", "x", "C3")):
        chosen = kinds == kind
        if chosen.any():
            ax.plot(d.east_m[chosen] / scale, d.north_m[chosen] / scale, marker, ms=3, color=colour,
                    ls="none", alpha=0.6, label=f"{kind} ({int(chosen.sum())})")
    other = ~np.isin(kinds, ("touchdown", "impact"))
    if other.any():
        ax.plot(d.east_m[other] / scale, d.north_m[other] / scale, ".", ms=3, color="0.3",
                label=f"came down ({int(other.sum())})")
    for e, style in zip(d.ellipses, _STYLES):
        x, y = e.outline()
        ax.plot(x / scale, y / scale, ls=style, color="C1", lw=1.2, label=f"{100 * e.probability:g} % ellipse (2-D)")
    for c, style in zip(circles, _STYLES):
        x, y = c.outline()
        ax.plot(x / scale, y / scale, ls=style, color="0.35", lw=0.8,
                label=f"R{100 * c.probability:g} about the {about} {c.radius_m / scale:.3g} {unit}")
    ax.plot([0.0], [0.0], "k+", ms=14, mew=2, label=f"target ({target.get('kind') or 'pad'})")
    ax.plot([d.mean[0] / scale], [d.mean[1] / scale], "o", mfc="none", mec="C1", ms=8, label="mean")
    ax.set_xlim(east_limits[0] / scale, east_limits[1] / scale)
    ax.set_ylim(north_limits[0] / scale, north_limits[1] / scale)
    ax.set_aspect("equal")
    ax.grid(True, lw=0.4)
    ax.set_xlabel(f"east of the target, {unit}")
    ax.set_ylabel(f"north of the target, {unit}")
    ax.set_title(f"{body}: {d.n} landings, about the {about}")
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))


HISTOGRAMS = 12                  # panels at most
# per body, by what became of it: the columns worth a histogram, in this order
_CAME_DOWN = ("landing.offset_m", "impact.surface_speed_m_s", "touchdown.vertical_speed_m_s",
              "touchdown.horizontal_speed_m_s", "touchdown.tilt_deg", "flight.apogee_height_agl_m",
              "flight.max_surface_speed_m_s", "flight.max_sensed_acceleration_g")
_IN_ORBIT = ("orbit.periapsis_altitude_m", "orbit.apoapsis_altitude_m", "orbit.inclination_deg",
             "orbit.eccentricity")
_WHAT = {"landing.offset_m": "miss distance from the target", "impact.surface_speed_m_s": "impact speed",
         "touchdown.vertical_speed_m_s": "touchdown vertical speed",
         "touchdown.horizontal_speed_m_s": "touchdown horizontal speed", "touchdown.tilt_deg": "touchdown tilt",
         "flight.apogee_height_agl_m": "apogee above the ground",
         "flight.max_surface_speed_m_s": "largest speed over the ground",
         "flight.max_sensed_acceleration_g": "largest sensed acceleration",
         "orbit.periapsis_altitude_m": "periapsis altitude", "orbit.apoapsis_altitude_m": "apoapsis altitude",
         "orbit.inclination_deg": "inclination", "orbit.eccentricity": "eccentricity"}
_UNITS = (("_m_s2", "m/s²"), ("_m_s", "m/s"), ("_deg", "deg"), ("_m", "m"), ("_g", "g"), ("_s", "s"),
          ("_kg", "kg"), ("_Pa", "Pa"))


def histogram_columns(report) -> list[str]:
    """The outputs of ``report`` worth a histogram, those that vary over its ok runs: the
    campaign's own outputs, then per body that came down in some run (a landing
    column) the figures of its coming down and its flight (:data:`_CAME_DOWN`), per
    body that never came down its orbit (a body on the ground has no orbit worth
    drawing); a column equal in every run to one before it is left out; at most
    :data:`HISTOGRAMS`."""
    flown = report.flown
    varied = {c for c in flown.columns if flown[c].dtype.kind == "f" and flown[c].std() > 0}   # NaN: < 2 runs
    def of_a_body(column: str) -> bool:         # <body>.<section>.<key>: the summary's parts
        parts = column.split(".")
        return len(parts) >= 3 and parts[1] in BODY_SECTIONS
    own = [c for c in report.main if not of_a_body(c)]          # the campaign's own outputs
    bodies = list(dict.fromkeys(c.split(".")[0] for c in flown.columns if of_a_body(c)))
    names = [c for c in own if c in varied]
    for body in bodies:
        down = f"{body}.landing.t_s" in flown and flown[f"{body}.landing.t_s"].notna().any()
        names += [f"{body}.{c}" for c in (_CAME_DOWN if down else _IN_ORBIT) if f"{body}.{c}" in varied]
    drawn: list[str] = []
    for name in dict.fromkeys(names):       # a figure the campaign also asked by its path: once
        values = flown[name].to_numpy(float)
        if not any(np.array_equal(values, flown[d].to_numpy(float), equal_nan=True) for d in drawn):
            drawn.append(name)
    return drawn[:HISTOGRAMS]


def _label(column: str) -> str:
    """What a results column is, as a histogram's title: ``sounding-payload: impact speed, m/s``."""
    body, _, rest = column.partition(".")
    if rest in _WHAT:
        unit = next((u for suffix, u in _UNITS if rest.endswith(suffix)), "")
        return f"{body}: {_WHAT[rest]}" + (f", {unit}" if unit else "")
    return column


def histograms(flown, columns: list[str], out: Path, title: str) -> Path:
    """Draw a histogram of each of ``columns`` of the ok runs' frame ``flown`` to ``out``."""
    plt = pyplot()
    ncols, nrows = _grid(len(columns), 4)
    figure, axes = plt.subplots(nrows, ncols, figsize=(4.2 * ncols, 3.2 * nrows), squeeze=False)
    for ax, column in zip(axes.flat, columns):
        x = flown[column].to_numpy(float)
        x = x[np.isfinite(x)]
        ax.hist(x, bins=int(min(50, max(10, math.sqrt(x.size)))), color="C0", alpha=0.8)
        ax.axvline(x.mean(), color="C3", lw=1.2, label="mean")
        for p, label in ((5, "5-95 %"), (95, None)):
            ax.axvline(np.percentile(x, p), color="C3", lw=0.8, ls="--", label=label)
        ax.set_title(f"{_label(column)} (n {x.size})", fontsize=8)
        ax.tick_params(labelsize=7)
        ax.ticklabel_format(axis="x", useOffset=False, style="plain")
        ax.grid(True, lw=0.4)
    axes.flat[0].legend(fontsize=7)
    return _finish(figure, axes, len(columns), out, f"{title}: outputs of the ok runs",
                   {"left": 0.05, "wspace": 0.25, "hspace": 0.45})


def tornado(table, columns: list[str], out: Path, title: str) -> Path:
    """Draw a tornado of the sensitivities ``table`` (the report's) for each of ``columns``
    that has rows in it, to ``out``."""
    plt = pyplot()
    shown = [c for c in columns if (table["output"] == c).any()]
    ncols, nrows = _grid(len(shown), 3)
    height = max(2.0, 0.35 * table["input"].nunique() + 1.2)
    figure, axes = plt.subplots(nrows, ncols, figsize=(5.2 * ncols, height * nrows), squeeze=False)
    for ax, column in zip(axes.flat, shown):
        rows = table[table["output"] == column]
        rows = rows.assign(order=rows["spearman"].abs().fillna(0.0)).sort_values("order", kind="stable")
        y = np.arange(len(rows))
        ax.barh(y - 0.2, rows["spearman"].fillna(0.0), height=0.38, color="C0", label="Spearman rho")
        ax.barh(y + 0.2, rows["src"].fillna(0.0), height=0.38, color="C1", label="SRC")
        ax.set_yticks(y, rows["input"], fontsize=7)
        ax.axvline(0.0, color="k", lw=0.6)
        ax.set_xlim(-1.05, 1.05)
        r2 = rows["r2"].iloc[0]
        ax.set_title(f"{column}\nlinear fit R^2 {r2:.2f}" if np.isfinite(r2) else column, fontsize=8)
        ax.tick_params(axis="x", labelsize=7)
        ax.grid(True, axis="x", lw=0.4)
    axes.flat[0].legend(fontsize=7, loc="lower right")
    return _finish(figure, axes, len(shown), out, f"{title}: which dispersed input drives each output",
                   {"left": 0.1, "wspace": 0.55, "hspace": 0.6})
