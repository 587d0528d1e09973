"""JSON messages spliced from byte templates: a sample's MCAP records in one compiled call.

A message whose shape is fixed (the same keys, nesting and strings every
sample, only its numbers changing) is written once by orjson with *slots* in
place of the numbers (:func:`template`): the bytes between the slots are the
template. A sample then needs its numbers formatted once, all together
(``orjson.dumps`` of a float64 array: shortest round-trip form, NaN and
infinities as ``null``, exactly the bytes orjson writes for the same floats in
a dict), and :func:`records` copies template and number bytes into the MCAP
Message records (mcap.dev/spec: opcode 5) of the sample's messages. The
result is byte for byte what ``orjson.dumps`` of the messages as dictionaries
gives, without building them.

Slot kinds: a float (the number's orjson bytes), an integer (the number
written as an integer: a count), and the whole seconds and nanoseconds of the
record's time (Foxglove's ``time``).
"""

from __future__ import annotations

import re

import numpy as np
import orjson
from numba.core import cgutils, types
from numba.extending import intrinsic

from rocketsim.jit import njit

FLOAT, INTEGER, SECONDS, NANOSECONDS = 0, 1, 2, 3
_KINDS = "fisn"
_MESSAGE = 5                                    # the MCAP opcode
HEADER = 1 + 8 + 2 + 4 + 8 + 8                 # opcode, length, channel, sequence, two times
_LONGEST = 24                                   # bytes of a number: "-1.2345678901234567e-308"
_SLOT = re.compile(rb'"\\u0000([fisn])(\d+)\\u0000"')


class Slot:
    """The place of ``values[index]`` (or of the record time's seconds, nanoseconds) in a
    message built for :func:`template`; ``integer`` writes the number as an integer."""

    def __init__(self, kind: str, index: int = 0):
        self.kind, self.index = kind, index

    def integer(self) -> "Slot":
        return Slot("i", self.index)

    def __repr__(self):
        return f"\0{self.kind}{self.index}\0"


def slots(n: int) -> list[Slot]:
    """Slots for the values ``0 .. n - 1`` (a template's stand-in for a sample's numbers)."""
    return [Slot("f", i) for i in range(n)]


def time_slots() -> dict:
    """Foxglove's ``time`` of the record (:func:`rocketsim.telemetry.foxglove.timestamp`) as slots."""
    return {"sec": Slot("s"), "nsec": Slot("n")}


