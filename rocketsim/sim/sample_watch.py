"""What the world reads of its own telemetry samples on their way out: each body's flight
figures, and the thinning of long coasts.

:class:`SampleWatch` stands between the world and its telemetry (a
:class:`~rocketsim.telemetry.sink.TelemetrySink`: an MCAP writer, or the samples kept
in memory), a sink itself: every sample passes through it, as one sample, a block of
one body's samples or interleaved blocks (the numbers of
:func:`rocketsim.stepping.sample_figures.figures`), and it hands them on, and every
other call unchanged, to the telemetry.

**Flight figures** (:meth:`SampleWatch.figures`), over a body's samples in flight:
from its first sample to its first ``touchdown`` or ``impact`` (the landing's own
sample and those after it left out: a touchdown's contact spike is not a load of the
flight): the highest ``height_agl`` and its time, the largest ``surface_speed``, Mach
and dynamic pressure in the air (where the dynamic pressure is at least :data:`IN_AIR_Q`:
none for a body that never met the air, or one the air does not act on, whose samples
have no dynamic pressure) and sensed acceleration (in standard gravities), and where the
body was at its first sample. They
are the samples' figures, at the telemetry rate: a peak between two samples is missed by
at most what the quantity changes in half a sample interval (the apogee, where the climb
rate is nought, by millimetres). A body split from another (a stage, a fairing half, the
payload) starts with its parent's figures (:meth:`SampleWatch.inherit`): it flew the
ascent with it, so a booster's largest q and load are those of the ascent it flew, and
its drift is from the pad.

**Coasts thinned** (the scenario's ``telemetry.coast_rate``): while a body coasts --
no engine running (a rigid body has none) and out of the air (a dynamic pressure
under :data:`IN_AIR_Q`, or none) -- its samples at the telemetry rate are written only at the multiples
of the coast interval (``round(1 / (coast_rate h))`` steps); its samples between the
sample steps (at a handover, a staging, a landing) are all written, and so is its
last sample of the flight. The rule reads the sample's own numbers and its step
number alone: the same inputs write the same samples, bit for bit.
"""

from __future__ import annotations

import copy
import math

import numpy as np

from rocketsim.constants import G0
from rocketsim.stepping.sample_figures import (N_SAMPLE_RIGID, SAMPLE_DYNAMIC_PRESSURE, SAMPLE_ENGINES_RUNNING,
                                               SAMPLE_HEIGHT, SAMPLE_HEIGHT_AGL, SAMPLE_LAT, SAMPLE_LON, SAMPLE_MACH,
                                               SAMPLE_SENSED, SAMPLE_SURFACE_SPEED)
from rocketsim.telemetry.sink import TelemetrySink

IN_AIR_Q = 1.0           # Pa: from it a body is in the air (below it one without engines running coasts)
LANDINGS = ("touchdown", "impact")


