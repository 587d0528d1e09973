"""Compiled entries: a kernel called without numba's typing of its arguments at every call.

Calling a kernel through numba's dispatcher types every argument on every call;
for a named tuple of arrays (a staged vehicle's ``VehicleArrays``) that takes
longer than a derivative. A caller that calls a kernel every step with
the same objects binds the entry once (:func:`entry_point`) and calls it directly,
or keeps its entries in an :class:`Entries` bound to its arguments. When kernels
run as plain Python (``ROCKETSIM_JIT=python``) an entry is the Python function.
"""

from __future__ import annotations

from ctypes import _CFuncPtr

import numpy as np

from rocketsim.jit import numba_internals


def entry_point(kernel, *args):
    """The compiled entry of ``kernel`` for the numba types of ``args`` (compiled, or
    loaded from the cache, on first need), to call with arguments of those same types.

    Entries are kept by the arguments' kinds (:func:`_kinds`), so a second world
    of the same shapes binds its entries without numba typing its arguments again.
    """
    if kernel.python:
        return kernel.py_func
    kinds = _kinds(args)
    entry = _ENTRIES.get((kernel, kinds)) if kinds is not None else None
    if entry is None:
        entry = kernel.entry(numba_internals.numba_types(kernel, args))
        if kinds is not None:
            _ENTRIES[kernel, kinds] = entry
    return entry


_ENTRIES: dict = {}     # (kernel, the arguments' kinds) -> compiled entry (entry_point)


def _kinds(values) -> tuple | None:
    """Everything numba's type of each of ``values`` depends on, for the values this
    library passes: an array's dtype, dimensions, layout, writeability and alignment;
    a (named) tuple's class and its items' kinds; a numpy scalar's dtype (a
    datetime's unit is in it); a number's, bytes', text's or None's class (an
    integer's, and whether it fits int64); a ctypes function's class (its prototype).
    None where a value is of another sort, to be typed by numba."""
    kinds = []
    for value in values:
        cls = type(value)
        if cls is np.ndarray:
            flags = value.flags
            kinds.append((value.dtype, value.ndim, flags.c_contiguous, flags.f_contiguous,
                          flags.writeable, flags.aligned))
        elif cls is int:
            kinds.append((cls, -2**63 <= value < 2**63))
        elif isinstance(value, np.generic):
            kinds.append(value.dtype)
        elif cls in (float, bool, bytes, str, type(None)):
            kinds.append(cls)
        elif isinstance(value, tuple):
            items = _kinds(value)
            if items is None:
                return None
            kinds.append((cls, items))
        elif isinstance(value, _CFuncPtr):      # a C function pointer: typed by its prototype
            kinds.append(cls)
        else:
            return None
    return tuple(kinds)


class Entries:
    """Compiled entries bound to one owner's arguments (see :func:`entry_point`).

    ``call(kernel, key, *args)`` returns ``kernel(*args)``; the entry is bound on
    the first call and again whenever ``key`` (the argument whose type is
    costly to work out, e.g. a vehicle's arrays, replaced at staging) is a new
    object. The other arguments keep their kinds from call to call (numbers as
    numbers, float64 arrays, a type-level switch such as the step's ``nbody``
    None or not, as the owner's parameters say: a body keeps its n-body field
    from start to end, a handover re-centres it). An array that is not
    C-contiguous goes through the dispatcher instead.
    """

    def __init__(self):
        self._bound = {}

    def call(self, kernel, key, *args):
        for a in args:
            if type(a) is np.ndarray and not a.flags.c_contiguous:
                return kernel(*args)
        bound = self._bound.get(kernel)
        if bound is None or bound[0] is not key:
            bound = self._bound[kernel] = (key, entry_point(kernel, *args))
        return bound[1](*args)