def template(messages: list[tuple[int, dict]]) -> tuple[np.ndarray, np.ndarray]:
    """``(text, plan)`` of ``(channel, message with slots)`` pairs, for :func:`records`.

    ``text``: the bytes between the slots, message after message; ``plan``: the
    number of messages, then per message its channel and number of slots, then
    per slot the end of the text before it, its kind and value index, and the
    end of the message's last text."""
    text, plan = bytearray(), [len(messages)]
    cuts = []
    for channel, message in messages:
        data = orjson.dumps(message, default=repr)
        pieces = _SLOT.split(data)
        plan += [channel, (len(pieces) - 1) // 3]
        for k in range(0, len(pieces) - 1, 3):
            text += pieces[k]
            cuts += [len(text), _KINDS.index(pieces[k + 1].decode()), int(pieces[k + 2])]
        text += pieces[-1]
        cuts.append(len(text))
    return np.frombuffer(bytes(text), dtype=np.uint8), np.array(plan + cuts, dtype=np.int64)


def most(text: np.ndarray, plan: np.ndarray) -> int:
    """Bytes the records of a template (:func:`template`) can take (the extra records aside)."""
    n_messages = int(plan[0])
    n_slots = int(plan[2:2 + 2 * n_messages:2].sum())
    return text.shape[0] + n_slots * _LONGEST + n_messages * HEADER


@njit
def _put_u64(out, at, x):
    for b in range(8):
        out[at + b] = (x >> (8 * b)) & 0xFF


@njit(inline="always")
def _put_int(out, at, x):
    """Decimal digits of the integer ``x`` at ``out[at:]``; returns the end."""
    if x < 0:
        out[at] = 45                            # "-"
        at += 1
        x = -x
    digits = 1
    rest = x // 10
    while rest > 0:
        digits += 1
        rest //= 10
    for d in range(digits - 1, -1, -1):
        out[at + d] = 48 + x % 10
        x //= 10
    return at + digits


@njit(nogil=True)
def records(numbers, values, row_first, stamps, sequence, texts, text_first, plans, plan_first, template,
            extras, extra_ends, extra_channels, extra_first, extra_after, out, at, index, n_index):
    """Write the MCAP Message records of samples into ``out`` from ``at`` and each
    record's (channel, log time, start) into ``index`` from entry ``n_index`` (three
    numbers per entry); returns where the records and the index entries end.

    ``values``: the samples' float64 numbers one after the other, sample ``k``'s
    ``values[row_first[k]:row_first[k + 1]]``; ``numbers``: ``orjson.dumps(values)``
    (``[a,b,...]``); ``stamps``: each sample's log and publish time (ns), whose seconds
    and nanoseconds fill the time slots; ``sequence`` the first record's sequence number
    (one more for each next record). Sample ``k``'s messages are those of template
    ``template[k]`` (:func:`template`): its text ``texts[text_first[i]:text_first[i + 1]]``
    and plan ``plans[plan_first[i]:plan_first[i + 1]]`` for template ``i``, so samples of
    several bodies and shapes, in any order, take one call. ``extras``: the data of more
    records, written after a sample's message ``extra_after``: record ``e``'s is
    ``extras[extra_ends[e]:extra_ends[e + 1]]`` on channel ``extra_channels[e]``, and
    sample ``k``'s are the records ``extra_first[k]`` to ``extra_first[k + 1] - 1``.
    ``out`` must have room for :func:`most` bytes a sample and the extra records with
    their headers (``HEADER`` bytes each)."""
    # where each number's bytes begin (after "[" or ","), then one past the closing "]"
    first = np.empty(values.shape[0] + 1, dtype=np.int64)
    first[0] = 1
    k = 1
    for i in range(1, len(numbers) - 1):
        if numbers[i] == 44:                    # ","
            first[k] = i + 1
            k += 1
    first[values.shape[0]] = len(numbers)
    r = n_index
    for sample in range(template.shape[0]):
        a, b, t = row_first[sample], row_first[sample + 1], template[sample]
        at, r = _sample(numbers, first[a:b + 1], values[a:b], stamps[sample], sequence + r - n_index,
                        texts[text_first[t]:text_first[t + 1]], plans[plan_first[t]:plan_first[t + 1]],
                        extras, extra_ends, extra_channels, extra_first[sample], extra_first[sample + 1],
                        extra_after, out, at, index, r)
    return at, r


@njit
def _sample(numbers, first, values, stamp, sequence, text, plan, extras, extra_ends, extra_channels,
            first_extra, end_extra, extra_after, out, at, index, r):
    """One sample's records (see :func:`records`): ``first`` where its numbers begin."""
    n_messages = plan[0]
    seconds, nanoseconds = stamp // 1_000_000_000, stamp % 1_000_000_000
    piece, cut, r0 = 0, 1 + 2 * n_messages, r
    for m in range(n_messages):
        head = at
        _entry(index, r, plan[1 + 2 * m], stamp, at)
        r += 1
        at += HEADER
        for _ in range(plan[2 + 2 * m]):
            end = plan[cut]
            at = _copy(out, at, text, piece, end)
            piece = end
            kind, j = plan[cut + 1], plan[cut + 2]
            cut += 3
            if kind == FLOAT:
                at = _copy(out, at, numbers, first[j], first[j + 1] - 1)
            elif kind == INTEGER:
                at = _put_int(out, at, int(values[j]))
            elif kind == SECONDS:
                at = _put_int(out, at, seconds)
            else:
                at = _put_int(out, at, nanoseconds)
        end = plan[cut]
        cut += 1
        at = _copy(out, at, text, piece, end)
        piece = end
        _header(out, head, at - head - 9, plan[1 + 2 * m], sequence + r - 1 - r0, stamp)
        if m == extra_after:
            for e in range(first_extra, end_extra):
                start, end, channel = extra_ends[e], extra_ends[e + 1], extra_channels[e]
                _entry(index, r, channel, stamp, at)
                r += 1
                _header(out, at, end - start + HEADER - 9, channel, sequence + r - 1 - r0, stamp)
                at = _copy(out, at + HEADER, extras, start, end)
    return at, r


@njit(inline="always")     # a few operations: typed in its callers, no kernel of its own
def _entry(index, r, channel, stamp, at):
    index[3 * r] = channel
    index[3 * r + 1] = stamp
    index[3 * r + 2] = at


@njit(inline="always")
def _copy(out, at, source, start, end):
    """``source[start:end]`` into ``out`` at ``at``; returns the end. Inlined (numba IR):
    its callers pass sources of three types, which would be three signatures."""
    _memcpy(out, at, source, start, end - start)
    return at + end - start


@intrinsic
def _memcpy(typingctx, out, at, source, start, n):
    """``n`` bytes from ``source[start:]`` to ``out[at:]`` (uint8 arrays or bytes), as one
    block copy, where a byte loop would pay per byte for each of a sample's hundred or
    so pieces of 5-30 bytes."""
    def codegen(context, builder, signature, args):
        target = context.make_array(signature.args[0])(context, builder, args[0])
        origin = context.make_array(signature.args[2])(context, builder, args[2])
        cgutils.raw_memcpy(builder, builder.gep(target.data, [args[1]]),
                           builder.gep(origin.data, [args[3]]), args[4], 1)
        return context.get_dummy_value()
    return types.void(out, at, source, start, n), codegen


@njit(inline="always")
def _header(out, at, length, channel, sequence, stamp):
    """An MCAP Message record's header at ``out[at:]``: ``length`` bytes of content follow
    its first 9 bytes (opcode and length)."""
    out[at] = _MESSAGE
    _put_u64(out, at + 1, length)
    out[at + 9] = channel & 0xFF
    out[at + 10] = (channel >> 8) & 0xFF
    for b in range(4):
        out[at + 11 + b] = (sequence >> (8 * b)) & 0xFF
    _put_u64(out, at + 15, stamp)
    _put_u64(out, at + 23, stamp)
