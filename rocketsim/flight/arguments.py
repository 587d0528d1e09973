"""The checks of what a flight program passes to ``fc``: types, finiteness, ranges, names.

Every ``fc`` call checks its arguments before anything reaches the world or
a compiled kernel: a ``nan`` pitch, a ``1e30`` s cruise (whose step count
overflows the kernels' 64-bit integers) or a string where a number belongs
would otherwise fly on as nonsense or end in a numba traceback. A check that
fails raises :class:`TypeError` (wrong kind of value) or :class:`ValueError`
(out of range) whose message starts with the call, ``fc.point(): pitch ...``;
raised inside the program, it ends the flight as a
:class:`~rocketsim.flight.program.ProgramError` naming the program's line.

Each function takes the call's name (``"fc.point"``), the argument's name and
value, and returns the value as the simulator uses it (a float, a bool, a
3-vector).
"""

from __future__ import annotations

import math
import numbers
from typing import Any, Callable

import numpy as np

from rocketsim.constants import MAX_DURATION, SPEED_OF_LIGHT
from rocketsim.limits import MAX_TEXT_LENGTH

# a heading or roll may be given in any turn, not one of thousands of turns
# (sin and cos of 1e300 are meaningless): within two turns either way
MAX_TURN = 4.0 * math.pi
# a pitch is an elevation above the horizon; a hair beyond a right angle is
# what math.radians(90.0) and pi/2 sums give
MAX_PITCH = math.pi / 2 + 1e-9
# a vector's components: their squares, and the sum of them, stay finite floats
# (a direction's length, a velocity's speed: 1e200 would overflow to inf)
MAX_COMPONENT = 1e150


def number(call: str, name: str, value: Any, low: float = -math.inf, high: float = math.inf) -> float:
    """``value`` as a finite float within ``[low, high]``."""
    if isinstance(value, (bool, np.bool_)) or not _is_real(value):
        raise TypeError(f"{call}(): {name} must be a number, got {_shown(value)}")
    try:
        x = float(value)
    except OverflowError:               # an integer beyond a float's range
        x = math.inf if value > 0 else -math.inf
    if not math.isfinite(x):
        raise ValueError(f"{call}(): {name} must be a finite number, got {x!r}")
    if not low <= x <= high:
        raise ValueError(f"{call}(): {name} must be within {low:g} .. {high:g}, got {x!r}")
    return x


def duration(call: str, value: Any, name: str = "seconds") -> float:
    """A time to hand control back for: finite, from 0 s to a century, s."""
    return number(call, name, value, 0.0, MAX_DURATION)


def angle(call: str, name: str, value: Any, limit: float = MAX_TURN) -> float:
    """An angle in rad, finite, within ``limit`` either way."""
    return number(call, name, value, -limit, limit)


def roll(call: str, value: Any) -> float | None:
    """A commanded roll (rad), or None: roll left free."""
    return None if value is None else angle(call, "roll", value)


def vector(call: str, name: str, value: Any) -> np.ndarray:
    """Three finite numbers, each within :data:`MAX_COMPONENT` either way, as a float array."""
    if isinstance(value, (str, bytes, dict)) or not hasattr(value, "__len__"):
        raise TypeError(f"{call}(): {name} must be 3 numbers (a list or array), got {_shown(value)}")
    if len(value) != 3:
        raise ValueError(f"{call}(): {name} must be 3 numbers, got {len(value)}")
    return np.array([number(call, f"{name}[{i}]", v, -MAX_COMPONENT, MAX_COMPONENT) for i, v in enumerate(value)])


def velocity(call: str, name: str, value: Any) -> np.ndarray:
    """A velocity (m/s) as :func:`vector`, slower than light."""
    v = vector(call, name, value)
    speed = math.sqrt(float(v @ v))
    if not speed < SPEED_OF_LIGHT:
        raise ValueError(f"{call}(): {name} must be slower than light ({SPEED_OF_LIGHT:.0f} m/s), "
                         f"got {speed:g} m/s")
    return v


