"""The VSOP87D and ELP2000-82B series laid out for their kernels.

A series as the files give it (terms of coordinates and powers, or of
coordinates and Delaunay multipliers) is reordered once for evaluation:
terms grouped by what the kernel sums together, each distinct frequency (or
multiplier row) listed once, and a plan to get most of their sines and
cosines from two others by angle addition (:func:`rocketsim.ephemeris.sincos.sum_recipe`).
The plan is the costly part (a search among the pairs of every phase, in
Python), so the generator
(``generate.py``) writes the truncated series' plans into ``_tables.py`` beside
the series, and a process lays them out at import with those; the
tests and the benchmark lay out the full series here to measure the truncation.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from rocketsim.ephemeris.sincos import sum_recipe

MAX_POWER = 5                       # VSOP87 series run to t^5
GROUPS = 3 * (MAX_POWER + 1)        # (coordinate, power) pairs
# Two frequencies whose sum matches a third within this (rad per millennium;
# the files give C to 1e-10) build its sine and cosine: the phase error is
# below 1e-9 rad over the span.
FREQUENCY_TOLERANCE = 1e-8


class VsopLayout(NamedTuple):
    """A VSOP87D series laid out for the kernel (see :mod:`rocketsim.ephemeris.vsop87`).

    Terms are sorted by group ``g = 6 * coord + power``; ``start[g]:start[g+1]``
    are the terms of group ``g``; ``term_freq`` indexes ``freq``.
    """

    freq: np.ndarray        # distinct frequencies C, rad per millennium
    start: np.ndarray       # (GROUPS + 1,) group boundaries
    term_freq: np.ndarray   # frequency index of each term
    P: np.ndarray           # A cos B
    Q: np.ndarray           # A sin B
    C: np.ndarray           # frequency of each term
    direct: np.ndarray      # frequencies whose sin/cos are computed ...
    derived: np.ndarray     # ... and those built as the sum of two others
    pair_a: np.ndarray      # (``sincos.sum_recipe``)
    pair_b: np.ndarray


def prepare_vsop(coord, power, A, B, C, recipe: tuple | None = None) -> VsopLayout:
    """Lay out a flat VSOP87D series (``generate.VsopSeries`` fields); ``recipe``: its
    frequencies' :func:`~rocketsim.ephemeris.sincos.sum_recipe` if known (the generator's)."""
    group = np.asarray(coord) * (MAX_POWER + 1) + np.asarray(power)
    order = np.argsort(group, kind="stable")
    freq, term_freq = np.unique(np.asarray(C)[order], return_inverse=True)
    start = np.searchsorted(group[order], np.arange(GROUPS + 1))
    a = np.asarray(A)[order]
    b = np.asarray(B)[order]
    return VsopLayout(freq, start.astype(np.int64), term_freq.astype(np.int64),
                      a * np.cos(b), a * np.sin(b), np.asarray(C)[order].astype(np.float64),
                      *(sum_recipe(freq, FREQUENCY_TOLERANCE) if recipe is None else recipe))


class ElpLayout(NamedTuple):
    """An ELP2000-82B main-problem series laid out for the kernel.

    The distinct argument multipliers (rows of ``i1..i4``) are evaluated once
    each (longitude and distance share most of them); terms are sorted by
    coordinate, ``start[c]:start[c+1]`` are the terms of coordinate ``c``.
    """

    mult: np.ndarray        # (4, U) distinct multipliers of D, l', l, F, as floats
    start: np.ndarray       # (4,) coordinate boundaries
    term_row: np.ndarray    # row of ``mult`` of each term
    A: np.ndarray           # amplitude (arcsec, arcsec, km)
    direct: np.ndarray      # rows whose sin/cos are computed ...
    derived: np.ndarray     # ... and those built as the sum of two others
    pair_a: np.ndarray      # (``sincos.sum_recipe``)
    pair_b: np.ndarray


def prepare_elp(coord, mult, A, recipe: tuple | None = None) -> ElpLayout:
    """Lay out a flat ELP series (``generate.ElpSeries`` fields); ``recipe``: its rows'
    :func:`~rocketsim.ephemeris.sincos.sum_recipe` if known (the generator's)."""
    order = np.argsort(np.asarray(coord), kind="stable")
    rows, term_row = np.unique(np.asarray(mult)[order], axis=0, return_inverse=True)
    start = np.searchsorted(np.asarray(coord)[order], np.arange(4))
    # a row is the sum of two others when its key is: key = sum i_j 100^j is
    # exact and one-to-one for |i_j| < 50; visit the rows shortest first
    if recipe is None:
        keys = rows @ (100.0 ** np.arange(4))
        recipe = sum_recipe(keys, 0.5, np.argsort(np.abs(rows).sum(axis=1), kind="stable"))
    return ElpLayout(np.ascontiguousarray(rows.T, dtype=np.float64), start.astype(np.int64),
                     term_row.ravel().astype(np.int64),
                     np.asarray(A, dtype=np.float64)[order], *recipe)
