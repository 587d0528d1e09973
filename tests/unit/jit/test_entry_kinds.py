"""Compiled entries kept by their arguments' kinds: values of one kind are values
numba types alike (numba's own ``typeof`` is the reference), so an entry bound for
one world's arguments is the right entry for another's."""

from collections import namedtuple
from itertools import combinations

import numpy as np
from numba import typeof

from rocketsim.jit.entries import _kinds, entry_point
from rocketsim.dynamics.rk4 import advance

Pair = namedtuple("Pair", "a b")
Other = namedtuple("Other", "a b")


def _values():
    base = np.arange(12.0).reshape(3, 4)
    frozen = np.zeros(3)
    frozen.flags.writeable = False
    return [
        np.zeros(3), np.zeros(5), np.zeros(3, dtype=np.int64), np.zeros(3, dtype=np.float32),
        base, base.T, base[:, ::2], base[0], base[:, 0], frozen, np.zeros((0, 4)),
        1, -7, 2**63, -2**63, 2**62, 1.5, -0.0, True, None, b"", b"abc", "text",
        np.float64(1.0), np.int32(3), np.datetime64("2026-12-03", "D"),
        np.datetime64("2026-12-03", "s"), (), (1.0, 2.0), (1.0, 2), (np.zeros(2), 3),
        Pair(np.zeros(2), 1.0), Pair(np.zeros(2), 2.0), Pair(np.zeros(2, dtype=np.int64), 1.0),
        Other(np.zeros(2), 1.0), Pair(base.T, 1.0), ((1.0,), (np.zeros(1),)),
    ]


def test_values_of_one_kind_are_typed_alike_by_numba():
    values = _values()
    kinds = [_kinds((v,)) for v in values]
    assert all(k is not None for k in kinds)
    types = [typeof(v) for v in values]
    for i, j in combinations(range(len(values)), 2):
        if kinds[i] == kinds[j]:
            assert types[i] == types[j], (values[i], values[j])


def test_an_entry_is_reused_for_arguments_of_its_kind_only():
    y, p = np.zeros(13), np.zeros(40)
    first = entry_point(advance, y, 0, 0.1, 1, p, None, None)
    assert entry_point(advance, np.ones(13), 5, 0.2, 3, np.ones(40), None, None) is first
    frozen = y.copy()
    frozen.flags.writeable = False      # numba types it apart: an entry of its own
    assert typeof(frozen) != typeof(y) and _kinds((frozen,)) != _kinds((y,))
