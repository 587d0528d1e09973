"""docs/fc.md, the `fc` reference, with an example for every call: every public member
of FlightComputer has a section there with an example that uses it, every example
compiles, and the examples run.

Each python block of the page starts with ``# runs on: <scenario>`` or ``# not run:
<why>``. Each scenario below is flown once with a program that runs all of its
blocks, in the page's order, each wrapped so that a block that raises is recorded
(with the page's line) and the next one still runs; the test fails naming every
block that raised or never finished (the flight ended while it waited).
"""

from __future__ import annotations

import inspect
import json
import re

import pytest

from rocketsim.flight.fc import FlightComputer
from rocketsim.flight.program import ProgramError
from rocketsim.scenario.load import load
from rocketsim.api.telemetry_flight import fly_to_file as fly
from tests.conftest import ROOT, VEHICLE

DOC = ROOT / "docs" / "fc.md"
MEMBERS = sorted(name for name in dir(FlightComputer) if not name.startswith("_"))
MAX_NOT_RUN = 3         # blocks that cannot run in a short flight (each says why)

EPOCH = "epoch: 2026-11-26T12:00:00Z"
F9 = ROOT / "vehicles" / "falcon9-block5.yaml"
SCENARIOS = {
    # the rigid probe of conftest coasting at 415 km, with a target orbit
    "orbit-probe": ("probe", "vehicle: vehicle.yaml\nmission:\n  " + EPOCH + """
  start: {orbit: {altitude: 415 km, inclination: 51.6 deg}}
  target: {orbit: {altitude: 500 km, inclination: 51.6 deg}}
  duration: 40 s
"""),
    # the probe thrown straight up from an equatorial pad: in the air, then falling back
    "probe-arc": ("probe", """vehicle: vehicle.yaml
site: {name: pad, latitude: 0 deg, longitude: 10 deg, pad_azimuth: 90 deg}
mission:
  """ + EPOCH + """
  start: {site: {elevation: 90 deg, velocity: [0, 0, 2000]}}
  duration: 70 s
"""),
    # the whole Falcon 9 stack in a 700 km orbit, out of the air
    "falcon9-orbit": ("falcon9-block5", f"vehicle: {F9}\nmission:\n  " + EPOCH + """
  start: {orbit: {altitude: 700 km, inclination: 28.5 deg}}
  duration: 20 s
"""),
    # the stack standing on its legs at SLC-40, realistic sensors, a target pad
    "falcon9-pad": ("falcon9-block5", f"vehicle: {F9}\nsensors: realistic\n" + """site:
  name: SLC-40
  latitude: 28.5619 deg
  longitude: -80.5774 deg
  pad_azimuth: 44 deg
  pads: [{name: landing zone, latitude: 28.4858 deg, longitude: -80.5429 deg}]
mission:
  """ + EPOCH + """
  start: {site: {}}
  target: {orbit: {altitude: 400 km, inclination: 51.6 deg}, pad: landing zone}
  duration: 4 s
"""),
    # the hobby rocket on its rail at a desert pad, a solid motor lit at T+0, parachutes
    "hobby-rail": ("hobby-rocket", f"vehicle: {ROOT / 'vehicles' / 'hobby-rocket.yaml'}\n" + """site:
  name: desert pad
  latitude: 32.99 deg
  longitude: -106.975 deg
  height: 1380 m
mission:
  """ + EPOCH + """
  start: {site: {rail: {length: 5.2 m, inclination: 85 deg, heading: 0 deg}}}
  duration: 2 s
"""),
    # a capsule with a heat shield in a 700 km Earth orbit
    "capsule-orbit": ("mars-entry-capsule", f"vehicle: {ROOT / 'vehicles' / 'mars-entry-capsule.yaml'}\n"
                      "mission:\n  " + EPOCH + """
  start: {orbit: {altitude: 700 km, inclination: 28.5 deg}}
  duration: 1 s
"""),
}

PROGRAM = '''\
import json
import traceback

BLOCKS = json.loads({blocks!r})


def main(fc):
    for line, text in BLOCKS:
        code = compile("\\n" * (line - 1) + text, "docs/fc.md", "exec")    # the page's line numbers
        try:
            exec(code, {{"fc": fc, "__name__": "fc_md_example"}})
        except Exception as error:
            lines = [f.lineno for f in traceback.extract_tb(error.__traceback__) if f.filename == "docs/fc.md"]
            message = "".join(traceback.format_exception_only(type(error), error)).strip()
            fc.event("fc.md failed", line=line, at=lines[-1] if lines else line, error=message)
        else:
            fc.event("fc.md ran", line=line)
'''


def _blocks() -> list[dict]:
    """The page's python blocks: ``line`` (of the block's first line), ``text``,
    ``section`` (the ``###`` heading above it), ``runs`` (scenario names) or ``not_run``."""
    found, section, block = [], "", None
    for number, line in enumerate(DOC.read_text(encoding="utf-8").splitlines(), 1):
        if block is not None:
            if line.strip() == "```":
                found.append(block)
                block = None
            else:
                block["lines"].append(line)
        elif line.startswith("### "):
            section = line
        elif line.startswith("## "):
            section = ""
        elif line.strip() == "```python":
            block = {"line": number + 1, "lines": [], "section": section}
    assert block is None, f"docs/fc.md: the block at line {block['line']} is not closed"
    for b in found:
        b["text"] = "\n".join(b.pop("lines")) + "\n"
        first = b["text"].splitlines()[0] if b["text"].strip() else ""
        runs = re.fullmatch(r"# runs on: ([\w\-, ]+)", first)
        not_run = re.fullmatch(r"# not run: (.{10,})", first)
        b["runs"] = [s.strip() for s in runs.group(1).split(",")] if runs else []
        b["not_run"] = not_run.group(1) if not_run else None
    return found


