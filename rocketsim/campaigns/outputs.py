"""One run's row of results: flat columns named with dots, from its summary and events.

Columns (the campaign directory's ``results.parquet``; floats unless said):

* ``<body>.final.<key>``, ``<body>.orbit.<key>``, ``<body>.flight.<key>``,
  ``<body>.touchdown.<key>``: the summary's numbers of that part (keys as the summary names them; vectors left out;
  ``orbit.central_body`` a string);
* ``<body>.<event>.t_s`` and ``<body>.<event>.<figure>``: the body's FIRST event of
  that name, its time and its numeric or string figures (lists left out): a ``t_s``
  that is not NaN says the event happened;
* ``<body>.landing.t_s``, ``.latitude_deg``, ``.longitude_deg`` and ``.kind``
  (``touchdown`` or ``impact``, a string): where the body first came down, from that
  event's figures; ``<body>.landing.outcome`` (a string): how it came down or broke up
  (:func:`rocketsim.campaigns.landing.landing_outcome`: upright on target, upright off
  target, hard landing, tipped over, impact, ran dry, broke up, under a parachute);
* each extra output path (the campaign's ``outputs:``) into the summary, in the
  scenario path syntax (``bodies.booster.events[touchdown].tilt_deg``;
  ``[name]`` picks the first item of that name): the column is the path.

A number is a float (a bool 1.0 or 0.0), missing values are NaN (None for a
string column).
"""

from __future__ import annotations

import json
import math
from typing import Any

from rocketsim.campaigns.landing import landing_outcome
from rocketsim.scenario.paths import parse

LANDINGS = ("touchdown", "impact")
SUMMARY_SECTIONS = ("final", "orbit", "flight", "touchdown")   # the summary's parts of a body, as columns
BODY_SECTIONS = (*SUMMARY_SECTIONS, "landing")                  # <body>.<section>.<key>: a body's figures


def _scalar(value) -> Any:
    """A value a column holds (float or str), or ``...`` for one it does not (a list)."""
    if value is None:
        return math.nan
    if isinstance(value, (bool, int, float)):
        return float(value)
    if isinstance(value, str):
        return value
    return ...


def _flat(prefix: str, values: dict | None, row: dict) -> None:
    for key, value in (values or {}).items():
        value = _scalar(value)
        if value is not ...:
            row[f"{prefix}.{key}"] = value


def summary_columns(summary: dict | None, events: list[dict]) -> dict[str, Any]:
    """The columns of the summary (None: the flight ended in an error) and the events
    (dicts with ``t``, ``body``, ``name``, ``figures``, as a run's file holds them)."""
    row: dict[str, Any] = {}
    for body, part in ((summary or {}).get("bodies") or {}).items():
        for section in SUMMARY_SECTIONS:
            _flat(f"{body}.{section}", part.get(section), row)
    landed: set[str] = set()
    seen: dict[str, dict] = {}
    for event in events:
        seen.setdefault(event["body"], {}).setdefault(event["name"], (float(event["t"]), event.get("figures") or {}))
        body, name = event["body"], event["name"]
        if f"{body}.{name}.t_s" in row:
            continue
        row[f"{body}.{name}.t_s"] = float(event["t"])
        _flat(f"{body}.{name}", event.get("figures"), row)
        if name in LANDINGS and body not in landed:
            landed.add(body)
            figures = event.get("figures") or {}
            row[f"{body}.landing.t_s"] = float(event["t"])
            row[f"{body}.landing.latitude_deg"] = _scalar(figures.get("latitude_deg"))
            row[f"{body}.landing.longitude_deg"] = _scalar(figures.get("longitude_deg"))
            row[f"{body}.landing.kind"] = name
    for body, named in seen.items():
        outcome = landing_outcome(named)
        if outcome is not None:
            row[f"{body}.landing.outcome"] = outcome
    return row


def extra_columns(summary: dict | None, paths: list[str]) -> dict[str, Any]:
    """The value at each path into the summary (NaN where there is none; a list or a
    mapping as its JSON text)."""
    row = {}
    for path in paths:
        node: Any = summary
        for step in parse(path):
            if step.key is not None:
                node = node.get(step.key) if isinstance(node, dict) else None
            elif isinstance(node, list) and step.index is not None:
                node = node[step.index] if -len(node) <= step.index < len(node) else None
            elif isinstance(node, list) and step.name is not None:
                node = next((item for item in node if isinstance(item, dict) and item.get("name") == step.name),
                            None)
            elif isinstance(node, dict) and step.name is not None:
                node = node.get(step.name)
            else:
                node = None
        value = _scalar(node)
        row[path] = json.dumps(node) if value is ... else value
    return row


def run_columns(run, paths: list[str]) -> dict[str, Any]:
    """``outcome`` and every output column of a :class:`~rocketsim.api.run.Run` (a whole
    run, or what flew before an error)."""
    return {"outcome": run.outcome, **summary_columns(run.summary, run.file.events),
            **extra_columns(run.summary, paths)}
