"""One body's state samples as numbers in columns, from a flight in memory or a file.

A sample is the body's state message (:data:`rocketsim.telemetry.schemas.BODY_STATE`)
flattened as the CSV export flattens it (:func:`rocketsim.telemetry.tables.flat_row`:
``position_x``, ``orbit_eccentricity``, ``propellant_tanks_booster_LOX``...). Runs of
samples with the same columns (a segment: until a staging changes the engines, or a
handover the central body) are kept as blocks of float64 rows, 8 bytes a number:
the 311-day Mars mission's samples take a few megabytes. A flight in memory adds
the array of numbers the world computed for its telemetry
(:func:`rocketsim.sim.sampling.values`: its columns worked out once per message
shape, from the same template the MCAP writer splices); a file adds its decoded
messages. Both give the same :meth:`Samples.columns`: what JSON cannot hold (NaN,
infinities) is NaN, counts are integers, the central body a string, every other
number the float64 the flight computed, bit for bit.
"""

from __future__ import annotations

import numpy as np

from rocketsim.telemetry.tables import flat_row

BLOCK = 1024            # rows of a block: a block is allocated whole
FLOAT, INTEGER, TEXT = "f", "i", "c"


class _Segment:
    """Samples with one layout: ``layout`` lists ``(column, kind, index or text)``;
    ``vectors``: the columns that are a vector's components (a vector keeps its
    columns when missing: a file writes null in a vector, and leaves out any other
    value it does not have)."""

    def __init__(self, key, layout: tuple, width: int, vectors: set):
        self.key = key
        self.layout = layout
        self.vectors = frozenset(vectors)
        self.width = width
        self.blocks: list[np.ndarray] = []
        self.rows = 0

    def add(self, numbers) -> None:
        at = self.rows % BLOCK
        if at == 0:
            self.blocks.append(np.empty((BLOCK, self.width)))
        self.blocks[-1][at] = numbers
        self.rows += 1

    def add_rows(self, rows: np.ndarray) -> None:
        """:meth:`add` of each row of ``rows``, in order."""
        done = 0
        while done < len(rows):
            at = self.rows % BLOCK
            if at == 0:
                self.blocks.append(np.empty((BLOCK, self.width)))
            n = min(BLOCK - at, len(rows) - done)
            self.blocks[-1][at:at + n] = rows[done:done + n]
            self.rows += n
            done += n

    def array(self) -> np.ndarray:
        if not self.blocks:
            return np.empty((0, self.width))
        whole = np.concatenate(self.blocks) if len(self.blocks) > 1 else self.blocks[0]
        return whole[:self.rows]

    @property
    def nbytes(self) -> int:
        return sum(b.nbytes for b in self.blocks)


class Samples:
    """The state samples of one body, in segments of one layout each."""

    def __init__(self):
        self.segments: list[_Segment] = []

    def __len__(self) -> int:
        return sum(s.rows for s in self.segments)

    @property
    def nbytes(self) -> int:
        """Bytes the blocks of numbers take."""
        return sum(s.nbytes for s in self.segments)

    def add_rows(self, rows: np.ndarray, fields) -> None:
        """Samples of the flight, a row each, in order: ``fields(row, integer)`` is a row's
        state message (:func:`rocketsim.sim.sampling.values`)."""
        segment = self.segments[-1] if self.segments else None
        if segment is None or segment.key[0] is not fields or segment.key[1] != rows.shape[1]:
            segment = self._segment_of(fields, rows.shape[1])
        segment.add_rows(rows)

    def _segment_of(self, fields, n: int) -> _Segment:
        from rocketsim.telemetry import splice     # with the flight: it compiles kernels
        vectors = set()
        row = flat_row(fields(splice.slots(n), splice.Slot.integer), vectors)
        layout = tuple((column, TEXT, value) if not isinstance(value, splice.Slot)
                       else (column, INTEGER if value.kind == "i" else FLOAT, value.index)
                       for column, value in row.items())
        segment = _Segment((fields, n), layout, n, vectors)
        self.segments.append(segment)
        return segment

    def add_message(self, message: dict) -> None:
        """A state message as a file holds it (decoded JSON)."""
        row = flat_row(message)
        key = tuple((column, TEXT, value) if isinstance(value, str)
                    else (column, INTEGER if type(value) is int else FLOAT)
                    for column, value in row.items())
        segment = self.segments[-1] if self.segments else None
        if segment is None or segment.key != key:
            numeric = [k for k in key if k[1] != TEXT]
            layout = tuple(k if k[1] == TEXT else (k[0], k[1], numeric.index(k)) for k in key)
            vectors = set()
            flat_row(message, vectors)
            segment = _Segment(key, layout, len(numeric), vectors)
            self.segments.append(segment)
        segment.add([np.nan if v is None else v for v in row.values() if not isinstance(v, str)])

    def columns(self) -> dict[str, np.ndarray]:
        """Every column over all samples, in the order the columns first appear: a
        column a segment lacks is NaN there (None for text)."""
        order: dict[str, str] = {}
        vectors = set().union(*(segment.vectors for segment in self.segments))
        for segment in self.segments:
            for column, kind, _ in segment.layout:
                order.setdefault(column, kind)
        n = len(self)
        arrays = [segment.array() for segment in self.segments]
        out, first = {}, {}
        for column, kind in order.items():
            values = np.full(n, None, dtype=object) if kind == TEXT else np.full(n, np.nan)
            at = 0
            for segment, numbers in zip(self.segments, arrays):
                found = next((entry for entry in segment.layout if entry[0] == column), None)
                if found is not None:
                    if kind == TEXT:
                        values[at:at + segment.rows] = found[2]
                    else:
                        values[at:at + segment.rows] = numbers[:, found[2]]
                at += segment.rows
            if kind != TEXT:
                values[~np.isfinite(values)] = np.nan        # JSON's null: NaN and infinities alike
                if np.isnan(values).all() and column not in vectors:
                    continue        # a value no sample has is left out of every message: no column
                if column not in vectors:
                    first[column] = int(np.argmax(~np.isnan(values)))
                if kind == INTEGER and not np.isnan(values).any():
                    values = values.astype(np.int64)
            out[column] = values
        # a file's table adds a column at the first message that has the value
        rank = {column: i for i, column in enumerate(out)}
        return {column: out[column] for column in sorted(out, key=lambda c: (first.get(c, 0), rank[c]))}
