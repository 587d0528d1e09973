"""The events of a run on its picture (:mod:`rocketsim.plots.flight_panels`): numbered in
time order along the top of a panel, events too close to be told apart sharing a label
(``3-5``) so that no two labels overlap, and every one of them listed under the panels in as
many columns as the page's width holds."""

from __future__ import annotations

import math

LIST_CHARACTERS = 210        # characters of the events' list (7.5 pt monospace) across the page


def event_labels(figure, ax, events, clock) -> None:
    """Number the events along the top of ``ax`` in time order; events whose numbers
    would touch share a label (``3-5``), so that no two labels overlap."""
    renderer = figure.canvas.get_renderer()
    groups: list[list[int]] = []
    placed = []                 # (label, its right edge in pixels)
    for k, event in enumerate(events, 1):
        x = clock(event["t"])
        if groups:
            label, right = placed[-1]
            start = ax.get_xaxis_transform().transform((x, 1.0))[0]    # any y scale (log: no 0)
            if start - right < 4.0:          # touches the label before: join its group
                groups[-1].append(k)
                label.set_text(_range(groups[-1]))
                placed[-1] = (label, label.get_window_extent(renderer).x1)
                continue
        groups.append([k])
        label = ax.annotate(str(k), (x, 1.0), xycoords=("data", "axes fraction"), xytext=(0, -2),
                            textcoords="offset points", ha="left", va="top", fontsize=7, color="0.25",
                            bbox={"boxstyle": "square,pad=0.1", "fc": "white", "ec": "none", "alpha": 0.85})
        placed.append((label, label.get_window_extent(renderer).x1))


def _range(numbers: list[int]) -> str:
    return str(numbers[0]) if len(numbers) == 1 else f"{numbers[0]}-{numbers[-1]}"


def event_lines(events, clock, problem) -> list[str]:
    lines = [f"{k:>3}  {clock.text(e['t'])}  {e['body']}: {e['name']}" for k, e in enumerate(events, 1)]
    return lines + (["     file damaged: partial data"] if problem else [])


def list_columns(lines: list[str]) -> int:
    """How many columns of the events' list fit the page's width (:data:`LIST_CHARACTERS`
    characters of the list's monospace type across), at most four."""
    return max(1, min(4, LIST_CHARACTERS // (max(map(len, lines), default=1) + 3)))


def event_list(ax, events, clock, problem) -> None:
    """Every event, numbered as on the height panel, whole, in columns under the panels."""
    ax.axis("off")
    lines = event_lines(events, clock, problem)
    ncols = list_columns(lines)
    per_column = math.ceil(len(lines) / ncols)
    for j in range(ncols):
        ax.text(j / ncols, 1.0, "\n".join(lines[j * per_column:(j + 1) * per_column]), transform=ax.transAxes,
                va="top", ha="left", family="monospace", fontsize=7.5)