class _Figures:
    """One body's flight figures so far (see the module). The samples are taken in as they
    come and their figures worked out together, :data:`SETTLE_BLOCKS` blocks at a time or
    when asked (:meth:`settle`): the same figures as block by block, in their order."""

    def __init__(self, row: np.ndarray):
        self.start = (float(row[SAMPLE_LAT]), float(row[SAMPLE_LON]), float(row[SAMPLE_HEIGHT]))
        self.ground = float(row[SAMPLE_HEIGHT] - row[SAMPLE_HEIGHT_AGL])
        self.apogee = (-math.inf, math.nan)          # (height above the ground m, t s)
        self.peaks = np.full(4, -math.inf)            # surface speed, Mach, q, sensed acceleration
        self.landed = math.inf                        # s: the first landing's time
        self._blocks: list[np.ndarray] = []           # samples taken in, their figures not yet worked out

    def add(self, rows: np.ndarray) -> None:
        if self.landed != math.inf:
            rows = rows[rows[:, -2] < self.landed]
            if not len(rows):
                return
        self._blocks.append(rows)
        if len(self._blocks) >= SETTLE_BLOCKS:
            self.settle()

    def settle(self) -> None:
        """Work out the figures of the samples taken in: the highest height of each block
        (NaN where it has one) and the first block that reaches the highest of them, as
        one block after the other would."""
        blocks, self._blocks = self._blocks, []
        if not blocks:
            return
        counts = np.array([len(rows) for rows in blocks], dtype=np.int64)
        rows = np.concatenate([_figure_columns(run) for run in _same_width(blocks)])
        heights = rows[:, 1]
        first = np.cumsum(counts) - counts
        tops = np.maximum.reduceat(heights, first)          # NaN for a block holding one
        reached = tops[~np.isnan(tops)]
        if len(reached) and reached.max() > self.apogee[0]:
            b = int(np.flatnonzero(tops == reached.max())[0])
            top = first[b] + int(np.argmax(heights[first[b]:first[b] + counts[b]]))
            self.apogee = (float(heights[top]), float(rows[top, 0]))
        figures = rows[:, 2:]
        figures[~(rows[:, 4] >= IN_AIR_Q), 1:3] = np.nan      # Mach and q in the air
        np.fmax(self.peaks, np.fmax.reduce(figures, axis=0, initial=-math.inf), out=self.peaks)

    def summary(self) -> dict:
        self.settle()
        speed, mach, q, sensed = (float(x) if math.isfinite(x) else math.nan for x in self.peaks)
        return {"apogee_height_agl_m": self.apogee[0] if math.isfinite(self.apogee[0]) else math.nan,
                "apogee_time_s": self.apogee[1], "ground_height_m": self.ground,
                "max_surface_speed_m_s": speed, "max_mach": mach, "max_dynamic_pressure_Pa": q,
                "max_sensed_acceleration_g": sensed / G0,
                "start_latitude_deg": self.start[0], "start_longitude_deg": self.start[1]}


SETTLE_BLOCKS = 64      # blocks of samples a body's figures take in before working them out
FIGURE_COLUMNS = [SAMPLE_HEIGHT_AGL, SAMPLE_SURFACE_SPEED, SAMPLE_MACH, SAMPLE_DYNAMIC_PRESSURE, SAMPLE_SENSED]


def _same_width(blocks: list[np.ndarray]) -> list[np.ndarray]:
    """``blocks`` (rows of samples), those that follow one another with the same number of
    values joined into one."""
    runs, start = [], 0
    for k in range(1, len(blocks) + 1):
        if k == len(blocks) or blocks[k].shape[1] != blocks[start].shape[1]:
            runs.append(blocks[start] if k - start == 1 else np.concatenate(blocks[start:k]))
            start = k
    return runs


def _figure_columns(rows: np.ndarray) -> np.ndarray:
    """The columns of samples ``rows`` the figures read: t, height above the ground, surface
    speed, Mach, dynamic pressure, sensed acceleration."""
    found = np.empty((len(rows), 6))
    found[:, 0] = rows[:, -2]
    found[:, 1:] = rows[:, FIGURE_COLUMNS]
    return found


