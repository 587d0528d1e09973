"""Overrides: fields of a scenario changed by path before it is validated.

``{"vehicle.stages[booster].structure_mass": "26 t", "mission.epoch":
"2026-11-27T15:00:00Z"}`` sets those fields (paths: :mod:`rocketsim.scenario.paths`)
in the data read from the files, or in a scenario given as a dict, and the
result is validated as if the files said so: same units, same checks. A path
entering a referenced file (``vehicle: ../vehicles/falcon9-block5.yaml``) changes
that file's data, not the file. Values are what a YAML file would hold (numbers,
strings with units, lists, mappings).

A path that names no field raises an :class:`~rocketsim.errors.InputError`
naming the path and the nearest valid name, before anything is validated; a
value that does not validate is reported at the override's path. :class:`Edited`
is the data of one file (or of a dict scenario) as the overrides left it: it
answers where each field was written, as :class:`~rocketsim.scenario.yaml_source.YamlSource`
does, and names the override for a field it set.
"""

from __future__ import annotations

from typing import Any, Callable, Mapping

from rocketsim.errors import InputError
from rocketsim.scenario.paths import (PathError, Step, field_names, field_type, format_path,
                                      is_mapping, item_type, parse, unknown_field, unknown_name)


class Overrides:
    """Paths and the values to set there, in order (a later one wins)."""

    def __init__(self, overrides: Mapping[str, Any] | None):
        self.items: list[tuple[str, tuple[Step, ...], Any]] = []
        for text, value in (overrides or {}).items():
            try:
                self.items.append((text, parse(text), value))
            except PathError as error:
                raise InputError(str(error), field=str(text)) from None
        self.edited: dict[tuple, str] = {}      # location set -> the override's path

    def apply(self, data: dict, model, open_reference: Callable[[str, str], Any]) -> dict:
        """``data`` (a scenario's mapping, not changed) with every override set.

        ``model``: the pydantic model of ``data``; ``open_reference(field, value)``: the
        data of the file a top-level field names (``vehicle: x.yaml``), for a path
        that enters it."""
        for text, steps, value in self.items:
            try:
                data = _set(data, model, steps, value, (), "", text, self.edited, open_reference)
            except PathError as error:
                raise InputError(f"{error}", field=text) from None
        return data

    def source(self, base, data, prefix: tuple = ()) -> "Edited":
        """The :class:`Edited` view of ``data``, read from ``base`` (a YamlSource, None:
        a dict) and found at ``prefix`` of the scenario."""
        n = len(prefix)
        return Edited(base, data, {loc[n:]: text for loc, text in self.edited.items() if loc[:n] == prefix},
                      prefix)


def _set(node, annotation, steps: tuple[Step, ...], value, loc: tuple, where: str, text: str,
         edited: dict, open_reference) -> Any:
    """``node`` (at ``loc``, of type ``annotation``; ``where``: the path to it as written)
    with ``value`` set at ``steps`` below it."""
    if not steps:
        edited[loc] = text
        return value
    step, rest = steps[0], steps[1:]
    if isinstance(node, str) and len(loc) == 1:
        node = open_reference(loc[0], node)         # enter a referenced file
    if step.key is not None and not isinstance(node, list):
        sub = field_type(annotation, step.key)
        if sub is None and not is_mapping(annotation):
            names = field_names(annotation)
            if not names:
                raise PathError(f"{where} is a value: it has no field {step.key!r}")
            raise unknown_field(step.key, names, where)
        if sub is None:
            sub = item_type(annotation)
        if node is not None and not isinstance(node, dict):
            raise PathError(f"{where} is {node!r}, not a mapping: it has no field {step.key!r}")
        node = dict(node or {})
        node[step.key] = _set(node.get(step.key), sub, rest, value, loc + (step.key,),
                              f"{where}.{step.key}" if where else step.key, text, edited, open_reference)
        return node
    if step.key is not None:
        raise PathError(f"{where} is a list: select its items with [name], [index] or [*] "
                        f"before {step.key!r}")
    if (node is None or isinstance(node, dict)) and step.name is not None and is_mapping(annotation):
        return _set(node, annotation, (Step(key=step.name),) + rest, value, loc, where, text, edited,
                    open_reference)
    if not isinstance(node, (list, tuple)):
        raise PathError(f"{where} is not a list{' (it is not set)' if node is None else ''}: "
                        f"{step} selects list items")
    items = list(node)
    if step.every:
        chosen = range(len(items))
    elif step.index is not None:
        if not 0 <= step.index < len(items):
            raise PathError(f"{where} has {len(items)} items: index {step.index} is out of range")
        chosen = [step.index]
    else:
        names = [i.get("name") for i in items if isinstance(i, dict) and isinstance(i.get("name"), str)]
        chosen = [k for k, i in enumerate(items) if isinstance(i, dict) and i.get("name") == step.name]
        if not chosen:
            raise unknown_name(step.name, names, where)
    sub = item_type(annotation)
    for k in chosen:
        shown = f"{where}[{k}]" if step.name is None else f"{where}[{step.name}]"
        items[k] = _set(items[k], sub, rest, value, loc + (k,), shown, text, edited, open_reference)
    return items


class Edited:
    """One file's data (``base``, a YamlSource) or a dict scenario's (``base`` None) as
    the overrides left it, found at ``prefix`` of the scenario; ``edited`` maps each
    location an override set (relative to ``prefix``) to the override's path.

    Read like a YamlSource by :func:`rocketsim.scenario.load.validate`: positions are the
    file's, except where an override wrote (none there, and no file)."""

    def __init__(self, base, data, edited: dict[tuple, str], prefix: tuple = ()):
        self.base = base
        self.path = base.path if base is not None else None
        self.data = data
        self.edited = edited
        self.prefix = prefix

    def written_path(self, loc: tuple) -> tuple:
        """The parts of ``loc`` that are places in the data (a union's tag is not one)."""
        path, node = (), self.data
        for part in loc:
            if isinstance(node, dict) and part in node:
                node = node[part]
            elif isinstance(node, (list, tuple)) and isinstance(part, int) and 0 <= part < len(node):
                node = node[part]
            else:
                continue
            path += (part,)
        return path

    def override(self, written: tuple) -> str | None:
        """The override that set ``written`` or a place above it (None: none did)."""
        for n in range(len(written), -1, -1):
            if written[:n] in self.edited:
                return self.edited[written[:n]]
        return None

    def position(self, loc: tuple):
        written = self.written_path(tuple(loc))
        if self.base is None or self.override(written) is not None:
            return None
        return self.base.positions.get(written)

    def place(self, written: tuple, message: str) -> tuple[str | None, str | None, str]:
        """``(file, field, message)`` of a problem at ``written``: the file's dotted field
        as the loader names it, or, for a dict scenario or an override's value, the
        field in the path syntax and no file."""
        override = self.override(written)
        if override is None and self.base is not None:
            return self.path, ".".join(str(part) for part in written) or None, message
        data = {self.prefix[0]: self.data} if len(self.prefix) == 1 else self.data
        field = format_path(self.prefix + written, data) or None
        if override is not None and override != field:
            message += f" (set by the override {override!r})"
        return None, field, message