def _heading(name: str) -> str:
    """How the page's heading writes member ``name``: ``fc.name`` for a property,
    ``fc.name(params)`` with the method's own parameters and defaults for a method."""
    member = inspect.getattr_static(FlightComputer, name)
    if isinstance(member, property):
        return f"`fc.{name}`"
    params = []
    for p in list(inspect.signature(member).parameters.values())[1:]:     # without self
        if p.kind is p.VAR_POSITIONAL:
            params.append(f"*{p.name}")
        elif p.kind is p.VAR_KEYWORD:
            params.append(f"**{p.name}")
        elif p.default is p.empty:
            params.append(p.name)
        else:                   # a string default as the page writes it: "eci"
            default = json.dumps(p.default) if isinstance(p.default, str) else repr(p.default)
            params.append(f"{p.name}={default}")
    return f"`fc.{name}({', '.join(params)})`"


def _mentions(text: str, name: str) -> bool:
    return re.search(rf"\bfc\.{re.escape(name)}(?!\w)", text) is not None


def test_every_public_member_has_a_section_with_an_example():
    """Found by introspection: each name of FlightComputer not starting with ``_`` (the
    aliases too) is named in a ``###`` heading, with the method's parameters and defaults
    as they are in the code, and a python block of that section uses it as ``fc.<name>``;
    no heading or example names a member that does not exist."""
    blocks = _blocks()
    headings = {b["section"] for b in blocks}
    missing = []
    for name in MEMBERS:
        mine = [b for b in blocks if _mentions(b["section"], name) and _mentions(b["text"], name)]
        if not mine:
            missing.append(name)
    assert not missing, f"docs/fc.md has no section with an example for: {', '.join(missing)}"
    stale = [_heading(name) for name in MEMBERS if not any(_heading(name) in h for h in headings)]
    assert not stale, f"docs/fc.md: no heading gives the member as it is now: {', '.join(stale)}"
    used = {m for b in blocks for m in re.findall(r"\bfc\.([A-Za-z_]\w*)", b["text"])}
    used |= {m for h in headings for m in re.findall(r"\bfc\.([A-Za-z_]\w*)", h)}
    unknown = sorted(used - set(MEMBERS))
    assert not unknown, f"docs/fc.md uses calls FlightComputer does not have: {', '.join(unknown)}"


def test_every_block_compiles_and_says_where_it_runs():
    """Every python block compiles, and is marked with the scenarios that run it (known
    ones) or why none can; at most a few are not run."""
    blocks = _blocks()
    assert len(blocks) >= len(MEMBERS)
    for b in blocks:
        compile("\n" * (b["line"] - 1) + b["text"], "docs/fc.md", "exec")
        assert b["runs"] or b["not_run"], f"docs/fc.md:{b['line']}: no '# runs on:' or '# not run:' line"
        unknown = set(b["runs"]) - set(SCENARIOS)
        assert not unknown, f"docs/fc.md:{b['line']}: unknown scenario {sorted(unknown)}"
    not_run = [b for b in blocks if b["not_run"]]
    assert len(not_run) <= MAX_NOT_RUN, [f"docs/fc.md:{b['line']}: {b['not_run']}" for b in not_run]
    assert all(any(kind in b["runs"] for b in blocks) for kind in SCENARIOS)


@pytest.mark.parametrize("kind", list(SCENARIOS))
def test_the_examples_run(kind, write, tmp_path):
    """Flies ``kind`` with one program running all its blocks in the page's order; every
    block must finish without raising."""
    body, text = SCENARIOS[kind]
    blocks = [b for b in _blocks() if kind in b["runs"]]
    write("vehicle.yaml", VEHICLE)
    write("program.py", PROGRAM.format(blocks=json.dumps([(b["line"], b["text"]) for b in blocks])))
    path = write("scenario.yaml", f"name: {kind}\nprogram: program.py\nprogram_cpu_budget: 10 s\n" + text)
    try:
        summary = fly(load(path), tmp_path / "run.mcap")
    except ProgramError as error:
        pytest.fail(f"{kind}: the flight stopped: {error}")
    events = summary["bodies"][body]["events"]
    ran = {e["line"] for e in events if e["name"] == "fc.md ran"}
    failed = {e["line"]: e for e in events if e["name"] == "fc.md failed"}
    problems = []
    for b in blocks:
        if b["line"] in failed:
            e = failed[b["line"]]
            problems.append(f"docs/fc.md:{e['at']} ({b['section']}) raised {e['error']}\n{b['text']}")
        elif b["line"] not in ran:
            problems.append(f"docs/fc.md:{b['line']} ({b['section']}) did not finish in the flight\n{b['text']}")
    assert not problems, f"{kind}:\n" + "\n".join(problems)