class SampleWatch(TelemetrySink):
    """The world's telemetry ``telemetry``, its samples watched (see the module).

    ``h``: the step (s); ``every``: steps between samples; ``coast_every``: steps between
    a coasting body's samples (None: coasts are not thinned)."""

    def __init__(self, telemetry, h: float, every: int, coast_every: int | None = None):
        self.telemetry = telemetry
        self.h, self.every, self.coast_every = h, every, coast_every
        self._figures: dict[str, _Figures] = {}
        self._held: dict[str, tuple] = {}       # body -> its last sample not written (thinned)

    def figures(self, body: str) -> dict | None:
        """The flight figures of ``body`` (see the module; None: no sample of it)."""
        found = self._figures.get(body)
        return None if found is None else found.summary()

    def inherit(self, body: str, parent: str) -> None:
        """``body``, split from ``parent`` now (before its first sample), starts with the
        flight figures ``parent`` has so far."""
        found = self._figures.get(parent)
        if found is not None:
            found.settle()
            self._figures[body] = copy.deepcopy(found)

    # --- the samples --------------------------------------------------------------
    def _watch(self, body: str, rows: np.ndarray) -> None:
        found = self._figures.get(body)
        if found is None:
            found = self._figures[body] = _Figures(rows[0])
        found.add(rows)

    def _kept(self, rows: np.ndarray) -> list[bool]:
        """Which of one body's samples ``rows`` the coast rule writes (see the module): in
        Python's arithmetic, a row at a time (blocks are a few samples long; the step is
        rounded half to even, as numpy's ``rint``)."""
        h, every, coast_every = self.h, self.every, self.coast_every
        air = rows[:, SAMPLE_DYNAMIC_PRESSURE].tolist()
        engines = rows[:, SAMPLE_ENGINES_RUNNING].tolist() if rows.shape[1] > N_SAMPLE_RIGID else [0.0] * len(air)
        kept = []
        for t, q, running in zip(rows[:, -2].tolist(), air, engines):
            step = round(t / h)
            coasting = not q >= IN_AIR_Q and running == 0.0      # no air figures: out of the air
            kept.append(not coasting or step % every != 0 or step % coast_every == 0)
        return kept

    def sample(self, body: str, values: np.ndarray, fields, leaving: bool = False) -> None:
        self._watch(body, values.reshape(1, -1))
        if self.coast_every is not None:
            if not self._kept(values.reshape(1, -1))[0]:
                self._held[body] = (values.copy(), fields, leaving)
                return
            self._held.pop(body, None)
        self.telemetry.sample(body, values, fields, leaving=leaving)

    def sample_rows(self, body: str, rows: np.ndarray, fields) -> None:
        if not len(rows):
            return
        self._watch(body, rows)
        if self.coast_every is None:
            self.telemetry.sample_rows(body, rows, fields)
            return
        kept = self._kept(rows)
        if not kept[-1]:
            self._held[body] = (rows[-1].copy(), fields, False)
        elif body in self._held:
            del self._held[body]
        if all(kept):
            self.telemetry.sample_rows(body, rows, fields)
        elif any(kept):
            self.telemetry.sample_rows(body, rows[np.array(kept)], fields)

    def sample_interleaved(self, blocks: list[tuple]) -> None:
        """The samples of interleaved ``blocks`` the coast rule keeps, handed on as
        interleaved blocks (each stretch of a block's kept samples one: written in the
        same order, by step and then rank), each body's last sample held back if the rule
        did not keep it."""
        for body, rows, *_ in blocks:
            if len(rows):
                self._watch(body, rows)
        if self.coast_every is None:
            self.telemetry.sample_interleaved(blocks)
            return
        written, last = [], {}          # last: body -> (its last step, its last sample, fields, kept)
        for body, rows, fields, first, every, rank in blocks:
            if not len(rows):
                continue
            kept = self._kept(rows)
            end = first + every * (len(rows) - 1)
            if body not in last or end > last[body][0]:
                last[body] = (end, rows[-1], fields, kept[-1])
            start = None            # the first kept sample of a stretch
            for j, keep in enumerate(kept + [False]):
                if keep and start is None:
                    start = j
                elif not keep and start is not None:
                    written.append((body, rows[start:j], fields, first + every * start, every, rank))
                    start = None
        for body, (_, values, fields, kept) in last.items():
            if kept:
                self._held.pop(body, None)
            else:
                self._held[body] = (values.copy(), fields, False)
        if written:
            self.telemetry.sample_interleaved(written)

    def event(self, t: float, body: str, name: str, figures: dict) -> None:
        found = self._figures.get(body)
        if name in LANDINGS and found is not None:
            found.landed = min(found.landed, t)
        self.telemetry.event(t, body, name, figures)

    # --- the other calls, handed on -----------------------------------------------------
    def add_body(self, name: str) -> None:
        self.telemetry.add_body(name)

    def log(self, t: float, body: str, message: str) -> None:
        self.telemetry.log(t, body, message)

    def error(self, t: float, message: str) -> None:
        self.telemetry.error(t, message)

    def attach(self, name: str, data: bytes, media_type: str = "text/plain") -> None:
        self.telemetry.attach(name, data, media_type)

    def metadata(self, name: str, values: dict[str, str]) -> None:
        self.telemetry.metadata(name, values)

    def close(self) -> None:
        self.telemetry.close()

    def __enter__(self) -> "SampleWatch":
        return self

    def __exit__(self, exc_type, exc, traceback) -> None:
        self.telemetry.__exit__(exc_type, exc, traceback)

    def finish(self) -> None:
        """Write each body's last sample if the coast rule held it back."""
        for body, (values, fields, leaving) in self._held.items():
            self.telemetry.sample(body, values, fields, leaving=leaving)
        self._held.clear()
