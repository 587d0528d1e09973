"""What the Foxglove app needs of an MCAP file, checked in Python (for the tests).

The same rules as the project's foxglove-check tool (the official TypeScript
readers and the app's own JSON-schema parser), so that a clone without that tool
still checks them:

* every JSON schema is one the app's parser (``parseJsonSchema`` of the
  open-source app's ``mcap-support`` package) turns into fields: a plain
  string ``type`` for every field, no ``$ref`` (it follows none), no type
  unions such as ``["number", "null"]``, ``oneOf`` only of numeric ``const``;
  the app drops a topic whose schema it cannot parse;
* every message validates against the schema embedded in the file;
* metadata values that hold JSON are strict JSON (no NaN, no Infinity);
* the transforms make one tree: a single root, one parent per frame, no cycle,
  and every ``frame_id`` used is in it;
* a ``foxglove.LocationFix`` only for a body whose latest state says it is
  about Earth (the app's Map panel has only Earth's tiles), and the body's
  frames (``<body>``, ``<body>/...``) under an Earth frame (``eci``, ``ecef``)
  only then.
"""

from __future__ import annotations

import json
from bisect import bisect_right
from dataclasses import dataclass, field

import jsonschema
from mcap.reader import make_reader

_TYPES = {"object", "array", "number", "integer", "string", "boolean"}


def parser_problems(schema: dict, path: str = "") -> list[str]:
    """Why the app's parser would reject ``schema`` (empty: it parses)."""
    out = []
    if "$ref" in schema or "$defs" in schema:
        out.append(f"{path or 'schema'}: $ref/$defs (the parser follows no reference)")
    if "oneOf" in schema and "type" not in schema:
        if not all(isinstance(o.get("const"), (int, float)) for o in schema["oneOf"]):
            out.append(f"{path}: oneOf of other than numeric consts")
        return out
    kind = schema.get("type")
    if not isinstance(kind, str) or kind not in _TYPES:
        return out + [f"{path or 'schema'}: type {kind!r} (one of {sorted(_TYPES)} needed)"]
    if kind == "object":
        for name, sub in schema.get("properties", {}).items():
            out += parser_problems(sub, f"{path}.{name}" if path else name)
        extra = schema.get("additionalProperties")
        if isinstance(extra, dict):
            out += parser_problems(extra, f"{path}.*")
    elif kind == "array":
        out += parser_problems(schema.get("items", {}), f"{path}[]")
    return out


@dataclass
class Contents:
    """What a file holds, as the rules need it."""

    schemas: dict[str, dict] = field(default_factory=dict)          # name -> schema
    topics: dict[str, str] = field(default_factory=dict)            # topic -> schema name
    messages: list[tuple[str, int, dict]] = field(default_factory=list)   # topic, log time, message
    metadata: dict[str, dict[str, str]] = field(default_factory=dict)

    def of(self, topic: str) -> list[tuple[int, dict]]:
        return [(t, m) for tp, t, m in self.messages if tp == topic]

    def transforms(self) -> list[tuple[str, int, dict]]:
        return [(tp, t, m) for tp, t, m in self.messages
                if self.topics[tp] == "foxglove.FrameTransform"]


def read(path) -> Contents:
    """The schemas, topics, messages (decoded, in file order) and metadata of ``path``."""
    out = Contents()
    with open(path, "rb") as stream:
        reader = make_reader(stream)
        for schema, channel, message in reader.iter_messages(log_time_order=False):
            if schema.name not in out.schemas:
                out.schemas[schema.name] = json.loads(schema.data)
            out.topics[channel.topic] = schema.name
            out.messages.append((channel.topic, message.log_time, json.loads(message.data)))
        for record in reader.iter_metadata():
            out.metadata[record.name] = dict(record.metadata)
    return out


def _strict(text: str):
    def refuse(constant):
        raise ValueError(f"{constant} is not JSON")
    return json.loads(text, parse_constant=refuse)


def problems(contents: Contents) -> list[str]:
    """Every rule of the module that ``contents`` breaks."""
    out = []
    for name, schema in contents.schemas.items():
        out += [f"{name}: {p}" for p in parser_problems(schema)]
    validators = {name: jsonschema.Draft202012Validator(s) for name, s in contents.schemas.items()}
    failing = {}
    for topic, t, message in contents.messages:
        for error in validators[contents.topics[topic]].iter_errors(message):
            failing.setdefault(topic, f"{topic} at {t}: {error.message}")
    out += list(failing.values())
    for name, values in contents.metadata.items():
        if name == "summary":
            try:
                _strict(values["json"])
            except ValueError as error:
                out.append(f"metadata summary: {error}")
    out += tree_problems(contents)
    out += location_problems(contents)
    return out


def tree_problems(contents: Contents) -> list[str]:
    """The frame tree's faults: several roots or parents, a cycle, a frame used but not in it."""
    parents: dict[str, set] = {}
    for _, _, tf in contents.transforms():
        parents.setdefault(tf["child_frame_id"], set()).add(tf["parent_frame_id"])
    frames = set(parents) | {p for ps in parents.values() for p in ps}
    out = []
    roots = sorted(f for f in frames if f not in parents)
    if len(roots) != 1:
        out.append(f"frame tree has roots {roots}")
    out += [f"frame {f} has parents {sorted(ps)}" for f, ps in parents.items() if len(ps) > 1]
    for start in parents:
        seen, f = set(), start
        while f in parents and f not in seen:
            seen.add(f)
            f = min(parents[f])
        if f in seen:
            out.append(f"frame tree has a cycle through {f}")
            break
    for topic, _, message in contents.messages:
        if "frame_id" in message and message["frame_id"] not in frames:
            out.append(f"{topic}: frame {message['frame_id']} is in no transform")
            break
    return out


def central_bodies(contents: Contents) -> dict[str, tuple[list[int], list[str]]]:
    """body -> (log times, central body) of its state messages, in time order."""
    out = {}
    for topic, t, message in contents.messages:
        if "central_body" in message:
            times, centres = out.setdefault(topic.split("/")[1], ([], []))
            times.append(t)
            centres.append(message["central_body"])
    return out


def central_at(states: tuple[list[int], list[str]], t: int) -> str:
    """The central body of the latest state at or before ``t`` (the first one before it)."""
    times, centres = states
    return centres[max(0, bisect_right(times, t) - 1)]


EARTH_FRAMES = {"eci", "ecef"}


def location_problems(contents: Contents) -> list[str]:
    """LocationFix messages of a body, or its frames under an Earth frame, while its latest
    state is about another body than Earth."""
    bodies = central_bodies(contents)
    out = []
    for topic, t, message in contents.messages:
        body = topic.split("/")[1]
        if contents.topics[topic] == "foxglove.LocationFix":
            centre = central_at(bodies[body], t)
            if centre != "earth":
                out.append(f"{topic} at {t}: a LocationFix while {body} is about {centre}")
        elif contents.topics[topic] == "foxglove.FrameTransform" and body in bodies \
                and message["parent_frame_id"] in EARTH_FRAMES:
            centre = central_at(bodies[body], t)
            if centre != "earth":
                out.append(f"{topic} at {t}: {message['child_frame_id']} under "
                           f"{message['parent_frame_id']} while {body} is about {centre}")
    return out[:3]
