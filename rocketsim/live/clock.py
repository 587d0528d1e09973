"""The clock a live view plays a flight's telemetry by: mission time at warp x wall time.

The clock shows a telemetry time (ns, the messages' log times) that advances at
``warp`` times the wall clock (``time.monotonic``) while playing, stands still
while paused, and is set by the first message it is asked about (it starts
where the telemetry starts). ``warp`` None is ``max``: every time is due at
once. A change of warp or a pause takes effect from the instant it is made,
so the time shown never jumps.

The wall clock only decides when a message already written is served: nothing
here reaches the simulation, whose steps and bytes are the same at every warp.
Changes come from the server's threads (a viewer's requests) while the player
reads the clock: each is made under a lock, and :meth:`PlaybackClock.changed`
wakes whoever waits on the clock.
"""

from __future__ import annotations

import math
import threading
import time

MAX = None      # warp "max": no pacing
_ANY = 2 ** 63 - 1      # a telemetry time later than any (ns)


def parse_warp(text: str | float | None) -> float | None:
    """A warp as given (a positive number, "10", "10x", or "max") as a float, or None
    for ``max``; ValueError for anything else."""
    if text is None or isinstance(text, str) and text.strip().lower() == "max":
        return MAX
    value = text
    if isinstance(text, str):
        value = text.strip().lower().removesuffix("x")
        try:
            value = float(value)
        except ValueError:
            raise ValueError(f"a warp is a positive number or 'max', not {text!r}") from None
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not (0 < value < math.inf):
        raise ValueError(f"a warp is a positive number or 'max', not {text!r}")
    return float(value)


def warp_text(warp: float | None) -> str:
    """``warp`` as a person writes it: ``10x``, ``0.5x``, ``max``."""
    return "max" if warp is MAX else f"{warp:g}x"


class PlaybackClock:
    """Telemetry time (ns) at ``warp`` x wall time; starts playing unless ``paused``."""

    def __init__(self, warp: float | None = 1.0, paused: bool = False, wall=time.monotonic):
        self._wall = wall
        self._lock = threading.Condition()
        self._warp = warp
        self._paused = paused
        self._anchor: tuple[float, int] | None = None      # (wall s, telemetry ns) of the last change

    @property
    def warp(self) -> float | None:
        return self._warp

    @property
    def paused(self) -> bool:
        return self._paused

    @property
    def started(self) -> bool:
        return self._anchor is not None

    def now(self) -> int | None:
        """The telemetry time shown (None: not started)."""
        with self._lock:
            return self._now(self._wall())

    def _now(self, wall: float) -> int | None:
        if self._anchor is None:
            return None
        at, shown = self._anchor
        if self._paused or self._warp is MAX:
            return shown
        return shown + round((wall - at) * self._warp * 1e9)

    def until(self) -> int | None:
        """The latest telemetry time due now (None: not started; at max, any)."""
        with self._lock:
            if self._warp is MAX and not self._paused and self._anchor is not None:
                return _ANY
            return self._now(self._wall())

    def show(self, telemetry_ns: int) -> None:
        """Show ``telemetry_ns`` from now: the first message's time; where the player takes
        up again after it waited for the flight (the flight's next messages follow it rather
        than catch up); at max, the last message served."""
        with self._lock:
            self._anchor = (self._wall(), telemetry_ns)
            self._lock.notify_all()

    def wait_for(self, telemetry_ns: int, longest: float) -> bool:
        """Wait until ``telemetry_ns`` is due (True) or ``longest`` seconds have gone by,
        or the clock was changed (False: ask again)."""
        with self._lock:
            wall = self._wall()
            shown = self._now(wall)
            if shown is None or self._warp is MAX and not self._paused:
                return True
            if not self._paused and shown >= telemetry_ns:
                return True
            delay = longest if self._paused else min(longest, (telemetry_ns - shown) / (self._warp * 1e9))
            self._lock.wait(delay)
            shown = self._now(self._wall())
            return not self._paused and shown >= telemetry_ns

    def set_warp(self, warp: float | None) -> None:
        """Play at ``warp`` (None: max) from now on."""
        with self._lock:
            self._rebase()
            self._warp = warp
            self._lock.notify_all()

    def pause(self) -> None:
        with self._lock:
            self._rebase()
            self._paused = True
            self._lock.notify_all()

    def resume(self) -> None:
        with self._lock:
            self._rebase()
            self._paused = False
            self._lock.notify_all()

    def _rebase(self) -> None:
        """Anchor the clock at the time it shows now (before a change)."""
        if self._anchor is not None:
            wall = self._wall()
            self._anchor = (wall, self._now(wall))

    def changed(self) -> None:
        """Wake whoever waits on the clock."""
        with self._lock:
            self._lock.notify_all()
