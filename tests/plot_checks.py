"""What a drawn figure must hold: labels that do not overlap, read from the figure's own
artists after a draw."""

from __future__ import annotations

import itertools


def _tick_labels(figure) -> tuple[set, list]:
    """``(every tick label, those drawn)``: a tick label is drawn when its tick lies in its
    axis's view (matplotlib keeps the labels of the ticks outside it, not drawn)."""
    every, drawn = set(), []
    for ax in figure.axes:
        for axis in (ax.xaxis, ax.yaxis):
            low, high = sorted(axis.get_view_interval())
            span = (high - low) * 1e-9
            for tick in axis.get_major_ticks() + axis.get_minor_ticks():
                labels = (tick.label1, tick.label2)
                every.update(labels)
                if low - span <= tick.get_loc() <= high + span:
                    drawn += [label for label in labels if label.get_visible()]
    return every, drawn


def text_boxes(figure) -> list[tuple[str, object]]:
    """``(text, window extent)`` of every drawn, non-empty text of ``figure`` after a draw:
    titles, axis and tick labels, legends, annotations, the events' list."""
    from matplotlib.text import Text
    figure.canvas.draw()
    renderer = figure.canvas.get_renderer()
    ticks, drawn = _tick_labels(figure)
    texts = [t for t in figure.findobj(Text) if t not in ticks and t.get_visible()] + drawn
    return [(t.get_text(), t.get_window_extent(renderer)) for t in texts if t.get_text().strip()]


def overlapping_labels(figure, slack: float = 0.5) -> list[tuple[str, str]]:
    """The pairs of texts of ``figure`` whose boxes overlap by more than ``slack`` pixels
    both ways (boxes that only touch are apart)."""
    pairs = []
    for (a, p), (b, q) in itertools.combinations(text_boxes(figure), 2):
        if min(p.x1, q.x1) - max(p.x0, q.x0) > slack and min(p.y1, q.y1) - max(p.y0, q.y0) > slack:
            pairs.append((a, b))
    return pairs


def assert_the_plot_reads(run, name: str) -> list[str]:
    """The replay plot of ``run`` (a :class:`rocketsim.api.run.Run` or an MCAP file) drawn
    without a warning, with no two labels overlapping and every event listed by its number
    and name; with ``ROCKETSIM_TEST_PLOTS`` set, written there as ``<name>.png`` to be
    looked at. Returns the titles of its panels."""
    import os
    import warnings
    from pathlib import Path

    from rocketsim.plots import flight_panels
    from rocketsim.plots.canvas import pyplot
    from rocketsim.telemetry.reader import read_run

    events = (read_run(run) if isinstance(run, (str, Path)) else run.file).events
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        figure = flight_panels.figure(run)
        try:
            overlaps = overlapping_labels(figure)
            titles = [ax.get_title() for ax in figure.axes if ax.get_title()]
            texts = "\n".join(text for text, _ in text_boxes(figure))
            folder = os.environ.get("ROCKETSIM_TEST_PLOTS")
            if folder:
                figure.savefig(Path(folder) / f"{name}.png", dpi=80)
        finally:
            pyplot().close(figure)
    assert not overlaps, overlaps
    assert not caught, [str(w.message) for w in caught]
    for k, event in enumerate(events, 1):
        assert f"{k:>3}  T+" in texts and f"{event['body']}: {event['name']}"[:40] in texts, (k, event["name"])
    return titles
