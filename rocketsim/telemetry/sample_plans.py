"""What the telemetry writer's byte templates of a body's sample are made from, and the order
its samples are written in (:class:`rocketsim.telemetry.writer.TelemetryWriter`): the
members of a state message that are left out when not finite, a body's *shape* (its message
function, its number of values, those optional values and its templates by the values
missing), the rows of a segment of samples or of interleaved blocks laid out for one
compiled call of :func:`rocketsim.telemetry.splice.records`, by step and then rank."""

from __future__ import annotations

import math

import numpy as np

from rocketsim.telemetry import foxglove, splice
from rocketsim.telemetry.frames import MISSION_FRAME
from rocketsim.telemetry.schemas import BODY_STATE

_REQUIRED = frozenset(BODY_STATE["required"])


def optional_members(message, required=_REQUIRED):
    """The slots of ``message`` that may be left out: values of object members (not vector
    items), but for the state's ``required`` fields."""
    for key, value in message.items():
        if isinstance(value, dict):
            yield from optional_members(value, ())
        elif isinstance(value, splice.Slot) and value.kind == "f" and key not in required:
            yield value


def without(message: dict, missing: set) -> dict:
    """``message`` without the members whose slots' values are ``missing`` (indices)."""
    return {key: without(value, missing) if isinstance(value, dict) else value
            for key, value in message.items()
            if not (isinstance(value, splice.Slot) and value.kind == "f" and value.index in missing)}


def joined(arrays: list[np.ndarray], dtype) -> tuple[np.ndarray, np.ndarray]:
    """``(arrays one after the other, where each begins and the last ends)``."""
    first = np.zeros(len(arrays) + 1, dtype=np.int64)
    np.cumsum([len(a) for a in arrays], out=first[1:])
    return np.concatenate(arrays).astype(dtype, copy=False), first


def present(message: dict, required=_REQUIRED) -> dict:
    """``message`` without the members that are None or not finite (vectors as they are),
    but for the state's ``required`` fields."""
    return {key: present(value, ()) if isinstance(value, dict) else value
            for key, value in message.items()
            if key in required or not (value is None or isinstance(value, float) and not math.isfinite(value))}


def mission_transform(time: dict, root: str, position) -> dict:
    """The mission frame at ``position`` (m) in the root frame, with its axes."""
    return foxglove.frame_transform(time, root, MISSION_FRAME, position, (1.0, 0.0, 0.0, 0.0))


def distinct_templates(plans) -> tuple[list, np.ndarray]:
    """``(templates, kinds)``: the distinct templates among ``plans`` (by identity, in the
    order first met) and the index among them of each plan."""
    templates: dict[int, int] = {}      # id of a template -> its index
    chosen, kinds = [], []
    for plan in plans:
        kind = templates.get(id(plan))
        if kind is None:
            kind = templates[id(plan)] = len(chosen)
            chosen.append(plan)
        kinds.append(kind)
    return chosen, np.array(kinds, dtype=np.int64)


def interleaving(blocks: list[tuple]) -> tuple[np.ndarray, np.ndarray]:
    """``(block, row)`` of each sample of interleaved ``blocks`` in the order they are
    written (see :meth:`~rocketsim.telemetry.writer.TelemetryWriter.sample_interleaved`): by step, then rank."""
    counts = np.array([len(rows) for _, rows, *_ in blocks], dtype=np.int64)
    block = np.repeat(np.arange(len(blocks)), counts)
    row = np.arange(len(block)) - np.repeat(np.cumsum(counts) - counts, counts)
    first, every, rank = (np.array(column, dtype=np.int64)[block] for column in zip(*(b[3:] for b in blocks)))
    order = np.lexsort((rank, first + every * row))
    return block[order], row[order]


def interleaved_samples(blocks: list[tuple]) -> list[tuple]:
    """The samples ``(body, numbers, fields)`` of interleaved ``blocks`` in the order they are
    written (see :meth:`~rocketsim.telemetry.writer.TelemetryWriter.sample_interleaved`)."""
    return [(blocks[b][0], blocks[b][1][r], blocks[b][2]) for b, r in zip(*(a.tolist() for a in interleaving(blocks)))]


