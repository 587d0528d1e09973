"""Paths to the fields of a scenario: ``vehicle.stages[booster].engines[*].isp_vacuum``.

One syntax names any field of a scenario and of the files it references
(vehicle, site, mission, weather), for overrides (``rocketsim.load(...,
overrides=...)``, ``rocketsim fly --set``) and anything else that changes a
scenario by name:

* ``a.b.c``: the field ``c`` of ``b`` of ``a`` (a referenced file is entered as
  if it were written inline: ``vehicle.payload.mass``);
* ``list[name]``: the item of a list whose ``name`` is ``name``
  (``stages[second stage]``: spaces are part of the name);
* ``list[2]``: the item at index 2 (from 0), for lists whose items have no name
  (``inertia[0]``, ``throttle[1]``);
* ``list[*]``: every item;
* ``mapping[key]``: a key of a mapping that is not a field name
  (``propellant[booster/LOX]``; ``propellant.booster/LOX`` is the same).

:func:`parse` reads a path into steps; :func:`format_path` writes a location
back in this syntax. Fields are checked against the scenario models, so a
misspelt one is named with the nearest valid name.
"""

from __future__ import annotations

import difflib
import re
import types
import typing
from dataclasses import dataclass
from typing import Callable

from pydantic import BaseModel, RootModel

ALL = "*"
_STEP = re.compile(r"\.?([^.\[\]]+)|\[([^\]]*)\]")


class PathError(ValueError):
    """A path that does not name a field; the message says what does."""


@dataclass(frozen=True)
class Step:
    """One step of a path: a field or key (``key``), an item by index, by name, or all."""

    key: str | None = None
    index: int | None = None
    name: str | None = None
    every: bool = False

    def __str__(self) -> str:
        if self.key is not None:
            return self.key
        return f"[{ALL if self.every else self.index if self.index is not None else self.name}]"


def parse(path: str) -> tuple[Step, ...]:
    """The steps of ``path``; :class:`PathError` if it is not in the syntax above."""
    if not isinstance(path, str) or not path.strip():
        raise PathError(f"expected a field path such as 'vehicle.stages[booster].structure_mass', got {path!r}")
    steps, at = [], 0
    for match in _STEP.finditer(path):
        if match.start() != at or (match.group(0).startswith(".") and at == 0):
            break
        key, selector = match.groups()
        if key is not None:
            steps.append(Step(key=key.strip()))
        elif selector.strip() == ALL:
            steps.append(Step(every=True))
        elif re.fullmatch(r"\s*-?\d+\s*", selector):
            steps.append(Step(index=int(selector)))
        elif selector.strip():
            steps.append(Step(name=selector))
        else:
            break
        at = match.end()
    if at != len(path) or steps[0].key is None:
        raise PathError(f"cannot read the path {path!r} at character {at + 1}: write fields as "
                        "'a.b', list items as '[name]', '[index]' or '[*]'")
    return tuple(steps)


def format_path(loc: tuple, data=None) -> str:
    """``loc`` (keys and list indices) in the path syntax; list items that have a
    ``name`` in ``data`` (the tree ``loc`` runs through) are named by it."""
    out, node = "", data
    for part in loc:
        if isinstance(part, int):
            item = node[part] if isinstance(node, list) and 0 <= part < len(node) else None
            name = item.get("name") if isinstance(item, dict) else None
            out += f"[{name}]" if isinstance(name, str) and _unique(node, name) else f"[{part}]"
            node = item
        else:
            text = str(part)
            out += (f".{text}" if out else text) if _plain(text) else f"[{text}]"
            node = node.get(part) if isinstance(node, dict) else None
    return out


def _plain(text: str) -> bool:
    return bool(text) and not set(text) & set(".[]")


def _unique(items: list, name: str) -> bool:
    return sum(isinstance(i, dict) and i.get("name") == name for i in items) == 1


# --- the models behind a path ---------------------------------------------------------

def models_in(annotation) -> list[type[BaseModel]]:
    """The pydantic models an annotation can hold (through Optional, unions, Annotated)."""
    if isinstance(annotation, type) and issubclass(annotation, BaseModel):
        if issubclass(annotation, RootModel):
            return models_in(annotation.model_fields["root"].annotation)
        return [annotation]
    origin = typing.get_origin(annotation)
    if origin is typing.Annotated:
        return models_in(typing.get_args(annotation)[0])
    if origin in (typing.Union, types.UnionType):
        return [m for arg in typing.get_args(annotation) for m in models_in(arg)]
    return []


def first_held(annotation, answer: Callable[[typing.Any], typing.Any]):
    """The first ``answer(a)`` that is not None over the annotations ``a`` that
    ``annotation`` holds, outside in: an ``Annotated[base, ...]`` itself (its metadata),
    then its base; a union's members in order; any other annotation itself. None if none."""
    origin = typing.get_origin(annotation)
    if origin is typing.Annotated:
        found = answer(annotation)
        return found if found is not None else first_held(typing.get_args(annotation)[0], answer)
    if origin in (typing.Union, types.UnionType):
        for arg in typing.get_args(annotation):
            found = first_held(arg, answer)
            if found is not None:
                return found
        return None
    return answer(annotation)


def _items(annotation):
    """The type of the items of a list, tuple or dict annotation itself (None: another)."""
    if typing.get_origin(annotation) in (list, tuple, dict):
        args = [a for a in typing.get_args(annotation) if a is not Ellipsis]
        return args[-1] if args else typing.Any
    return None


def item_type(annotation):
    """The type of the items of a list, tuple or dict annotation (None: not a container)."""
    return first_held(annotation, _items)


def is_mapping(annotation) -> bool:
    """Whether the annotation is (or may be) a ``dict`` of free keys."""
    return first_held(annotation, lambda a: True if typing.get_origin(a) is dict else None) is not None


def field_names(annotation) -> list[str]:
    """Field names of every model the annotation can hold, in order, once each."""
    return list(dict.fromkeys(name for m in models_in(annotation) for name in m.model_fields))


def field_type(annotation, key: str):
    """The annotation of field ``key`` in the models of ``annotation`` (None: no such field)."""
    for model in models_in(annotation):
        if key in model.model_fields:
            return model.model_fields[key].annotation
    return None


def nearest(given: str, names: list[str]) -> str | None:
    """The valid name nearest ``given``: the closest spelling (difflib), else the first
    name that contains it (``isp`` -> ``isp_vacuum``); None when none is near."""
    close = difflib.get_close_matches(given, names, n=1, cutoff=0.5)
    if close:
        return close[0]
    return next((name for name in names if given.lower() in name.lower()), None)


def unknown_field(key: str, names: list[str], where: str) -> PathError:
    """The error for ``key``, not a field of ``where``: the nearest valid name, or all of them."""
    close = nearest(key, names)
    hint = f"; did you mean {close!r}?" if close else (f"; its fields: {', '.join(names)}" if names else "")
    return PathError(f"{where or 'the scenario'} has no field {key!r}{hint}")


def unknown_name(name: str, names: list[str], where: str) -> PathError:
    """The error for ``[name]``, no item of the list ``where``: the nearest name and all."""
    close = nearest(name, names)
    hint = f"; did you mean {close!r}?" if close else ""
    return PathError(f"{where} has no item named {name!r}{hint}"
                     + (f" (items: {', '.join(names)})" if names else " (its items have no names: use "
                        "an index, [0])"))