def flag(call: str, name: str, value: Any) -> bool:
    """True or False (a Python or numpy bool)."""
    if not isinstance(value, (bool, np.bool_)):
        raise TypeError(f"{call}(): {name} must be True or False, got {_shown(value)}")
    return bool(value)


def choice(call: str, name: str, value: Any, options) -> str:
    """One of ``options`` (strings)."""
    if not isinstance(value, str) or value not in options:
        raise ValueError(f"{call}(): {name} must be one of {', '.join(options)}; got {_shown(value)}")
    return value


def text(call: str, name: str, value: Any) -> str:
    """A string of at most :data:`~rocketsim.limits.MAX_TEXT_LENGTH` characters."""
    if not isinstance(value, str):
        raise TypeError(f"{call}(): {name} must be a string, got {_shown(value)}")
    if len(value) > MAX_TEXT_LENGTH:
        raise ValueError(f"{call}(): {name} is {len(value)} characters long, more than the "
                         f"{MAX_TEXT_LENGTH} allowed")
    return value


def engines(call: str, which: Any):
    """An engine selection: None (all), an index, a name, or a list of indices and names
    (:mod:`rocketsim.vehicle.control`); the names themselves are checked there."""
    items = which if isinstance(which, (list, tuple)) else [which]
    if which is None:
        return None
    for item in items:
        if isinstance(item, (bool, np.bool_)) or not isinstance(item, (str, numbers.Integral)):
            raise TypeError(f"{call}(): which must be None, an engine index or name, or a list of "
                            f"them; got {_shown(item)}")
    return which


def condition(call: str, predicate: Any) -> Callable[[], bool]:
    """A function of no arguments (checked when called: :func:`truth`)."""
    if not callable(predicate):
        raise TypeError(f"{call}() needs a function, e.g. lambda: fc.altitude > 1e5; "
                        f"got {_shown(predicate)}")
    return predicate


def truth(value: Any) -> bool:
    """What a ``fc.wait_until`` condition returned, as a bool: True or False only
    (``lambda: None`` would otherwise wait to the end of the flight unnoticed)."""
    if not isinstance(value, (bool, np.bool_)):
        raise TypeError(f"fc.wait_until(): the condition must return True or False, "
                        f"got {_shown(value)}")
    return bool(value)


def figures(call: str, values: dict) -> dict:
    """An event's figures by name: strings, bools, 64-bit integers and floats (nan too:
    a figure may be unknown), or a list of them (a vector), as their Python types."""
    for key in values:
        if key == "time_s":
            raise ValueError(f"{call}(): the figure time_s is the event's own time; name it otherwise")
    return {key: [_figure(call, f"{key}[{i}]", item) for i, item in enumerate(_items(call, key, value))]
            if isinstance(value, (list, tuple, np.ndarray)) and not _is_real(value)
            else _figure(call, key, value) for key, value in values.items()}


def _items(call: str, key: str, value) -> list:
    if len(value) > MAX_TEXT_LENGTH:
        raise ValueError(f"{call}(): the figure {key} has {len(value)} items, more than the "
                         f"{MAX_TEXT_LENGTH} allowed")
    return list(value)


def _figure(call: str, key: str, value: Any):
    if isinstance(value, str):
        return text(call, key, value)
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    if isinstance(value, numbers.Integral):
        if not -2**63 <= value < 2**63:
            raise ValueError(f"{call}(): the figure {key} is an integer beyond 64 bits")
        return int(value)
    if not _is_real(value):
        raise TypeError(f"{call}(): the figure {key} must be a number, a string, a bool or a "
                        f"list of them, got {_shown(value)}")
    return float(value)


def _is_real(value: Any) -> bool:
    return isinstance(value, numbers.Real) or (
        isinstance(value, np.ndarray) and value.shape == () and value.dtype.kind in "iuf")


def _shown(value: Any) -> str:
    """``value`` for a message: its type and a short repr."""
    shown = repr(value) if isinstance(value, (str, bytes, int, float, type(None))) else type(value).__name__
    return shown if len(shown) <= 60 else shown[:57] + "..."
