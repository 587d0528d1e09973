"""Validation of a file's data against its pydantic model, with errors a user can act on.

:func:`validate` checks what a YAML file (or a scenario given as a mapping, or an
override) holds against a model and turns pydantic's first complaint into one
:class:`~rocketsim.errors.InputError` naming the file, line, column and field path as
written, what was expected, and for a misspelt field the closest valid name. The
scenario's loader (:mod:`rocketsim.scenario.load`), the weather file's
(:mod:`rocketsim.scenario.weather`) and the campaign file's all validate through it.
"""

from __future__ import annotations

import difflib
import re
import reprlib
import types
import typing
from pathlib import Path

from pydantic import BaseModel, ValidationError

from rocketsim.errors import InputError
from rocketsim.scenario.overrides import Edited
from rocketsim.scenario.strict import REQUIRED
from rocketsim.scenario.yaml_source import YamlSource

# a value quoted in a message: a 60 000-character string is shown by its ends
_SHORT = reprlib.Repr()
_SHORT.maxstring = _SHORT.maxother = 80


def quoted(value) -> str:
    """``value`` as a message quotes it: its ``repr``, a long one shortened to its ends."""
    return _SHORT.repr(value)


def validate(source: YamlSource, model: type[BaseModel], data=None, base_dir: Path | None = None):
    """Validate ``source``'s data (or ``data`` read from it) against ``model``; files the
    data names (a solid motor's thrust curve) are relative to ``base_dir`` (default: the
    source file's folder).

    Raises :class:`InputError` for the first problem, with its position.
    """
    if base_dir is None and source.path is not None:
        base_dir = Path(source.path).parent
    try:
        return model.model_validate(source.data if data is None else data,
                                    context={"base_dir": base_dir})
    except ValidationError as error:
        raise _input_error(error, source, model) from None


def _input_error(error: ValidationError, source: YamlSource, model: type[BaseModel]) -> InputError:
    # a field that is "inline or a file name" fails twice when it is wrong:
    # drop the file-name branch's complaint when the inline one explains more
    problems = error.errors(include_url=False)
    problems = [p for p in problems if not {"str", "constrained-str"} & set(p["loc"])] or problems
    # each branch of a union complains: a field one branch has and finds wrong (itself or
    # a field inside it) is unknown to the others; name what the branch that has it says
    unknown = {(p["loc"][:-2], p["loc"][-1]) for p in problems if p["type"] == "extra_forbidden"}
    problems = [p for p in problems if p["type"] != "extra_forbidden"
                and any(_inside_branch(tuple(p["loc"]), base, name) for base, name in unknown)] or problems
    # a misspelt field shows as an unknown one plus a missing one: name the
    # misspelling first, since it is what the user has to fix
    first = min(problems, key=lambda p: p["type"] != "extra_forbidden")
    loc = tuple(first["loc"])
    line, column = source.position(loc) or (None, None)
    # name the field as written; a missing field is not written, so add its name
    written = source.written_path(loc)
    if first["type"] in ("missing", REQUIRED) and loc and written[-1:] != loc[-1:]:
        written += loc[-1:]
    message = _describe(first, written, model)
    words = _words_also_accepted(problems, first)
    if words:
        # a field that is a quantity or a word (a motor's ``ignition``: a time or "program")
        message += f"; or {' or '.join(map(repr, words))}"
        close = difflib.get_close_matches(first["input"], words, n=1, cutoff=0.6)
        if close:
            message += f" (did you mean {close[0]!r}?)"
        problems = [p for p in problems if p is first or not _same_field_literal(p, first)]
    if len(problems) > 1:
        message += f" ({len(problems) - 1} more problem{'s' if len(problems) > 2 else ''} in this file)"
    file, field = source.path, ".".join(str(part) for part in written) or None
    if isinstance(source, Edited):     # a dict scenario, or a value an override set
        file, field, message = source.place(written, message)
    return InputError(message, file=file, line=line, column=column, field=field)


def _inside_branch(loc: tuple, base: tuple, name: str) -> bool:
    """Whether ``loc`` is at or inside the field ``name`` of a union's branch at ``base``
    (``base + (branch tag, name, ...)``)."""
    n = len(base)
    return len(loc) > n + 1 and loc[:n] == base and loc[n + 1] == name


def _same_field_literal(problem: dict, first: dict) -> bool:
    """Whether ``problem`` is the complaint of a literal branch of ``first``'s union field
    about the same string (the two locations differ only in their branch's tag)."""
    return (problem is not first and problem["type"] == "literal_error"
            and tuple(problem["loc"][:-1]) == tuple(first["loc"][:-1]) and problem.get("input") == first.get("input"))


def _words_also_accepted(problems: list[dict], first: dict) -> list[str]:
    """The words a literal branch of ``first``'s union field accepts, when ``first`` is
    another branch's complaint about a string (e.g. ``ignition: progam``: not a time,
    nor ``"program"``)."""
    if not isinstance(first.get("input"), str) or first["type"] == "literal_error":
        return []
    return [word for problem in problems if _same_field_literal(problem, first)
            for word in re.findall(r"'([^']*)'", problem.get("ctx", {}).get("expected", ""))]


def _describe(problem: dict, loc: tuple, model: type[BaseModel]) -> str:
    kind = problem["type"]
    message = problem["msg"]
    if message.startswith("Value error, "):
        message = message[len("Value error, "):]
    if kind == "extra_forbidden":
        allowed = _fields_at(model, loc[:-1])
        message = f"unknown field {loc[-1]!r}"
        close = difflib.get_close_matches(str(loc[-1]), allowed, n=1, cutoff=0.6)
        if close:
            message += f"; did you mean {close[0]!r}?"
        elif allowed:
            message += f"; expected one of: {', '.join(allowed)}"
    elif kind == "missing":
        message = f"missing required field {loc[-1]!r}" if loc else "missing required field"
    elif kind == REQUIRED:
        pass                # the message says what is missing and why
    else:
        given = problem.get("input")
        if not isinstance(given, (dict, list)) and f"got {given!r}" not in message:
            message += f" (got {quoted(given)})"
    return message


def _fields_at(model: type[BaseModel], loc: tuple) -> list[str]:
    """Field names of the model found by following ``loc`` from ``model``."""
    current: object = model
    for part in loc:
        if isinstance(part, int):
            continue
        submodel = _model_in(current)
        if submodel is None or part not in submodel.model_fields:
            return []
        current = submodel.model_fields[part].annotation
    found = _model_in(current)
    return list(found.model_fields) if found else []


def _model_in(annotation: object) -> type[BaseModel] | None:
    """The pydantic model inside an annotation (through Optional, tuple, list)."""
    if isinstance(annotation, type) and issubclass(annotation, BaseModel):
        return annotation
    origin = typing.get_origin(annotation)
    if origin is typing.Annotated:
        return _model_in(typing.get_args(annotation)[0])
    if origin in (typing.Union, types.UnionType, list, tuple):
        for arg in typing.get_args(annotation):
            found = _model_in(arg)
            if found is not None:
                return found
    return None
