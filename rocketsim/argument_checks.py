"""The checks of a call's arguments at the library's doors: a wrong type or value is an
:class:`~rocketsim.errors.ArgumentError` naming the argument (as the call wrote it; the
command line shows its option), never a TypeError from deep inside. The front door
(:mod:`rocketsim.api`, :mod:`rocketsim.campaigns`) and the calls it hands its arguments
to (a design review, a table export) check with these. A time given as the files write
it (``"10 s"``) is read by :func:`rocketsim.scenario.models.time_argument`."""

from __future__ import annotations

import numbers
import os

from rocketsim.errors import ArgumentError


def expect(value, types: tuple, name: str, expected: str) -> None:
    """Refuse ``value`` unless an instance of ``types``, naming the argument ``name``."""
    if not isinstance(value, types):
        raise ArgumentError(f"expected {expected}, got {type(value).__name__} {value!r:.60}", name)


def whole(value, name: str, low: int | None = None, optional: bool = True) -> int | None:
    """``value`` as a whole number (an int or a numpy integer, not a bool) of at least
    ``low``; None passes when ``optional``."""
    if value is None and optional:
        return None
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise ArgumentError(f"expected a whole number, got {type(value).__name__} {value!r:.60}", name)
    if low is not None and value < low:
        raise ArgumentError(f"expected a whole number of at least {low}, got {value}", name)
    return int(value)


def switch(value, name: str) -> bool:
    """``value`` as True or False (a bool or a numpy bool; not a string nor a number)."""
    if not isinstance(value, bool) and type(value).__name__ != "bool_":
        raise ArgumentError(f"expected True or False, got {type(value).__name__} {value!r:.60}", name)
    return bool(value)


def one_of(value, choices, name: str) -> None:
    """Refuse ``value`` unless one of ``choices`` (names), naming the argument ``name``."""
    if not isinstance(value, str) or value not in choices:
        raise ArgumentError(f"expected one of {', '.join(choices)}, got {value!r:.60}", name)


def file_path(value, name: str) -> None:
    """Refuse ``value`` unless a file's path (a str or os.PathLike)."""
    expect(value, (str, os.PathLike), name, "a file's path")
