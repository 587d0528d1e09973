"""The porkchop plot of a launch-window search: contours of C3 (km²/s², red, solid at any
sign: a lunar C3 is negative) and of the arrival v-infinity (km/s, blue dashed) over
departure x arrival dates (UTC), the windows found starred and numbered best first; a
window on a bound of the search (its ``edge``) hollow and marked "edge"."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from rocketsim.plots.canvas import Picture, pyplot, save


def porkchop(found, out: str | Path | None = None) -> Path | Picture:
    """Draw ``found`` (the :class:`~rocketsim.api.window_search.LaunchWindows` of a search)
    to the PNG ``out`` and return its path, or without ``out`` return the picture."""
    plt = pyplot()
    import matplotlib.dates as mdates

    grid, utc = found.search.grid, found.grid.clock.utc
    departures = [utc(jd) for jd in grid.departure_jd[:, 0]]
    arrivals = [utc(jd) for jd in grid.arrival_jd[0, :]]
    x = mdates.date2num(departures)
    y = mdates.date2num(arrivals)
    c3 = grid.c3.T / 1e6
    vinf = grid.vinf_arrival.T / 1e3
    fig, ax = plt.subplots(figsize=(10, 8))
    if np.isfinite(c3).any():
        low = float(np.nanmin(c3))
        span = max(1.0, abs(low))
        c3_levels = low + span * np.array([0.02, 0.1, 0.3, 1.0, 3.0])
        lines = ax.contour(x, y, c3, levels=c3_levels, colors="tab:red", linewidths=1.0,
                           negative_linestyles="solid")
        ax.clabel(lines, fmt="%.1f", fontsize=8)
        low_v = float(np.nanmin(vinf))
        v_levels = low_v + np.array([0.1, 0.5, 1.5])
        lines = ax.contour(x, y, vinf, levels=v_levels, colors="tab:blue", linewidths=0.8,
                           linestyles="dashed")
        ax.clabel(lines, fmt="%.1f", fontsize=8)
    for k, window in enumerate(found.windows, 1):
        at = (mdates.date2num(utc(window.departure_jd_tt)), mdates.date2num(utc(window.arrival_jd_tt)))
        ax.plot(*at, "*", markersize=12, color="k", mfc="none" if window.edge else "k", clip_on=False)
        ax.annotate(f"{k} (edge)" if window.edge else str(k), at, textcoords="offset points",
                    xytext=(-8, 8), ha="right", fontweight="bold",
                    bbox={"boxstyle": "round,pad=0.2", "fc": "white", "ec": "none", "alpha": 0.8})
    ax.xaxis_date()
    ax.yaxis_date()
    ax.xaxis.set_major_formatter(mdates.DateFormatter("%Y-%m-%d"))
    ax.yaxis.set_major_formatter(mdates.DateFormatter("%Y-%m-%d"))
    fig.autofmt_xdate()
    ax.set_xlabel("departure (UTC)")
    ax.set_ylabel("arrival (UTC)")
    ax.set_title(f"Earth to {found.search.target.name.capitalize()}: C3 (km²/s², red) and arrival v∞ "
                 "(km/s, blue dashed); ★ windows, best first")
    ax.grid(alpha=0.3)
    return save(fig, out, dpi=120)
