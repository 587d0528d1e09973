"""YAML read with the line and column of every key and value kept.

:func:`read_yaml` returns the plain data (dicts, lists, scalars) and a map
from each path (a tuple of keys and list indices) to its 1-based
``(line, column)``, so a validation error deep in a file can be reported
where the user wrote it. Duplicate keys are refused, which plain PyYAML
silently accepts. Reading stays within the limits of :mod:`rocketsim.limits`
(file size, nesting, values after aliases are expanded).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import yaml

from rocketsim.errors import InputError
from rocketsim.limits import MAX_VALUES, MAX_YAML_BYTES, ValueBudget, compose_yaml, read_bounded

Position = tuple[int, int]

MERGE_TAG = "tag:yaml.org,2002:merge"


class YamlSource:
    """The data of one YAML file and where each piece of it stands."""

    def __init__(self, path: Path, data: Any, positions: dict[tuple, Position]):
        self.path = path
        self.data = data
        self.positions = positions

    def written_path(self, loc: tuple) -> tuple:
        """The part of ``loc`` that names places written in the file.

        Validation locations can carry parts the file does not contain (a
        discriminated union's tag, for one): those are skipped, so
        ``('weather', 'random', 'seed')`` becomes ``('weather', 'seed')``.
        """
        path: tuple = ()
        for part in loc:
            if path + (part,) in self.positions:
                path += (part,)
        return path

    def position(self, loc: tuple) -> Position | None:
        """Line and column of the deepest written place along ``loc``."""
        return self.positions.get(self.written_path(tuple(loc)))


def read_yaml(path: Path) -> YamlSource:
    """Read ``path`` as YAML with positions; :class:`InputError` if unreadable or
    beyond the limits of :mod:`rocketsim.limits` (size, nesting, alias expansion).

    The file is read every time; what its bytes hold is parsed once per process
    (:data:`_PARSED`, by the bytes themselves: a file changed, whatever its name and
    times, is parsed again) and each caller gets data of its own to change."""
    path = Path(path)
    raw = read_bounded(path, MAX_YAML_BYTES, "YAML file")
    found = _PARSED.get(raw)
    if found is None:
        found = _parse(raw, path)
        if len(raw) + sum(map(len, _PARSED)) > PARSED_BYTES:
            _PARSED.clear()
        _PARSED[raw] = found
    data, positions = found
    return YamlSource(path, _fresh(data), dict(positions))


PARSED_BYTES = 1024 * 1024      # the files' bytes kept parsed at most (a scenario's files: a few kB each)
_PARSED: dict[bytes, tuple[Any, dict[tuple, Position]]] = {}     # a file's bytes -> (data, positions)


def _parse(raw: bytes, path: Path) -> tuple[Any, dict[tuple, Position]]:
    """``(data, positions)`` of the YAML bytes ``raw`` read from ``path`` (see :func:`read_yaml`)."""
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as error:
        raise InputError(f"cannot read the file ({error})", file=path) from None
    node = compose_yaml(text, path)
    if node is None:
        raise InputError("the file is empty; expected a YAML mapping", file=path, line=1)
    builder = _Builder(path)
    try:
        data = builder.build(node, ())
    finally:
        builder.loader.dispose()
    return data, builder.positions


def _fresh(data: Any) -> Any:
    """A copy of YAML ``data`` sharing nothing that can be changed (its mappings and lists
    anew; its scalars, which cannot be changed, as they are)."""
    if type(data) is dict:
        return {key: _fresh(value) for key, value in data.items()}
    if type(data) is list:
        return [_fresh(value) for value in data]
    return data


class _Builder:
    """Turns one document's nodes into data, keeping positions, within a
    :class:`~rocketsim.limits.ValueBudget` (every value reached through an
    alias counts again, so nested aliases cannot expand without bound)."""

    def __init__(self, path: Path):
        self.path = path
        self.positions: dict[tuple, Position] = {}
        self.budget = ValueBudget()
        self.loader = yaml.SafeLoader("")          # constructs the scalars

    def build(self, node: yaml.Node, loc: tuple) -> Any:
        self.positions.setdefault(loc, _position(node))
        if isinstance(node, yaml.MappingNode):
            self._admit(loc, None, node)
            result: dict = {}
            merged: dict = {}
            for key_node, value_node in node.value:
                if key_node.tag == MERGE_TAG:
                    merged = {**self._merged(value_node, loc), **merged}
                    continue
                key = self._scalar(key_node) if isinstance(key_node, yaml.ScalarNode) else None
                if not isinstance(key, (str, int, float, bool)):
                    raise self._error("a mapping key must be a plain name", key_node)
                if key in result:
                    raise self._error(f"duplicate key {key!r}", key_node)
                self.positions[loc + (key,)] = _position(key_node)
                result[key] = self.build(value_node, loc + (key,))
            return {**merged, **result}
        if isinstance(node, yaml.SequenceNode):
            self._admit(loc, None, node)
            return [self.build(item, loc + (i,)) for i, item in enumerate(node.value)]
        value = self._scalar(node)
        self._admit(loc, value, node)
        return value

    def _merged(self, node: yaml.Node, loc: tuple) -> dict:
        """The mapping a merge key (``<<: *defaults`` or ``<<: [*a, *b]``) brings in: the
        earlier of several mappings wins, as in the YAML merge-key specification."""
        parts = node.value if isinstance(node, yaml.SequenceNode) else [node]
        result: dict = {}
        for part in parts:
            if not isinstance(part, yaml.MappingNode):
                raise self._error("YAML merge key: expected a mapping or a list of mappings to merge",
                                  part)
            result = {**self.build(part, loc), **result}
        return result

    def _admit(self, loc: tuple, value: Any, node: yaml.Node) -> None:
        problem = self.budget.admit(len(loc), value)
        if problem is None:
            return
        if self.budget.values > MAX_VALUES:
            # an expansion is reported at the top-level field it happens under (the
            # node itself may be an anchor's, far from where it is expanded)
            loc = loc[:1]
        line, column = self.positions.get(loc, _position(node))
        raise InputError(problem, file=self.path, line=line, column=column,
                         field=".".join(str(part) for part in loc) or None)

    def _scalar(self, node: yaml.ScalarNode) -> Any:
        try:
            return self.loader.construct_object(node, deep=True)
        except yaml.MarkedYAMLError as error:
            raise self._error(f"YAML value: {error.problem}", node, error.problem_mark) from None

    def _error(self, message: str, node: yaml.Node, mark=None) -> InputError:
        mark = mark or node.start_mark
        return InputError(message, file=self.path, line=mark.line + 1, column=mark.column + 1)


def _position(node: yaml.Node) -> Position:
    return node.start_mark.line + 1, node.start_mark.column + 1
