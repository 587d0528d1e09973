"""The fields a path names in a validated scenario, each with its value and unit reader.

A path in the syntax of :mod:`rocketsim.scenario.paths` (``vehicle.stages[*].dry_mass``)
is walked through a loaded, validated scenario: each field it reaches is a
:class:`Place` (its path as written back with the items' names, its validated value,
and the reader of its quantity's units, from the field's annotation). A field the
scenario leaves unset is still reached through the models' annotations. A path that
names no field is a :class:`~rocketsim.scenario.paths.PathError`; :func:`nearest_path` gives
the nearest valid path (each misspelt field or item name replaced by the nearest one).
"""

from __future__ import annotations

import typing
from dataclasses import dataclass
from typing import Any, Callable

from pydantic import BaseModel, BeforeValidator

from rocketsim.scenario.paths import (PathError, Step, field_names, field_type, first_held, is_mapping,
                                      item_type, nearest, unknown_field, unknown_name)
from rocketsim.scenario.units import UnitError


@dataclass(frozen=True)
class Place:
    """One field a path names: its path, its validated value in the scenario (``nominal``)
    and its unit reader (``read(value) -> SI float``; None: a plain number or not a quantity)."""

    path: str
    nominal: Any
    read: Callable[[Any], float] | None

    @property
    def angle(self) -> bool:
        """Whether the field is an angle (it refuses a bare number: written ``"<x> rad"``)."""
        if self.read is None:
            return False
        try:
            self.read(1.0)
        except UnitError:
            return True
        return False


def _join(where: str, key: str) -> str:
    if set(key) & set(".[]"):
        return f"{where}[{key}]"
    return f"{where}.{key}" if where else key


def _name_of(item) -> str | None:
    name = item.get("name") if isinstance(item, dict) else getattr(item, "name", None)
    return name if isinstance(name, str) else None


def _annotation(info):
    """A model field's annotation with the metadata pydantic keeps beside it (its validators)."""
    return typing.Annotated[(info.annotation, *info.metadata)] if info.metadata else info.annotation


def _unit_reader(annotation) -> Callable[[Any], float] | None:
    """The quantity reader (value -> SI float) of a field's annotation, its bounds left
    out (a sigma of a positive field may be read at 0), None for a plain number."""
    return first_held(annotation, _own_reader)


def _own_reader(annotation) -> Callable[[Any], float] | None:
    """The first ``BeforeValidator``'s function in the metadata of an ``Annotated``
    annotation itself (None: none, or not an ``Annotated``)."""
    if typing.get_origin(annotation) is not typing.Annotated:
        return None
    readers = [m.func for m in typing.get_args(annotation)[1:] if isinstance(m, BeforeValidator)]
    return readers[0] if readers else None


def _step_into(node, annotation, step: Step, where: str, repair: bool):
    """``[(where, node, annotation, step as taken)]`` one key step below ``node``."""
    key = step.key
    if isinstance(node, BaseModel):
        fields = type(node).model_fields
        if key not in fields:
            if not repair or nearest(key, list(fields)) is None:
                raise unknown_field(key, list(fields), where)
            key = nearest(key, list(fields))
        return [(_join(where, key), getattr(node, key), _annotation(fields[key]), Step(key=key))]
    if isinstance(node, dict):
        return [(_join(where, key), node.get(key), item_type(annotation), step)]
    if node is None:            # not set in the scenario: the models still name the fields
        sub = field_type(annotation, key)
        if sub is None and not is_mapping(annotation):
            names = field_names(annotation)
            if not names:
                raise PathError(f"{where} is a value: it has no field {key!r}")
            if not repair or nearest(key, names) is None:
                raise unknown_field(key, names, where)
            key = nearest(key, names)
            sub = field_type(annotation, key)
        return [(_join(where, key), None, sub if sub is not None else item_type(annotation), Step(key=key))]
    raise PathError(f"{where} is {node!r}, a value: it has no field {key!r}")


def _step_items(node, annotation, step: Step, where: str, repair: bool):
    """``[(where, item, annotation, step as taken)]`` of the list items ``step`` selects."""
    sub = item_type(annotation)
    if node is None:
        return [(f"{where}{step}", None, sub, step)]
    if not isinstance(node, (list, tuple)):
        raise PathError(f"{where} is not a list: {step} selects list items")
    names = [_name_of(item) for item in node]

    def shown(k: int) -> str:
        unique = names[k] is not None and names.count(names[k]) == 1
        return f"{where}[{names[k]}]" if unique else f"{where}[{k}]"

    if step.every:
        return [(shown(k), item, sub, step) for k, item in enumerate(node)]
    if step.index is not None:
        if not 0 <= step.index < len(node):
            raise PathError(f"{where} has {len(node)} items: index {step.index} is out of range")
        return [(f"{where}[{step.index}]", node[step.index], sub, step)]
    chosen = [k for k, name in enumerate(names) if name == step.name]
    if not chosen:
        valid = [n for n in names if n is not None]
        if not repair or nearest(step.name, valid) is None:
            raise unknown_name(step.name, valid, where)
        fixed = nearest(step.name, valid)
        chosen = [k for k, name in enumerate(names) if name == fixed]
        step = Step(name=fixed)
    return [(f"{where}[{step.name}]", node[k], sub, step) for k in chosen]


def _walk(node, annotation, steps: tuple[Step, ...], where: str, repair: bool):
    """Every ``(where, node, annotation, steps taken)`` that ``steps`` reach from ``node``."""
    if not steps:
        return [(where, node, annotation, ())]
    step, rest = steps[0], steps[1:]
    if step.key is None and isinstance(node, dict) and step.name is not None:
        step = Step(key=step.name)          # mapping[key]
    below = (_step_into if step.key is not None else _step_items)(node, annotation, step, where, repair)
    found = []
    for text, child, sub, taken in below:
        found += [(t, n, a, (taken,) + s) for t, n, a, s in _walk(child, sub, rest, text, repair)]
    return found


def locate(scenario, annotation, steps: tuple[Step, ...], where: str) -> list[Place]:
    """The fields ``steps`` name in the validated ``scenario``; PathError if one is not a field."""
    return [Place(text, node, _unit_reader(sub)) for text, node, sub, _ in
            _walk(scenario, annotation, steps, where, repair=False)]


def nearest_path(scenario, annotation, steps: tuple[Step, ...]) -> str | None:
    """``steps`` with each misspelt field or item name replaced by the nearest valid one,
    as a path (the selectors as given), or None when none is near."""
    found = _walk(scenario, annotation, steps, "", repair=True)
    if not found:
        return None
    taken = found[0][3]
    text = ""
    for step in taken:
        text = _join(text, step.key) if step.key is not None else f"{text}{step}"
    return text
