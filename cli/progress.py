"""Progress of a long flight on a terminal: mission time, real-time factor, phase.

Shown only when stderr is a terminal and the flight is long enough to be
worth it; the wall clock it reads is for display only and never reaches the
simulation (runs stay bit-identical).
"""

from __future__ import annotations

import sys
import time
from contextlib import contextmanager

import click

MIN_MISSION_SECONDS = 60.0   # shorter flights finish before a bar is useful


@contextmanager
def flight_progress(duration: float):
    """Yield a callback ``on_progress(t, phase)`` that draws a bar (or None: nothing to draw).

    The bar reads ``T+<mission s>  <factor>x real time  <phase>``, the phase being the
    flight's latest event (``falcon9-block5: MECO``, ``booster: landing burn start``)."""
    if not sys.stderr.isatty() or duration < MIN_MISSION_SECONDS:
        yield None
        return
    start = time.perf_counter()
    shown = [0.0]

    def describe(item):
        if item is None:
            return ""
        t, phase = item
        elapsed = time.perf_counter() - start
        factor = t / elapsed if elapsed > 0 else 0.0
        return f"T+{t:,.0f} s  {factor:,.0f}x real time  {phase}".rstrip()

    with click.progressbar(length=int(duration), label="flying", file=sys.stderr,
                           item_show_func=describe, show_eta=True) as bar:
        def on_progress(t: float, phase: str) -> None:
            step = int(t) - int(shown[0])
            if step > 0:
                bar.update(step, (t, phase))
                shown[0] = t

        yield on_progress
