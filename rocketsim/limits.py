"""Bounds on what rocketsim reads from a user: file sizes, nesting, alias expansion.

Scenario, vehicle, site, weather and mission files, soundings and programs
come from colleagues, forums and scripts. Each is read within the limits
below, so a hostile or broken file (a YAML "billion laughs" of nested
aliases, a list nested ten thousand deep, a sounding that is really a disk
image, a FIFO that never ends) is refused with an
:class:`~rocketsim.errors.InputError` naming the file, the line and the limit
instead of taking the machine's memory or hanging.

The limits, and why each is where it is:

* :data:`MAX_YAML_BYTES`, 256 KiB: PyYAML reads about 100-200 kB/s of YAML
  on a loaded machine, so a file at the limit parses in a few seconds; the
  largest shipped file (vehicles/falcon9-block5.yaml) is 8 kB.
* :data:`MAX_TEXT_BYTES`, 4 MiB: soundings (CSV, Wyoming text) and programs,
  read by fast parsers; a radiosonde's high-resolution listing is under 1 MB.
* :data:`MAX_DEPTH`, 32 levels of mappings and lists within each other (the
  deepest shipped file has 6).
* :data:`MAX_VALUES`, 100 000 values once YAML aliases are expanded (a
  mapping, a list and a scalar are a value each; the largest shipped file has
  about 1 000).
* :data:`MAX_TEXT_LENGTH`, 65 536 characters in one string.
* :data:`MAX_QUANTITY`, 1e30 in SI units: the largest magnitude a quantity
  (a length, a mass, a force...) may have, so that squares and cubes of what
  was read stay finite.

:func:`check_data` applies the last three to data handed over in memory (a
scenario given as a dict), and :func:`compose_yaml` to YAML text before it
becomes data. Within these, a vehicle's figures are held to what a vehicle can
physically have by :mod:`rocketsim.scenario.bounds` (docs/physics.md#input-bounds).
"""

from __future__ import annotations

import os
import stat
from pathlib import Path
from typing import Any

import yaml

from rocketsim.errors import InputError

MAX_YAML_BYTES = 256 * 1024
MAX_TEXT_BYTES = 4 * 1024 * 1024
MAX_DEPTH = 32
MAX_VALUES = 100_000
MAX_TEXT_LENGTH = 65_536
# the largest magnitude of any quantity in SI units (a length, a mass, a force...): no input
# of a flight comes near it (a planet's mass is 6e24 kg, Neptune 4.5e12 m away), and its
# square and cube stay finite, so no formula overflows on a value that passed
MAX_QUANTITY = 1e30
# the largest seed of a random stream: numpy's SeedSequence takes non-negative integers,
# and a seed up to 2^64 - 1 travels exactly in telemetry metadata and Parquet (uint64)
MAX_SEED = 2 ** 64 - 1


def read_bounded(path: str | Path, limit: int, what: str) -> bytes:
    """The bytes of the regular file ``path``, refused above ``limit`` bytes.

    ``what`` names the kind of file in messages ("YAML file", "sounding").
    A missing file, a folder, a device or a FIFO (which could block forever)
    is an :class:`InputError` naming the file.
    """
    path = Path(path)
    try:
        with open(path, "rb", buffering=0) as stream:
            if not stat.S_ISREG(os.fstat(stream.fileno()).st_mode):
                raise InputError(f"not a regular file (a {what} is read from a file)", file=path)
            data = stream.read(limit + 1)
    except FileNotFoundError:
        raise InputError("file not found", file=path) from None
    except IsADirectoryError:
        raise InputError(f"is a folder, not a {what}", file=path) from None
    except OSError as error:
        raise InputError(f"cannot read the file ({error.strerror or error})", file=path) from None
    if len(data) > limit:       # named at the line where the limit is crossed
        raise InputError(f"the file is larger than the {limit // 1024} KiB a {what} may have",
                         file=path, line=data.count(b"\n", 0, limit) + 1)
    return data


