"""JSON text of telemetry messages and files: compact, floats in their shortest round-trip
form, NaN and infinities as null (orjson), numpy scalars and arrays as numbers."""

from __future__ import annotations

import orjson


def encode(message: dict) -> bytes:
    """JSON bytes of a message: compact, keys in insertion order, floats in
    their shortest round-trip form (orjson, several times faster than the
    standard library's json on a state message). NaN and infinities become null, as
    JSON has no spelling for them; numpy scalars and arrays are written as numbers."""
    return orjson.dumps(message, default=_plain, option=orjson.OPT_SERIALIZE_NUMPY)


def strict_json(value, indent: bool = False) -> str:
    """``value`` as strict JSON (RFC 8259, what every JSON reader takes): as :func:`encode`,
    NaN and infinities as null; indented by two spaces with ``indent``."""
    return orjson.dumps(value, default=_plain,
                        option=orjson.OPT_SERIALIZE_NUMPY | (orjson.OPT_INDENT_2 if indent else 0)).decode()


def _plain(value):
    if hasattr(value, "item"):          # numpy scalars orjson does not take natively
        return value.item()
    raise TypeError(f"cannot write {type(value).__name__} to telemetry")
