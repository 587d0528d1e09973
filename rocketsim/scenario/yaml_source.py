"""YAML read with the line and column of every key and value kept.

:func:`read_yaml` returns the plain data (dicts, lists, scalars) and a map
from each path (a tuple of keys and list indices) to its 1-based
``(line, column)``, so a validation error deep in a file can be reported
where the user wrote it. Duplicate keys are refused, which plain PyYAML
silently accepts.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import yaml

from rocketsim.errors import InputError

Position = tuple[int, int]


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
    """Read ``path`` as YAML with positions; :class:`InputError` if unreadable."""
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise InputError("file not found", file=path) from None
    except (OSError, UnicodeDecodeError) as error:
        raise InputError(f"cannot read the file ({error})", file=path) from None
    try:
        node = yaml.compose(text, Loader=yaml.SafeLoader)
    except yaml.MarkedYAMLError as error:
        mark = error.problem_mark or error.context_mark
        problem = error.problem or error.context or "invalid YAML"
        raise InputError(f"YAML syntax error: {problem}", file=path,
                         line=mark.line + 1 if mark else None,
                         column=mark.column + 1 if mark else None) from None
    positions: dict[tuple, Position] = {}
    if node is None:
        raise InputError("the file is empty; expected a YAML mapping", file=path, line=1)
    data = _construct(node, (), positions, path)
    return YamlSource(path, data, positions)


def _construct(node: yaml.Node, loc: tuple, positions: dict, path: Path) -> Any:
    positions.setdefault(loc, (node.start_mark.line + 1, node.start_mark.column + 1))
    if isinstance(node, yaml.MappingNode):
        _flatten_merge_keys(node, path)
        result: dict = {}
        for key_node, value_node in node.value:
            key = _scalar(key_node, path) if isinstance(key_node, yaml.ScalarNode) else None
            if not isinstance(key, (str, int, float, bool)):
                raise InputError("a mapping key must be a plain name", file=path,
                                 line=key_node.start_mark.line + 1,
                                 column=key_node.start_mark.column + 1)
            if key in result:
                raise InputError(f"duplicate key {key!r}", file=path,
                                 line=key_node.start_mark.line + 1,
                                 column=key_node.start_mark.column + 1)
            positions[loc + (key,)] = (key_node.start_mark.line + 1, key_node.start_mark.column + 1)
            result[key] = _construct(value_node, loc + (key,), positions, path)
        return result
    if isinstance(node, yaml.SequenceNode):
        return [_construct(item, loc + (i,), positions, path) for i, item in enumerate(node.value)]
    return _scalar(node, path)


def _flatten_merge_keys(node: yaml.MappingNode, path: Path) -> None:
    """Apply YAML merge keys (``<<: *defaults``) in place, as PyYAML's loader does."""
    loader = yaml.SafeLoader("")
    try:
        loader.flatten_mapping(node)
    except yaml.MarkedYAMLError as error:
        mark = error.problem_mark
        raise InputError(f"YAML merge key: {error.problem}", file=path,
                         line=mark.line + 1 if mark else None,
                         column=mark.column + 1 if mark else None) from None
    finally:
        loader.dispose()


def _scalar(node: yaml.ScalarNode, path: Path) -> Any:
    loader = yaml.SafeLoader("")
    try:
        return loader.construct_object(node, deep=True)
    except yaml.MarkedYAMLError as error:
        mark = error.problem_mark or node.start_mark
        raise InputError(f"YAML value: {error.problem}", file=path,
                         line=mark.line + 1, column=mark.column + 1) from None
    finally:
        loader.dispose()