class ValueBudget:
    """Counts the values of one document as they are built and refuses the
    one past :data:`MAX_VALUES`, or one deeper than :data:`MAX_DEPTH`.

    :meth:`admit` returns None while within the limits, else the message to
    raise (the caller knows where the value stands).
    """

    __slots__ = ("values",)

    def __init__(self):
        self.values = 0

    def admit(self, depth: int, value: Any = None) -> str | None:
        self.values += 1
        if depth > MAX_DEPTH:
            return f"nested deeper than {MAX_DEPTH} levels of mappings and lists (the limit)"
        if self.values > MAX_VALUES:
            return (f"more than {MAX_VALUES} values once YAML aliases are expanded "
                    "(the limit; a 'billion laughs' of nested aliases?)")
        if isinstance(value, str) and len(value) > MAX_TEXT_LENGTH:
            return f"a text of {len(value)} characters, more than the {MAX_TEXT_LENGTH} allowed"
        return None


def check_data(data: Any, file: str | Path | None = None) -> Any:
    """Refuse ``data`` (dicts, lists, tuples and scalars, as a scenario handed over in
    memory) beyond the nesting, value-count and text-length limits; return it.

    Walks without recursion and counts shared and self-referencing parts once
    per place they are reached, as validating them would: a structure that
    contains itself is refused as too deep. The error's field is the dotted
    path of the offending value.
    """
    budget = ValueBudget()
    stack: list[tuple[Any, tuple]] = [(data, ())]
    while stack:
        value, loc = stack.pop()
        problem = budget.admit(len(loc), value)
        if problem is not None:
            raise InputError(problem, file=file, field=".".join(str(p) for p in loc) or None)
        if isinstance(value, dict):
            for key, item in value.items():
                if isinstance(key, str) and len(key) > MAX_TEXT_LENGTH:
                    raise InputError(f"a key of {len(key)} characters, more than the "
                                     f"{MAX_TEXT_LENGTH} allowed", file=file,
                                     field=".".join(str(p) for p in loc) or None)
                stack.append((item, loc + (key,)))
        elif isinstance(value, (list, tuple)):
            stack.extend((item, loc + (i,)) for i, item in enumerate(value))
    return data


class _DepthBoundedLoader(yaml.SafeLoader):
    """PyYAML's safe loader, composing at most :data:`MAX_DEPTH` nested nodes.

    PyYAML composes recursively: a list nested a few hundred deep would end
    in a RecursionError, and nodes are what aliases share, so the composed
    graph stays as small as the text (expansion is bounded by
    :class:`ValueBudget` when the nodes become data).
    """

    def __init__(self, stream):
        super().__init__(stream)
        self._depth = 0

    def compose_node(self, parent, index):
        self._depth += 1
        try:
            if self._depth > MAX_DEPTH:
                mark = self.peek_event().start_mark
                raise _TooDeep(mark)
            return super().compose_node(parent, index)
        finally:
            self._depth -= 1


class _TooDeep(Exception):
    def __init__(self, mark):
        super().__init__()
        self.mark = mark


def compose_yaml(text: str, file: str | Path | None):
    """The YAML node graph of ``text`` (None for an empty document), nested at most
    :data:`MAX_DEPTH` deep; syntax errors and the depth limit are an
    :class:`InputError` at their line and column in ``file``."""
    try:
        return yaml.compose(text, Loader=_DepthBoundedLoader)
    except _TooDeep as error:
        raise InputError(f"nested deeper than {MAX_DEPTH} levels of mappings and lists (the limit)",
                         file=file, line=error.mark.line + 1, column=error.mark.column + 1) from None
    except yaml.MarkedYAMLError as error:
        mark = error.problem_mark or error.context_mark
        problem = error.problem or error.context or "invalid YAML"
        raise InputError(f"YAML syntax error: {problem}", file=file,
                         line=mark.line + 1 if mark else None,
                         column=mark.column + 1 if mark else None) from None
    except yaml.YAMLError as error:
        raise InputError(f"YAML error: {error}", file=file) from None