def shape(fields, n: int) -> tuple:
    """``(fields, n, optional, templates)``: the value indices of the state message
    ``fields`` makes of ``n`` values that are left out when not finite
    (:func:`optional_members`), and a dictionary for its templates by the values missing."""
    message = fields(splice.slots(n), splice.Slot.integer)
    optional = sorted({slot.index for slot in optional_members(message)})
    return fields, n, np.array(optional, dtype=np.int64), {}


def shape_of(plans: dict, body: str, fields, n: int) -> tuple:
    """The :func:`shape` of ``body``'s samples of ``n`` values made by ``fields``, from
    ``plans`` (body -> shape), made anew there when the body's fields or size changed."""
    found = plans.get(body)
    if found is None or found[0] is not fields or found[1] != n:
        found = plans[body] = shape(fields, n)
    return found


def segment_rows(segment: list[tuple]) -> tuple:
    """The arguments of :meth:`~rocketsim.telemetry.writer.TelemetryWriter._write_rows` for the
    samples of ``segment`` (``(block of samples, a row each, their template)`` pairs, in order)."""
    chosen, kinds = distinct_templates(plan for _, plan in segment)
    sizes = np.array([block.shape[1] for block, _ in segment], dtype=np.int64)
    counts = np.array([block.shape[0] for block, _ in segment], dtype=np.int64)
    kind = np.repeat(kinds, counts)
    row_first = np.zeros(len(kind) + 1, dtype=np.int64)
    np.cumsum(np.repeat(sizes, counts), out=row_first[1:])
    return np.concatenate([block.ravel() for block, _ in segment]), row_first, kind, chosen


def interleaved_rows(blocks: list[tuple], plans: dict) -> tuple | None:
    """The arguments of :meth:`~rocketsim.telemetry.writer.TelemetryWriter._write_rows` for
    the samples of interleaved ``blocks`` (see :meth:`~rocketsim.telemetry.writer.TelemetryWriter.sample_interleaved`),
    each body's shape taken from (or added to) ``plans`` (body -> :func:`shape`); None
    where a sample needs a template not yet made, or a body's blocks differ in shape."""
    block, row = interleaving(blocks)
    counts = np.array([len(rows) for _, rows, *_ in blocks], dtype=np.int64)
    widths = np.array([rows.shape[1] for _, rows, *_ in blocks], dtype=np.int64)
    width = widths[block]
    row_first = np.zeros(len(block) + 1, dtype=np.int64)
    np.cumsum(width, out=row_first[1:])
    begin = (np.cumsum(counts * widths) - counts * widths)[block] + row * width
    values = np.concatenate([rows.ravel() for _, rows, *_ in blocks])
    values = values[np.repeat(begin - row_first[:-1], width) + np.arange(row_first[-1])]
    stretch_of = np.empty(len(block), dtype=np.int64)     # each sample's stretch of one template
    stretches: list = []                                    # their templates, in order
    names = [name for name, *_ in blocks]
    for body in dict.fromkeys(names):
        members = [b for b, name in enumerate(names) if name == body]
        fields, size = blocks[members[0]][2], widths[members[0]]
        if any(blocks[b][2] is not fields or widths[b] != size for b in members):
            return None
        _, _, optional, templates = shape_of(plans, body, fields, int(size))
        mine = np.zeros(len(blocks), dtype=bool)
        mine[members] = True
        at = np.flatnonzero(mine[block])                    # the body's samples, in order
        missing = ~np.isfinite(values[row_first[at][:, None] + optional])
        starts = [0] + (np.flatnonzero((missing[1:] != missing[:-1]).any(axis=1)) + 1).tolist()
        stretch = [templates.get((missing[start].tobytes(), False)) for start in starts]
        if None in stretch:
            return None
        stretch_of[at] = np.repeat(np.arange(len(stretches), len(stretches) + len(stretch)),
                                   np.diff(starts + [len(at)]))
        stretches += stretch
    chosen, kinds = distinct_templates(stretches)
    return values, row_first, kinds[stretch_of], chosen
