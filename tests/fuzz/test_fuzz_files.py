"""Mutated scenario, vehicle, site, mission and weather files: they fly, or exit 2 at file:line.

Hypothesis starts from three sets of files that fly (the conftest probe in
orbit with an inline sounding; an Electron from Mahia with a site file, a
weather file (a random day) and a payload; the Falcon 9 stack in orbit, with its grid fins,
legs and RCS; the Electron's mission names a target orbit, a landing pad and its
gravity model) and changes one to four things in them: drops a field or an
item, replaces a value by one from a hostile alphabet (nan, inf, -0, 1e308,
10**400, empty, long and unicode strings, numbers with units and without,
bools, None, lists, mappings nested 60 deep), renames or duplicates a field,
or edits the text (a line repeated, which duplicates its key; cut short; an
anchor and aliases). ``rocketsim validate`` must then say ok or exit 2 naming
a file and line, and a file that validates must fly 0.1 s or exit 2 with a
message: never a traceback, a hang or a gigabyte.
"""

from __future__ import annotations

import copy
import re
from fractions import Fraction
import tempfile
from pathlib import Path

import yaml
from hypothesis import given, settings, strategies as st

from tests.conftest import MISSION, ROOT, VEHICLE
from tests.fuzz.harness import AT_LINE, bounded, examples, invoke, write_files


def _load(path: Path):
    return yaml.safe_load(path.read_text())


CASES = {
    "probe": {
        "scenario.yaml": {"name": "probe", "vehicle": "vehicle.yaml", "mission": "mission.yaml",
                          "step": "0.02 s", "seed": 3, "telemetry": {"rate": "10 Hz"},
                          "weather": {"kind": "sounding", "columns": {
                              "PRES": [1000, 850, 700], "HGHT": [100, 1500, 3000], "TEMP": [20.0, 12.5, 2.0]}}},
        "vehicle.yaml": yaml.safe_load(VEHICLE),
        "mission.yaml": yaml.safe_load(MISSION.format(duration="10 s")),
    },
    "electron": {
        "scenario.yaml": {"name": "electron", "vehicle": "electron.yaml", "site": "site.yaml",
                          "weather": "weather.yaml",
                          "payload": {"name": "smallsat", "mass": "100 kg", "length": "0.8 m",
                                      "diameter": "0.6 m"},
                          "mission": {"epoch": "2026-11-26T15:00:00Z", "start": {"site": {}},
                                      "duration": "460 s",
                                      "target": {"orbit": {"altitude": "500 km", "inclination": "sso"},
                                                 "pad": {"name": "barge", "latitude": "-39.4 deg",
                                                         "longitude": "178.5 deg"}},
                                      "gravity": "earth"}},
        "electron.yaml": _load(ROOT / "vehicles" / "electron.yaml"),
        "site.yaml": _load(ROOT / "scenarios" / "sites" / "mahia-lc1.yaml"),
        "weather.yaml": {"kind": "random", "seed": 7},
    },
    "falcon9": {
        "scenario.yaml": {"name": "falcon9", "vehicle": "falcon9.yaml", "sensors": "realistic",
                          "mission": {"epoch": "2026-11-26T12:00:00Z",
                                      "start": {"orbit": {"altitude": "700 km", "inclination": "28.5 deg"}},
                                      "duration": "20 s"}},
        "falcon9.yaml": _load(ROOT / "vehicles" / "falcon9-block5.yaml"),
    },
}

_NUMBERS = [float("nan"), float("inf"), -float("inf"), -0.0, 0, 1, -1, 1e308, -1e308, 5e-324, 10**400, 2**63]
_UNITS = ["", "m", "km", "kg", "t", "s", "h", "deg", "rad", "m/s", "kN", "Pa", "bar", "K", "C", "Hz",
          "kg/s", "%", "g", "parsecs", "km km", "\u00b0", "deg/s"]
HOSTILE = st.one_of(
    st.sampled_from(_NUMBERS),
    st.sampled_from(["", " ", "x" * 70_000, "\u540d\u524d", "\u202e", "\U0001f680", "~", "null", "yes",
                     "nan", "sso", "classic", "../vehicle.yaml", "no/such/file.yaml", "/dev/zero",
                     "2026-13-45T99:00:00Z", "1969-07-16T13:32:00Z", "9" * 400 + " m"]),
    st.builds(lambda n, u: f"{n} {u}".strip(), st.sampled_from(["nan", "inf", "-0", "1e308", "1e-320", "-5",
                                                                 "0", "42", "31", "-300", "1e6"]),
              st.sampled_from(_UNITS)),
    st.none(), st.booleans(), st.just([]), st.just({}),
    st.floats(), st.integers(), st.text(max_size=12),
    st.integers(1, 60).map(lambda n: _nested([], n)),
    st.integers(1, 60).map(lambda n: _nested({}, n)),
    st.just(list(range(5000))),
)


def _nested(inner, depth: int):
    for _ in range(depth):
        inner = [inner] if isinstance(inner, list) else {"k": inner}
    return inner


def _places(tree):
    """Every place in ``tree`` (a path of keys and indices), the root excluded, in order."""
    places, stack = [], [(tree, ())]
    while stack:
        node, loc = stack.pop()
        items = node.items() if isinstance(node, dict) else enumerate(node) if isinstance(node, list) else ()
        children = [(value, loc + (key,)) for key, value in items]
        places.extend(child for _, child in children)
        stack.extend(reversed(children))
    return places


def _parent(tree, loc):
    for part in loc[:-1]:
        tree = tree[part]
    return tree


@st.composite
def mutated(draw) -> tuple[str, dict[str, str]]:
    """A case's name and its files' texts, one to four things changed."""
    case = draw(st.sampled_from(["probe", "probe", "electron", "falcon9"]))   # the probe is quickest
    return case, mutate(draw, CASES[case])


def mutate(draw, files: dict) -> dict[str, str]:
    """The texts of ``files`` (name -> YAML data), one to four things changed in them."""
    files = copy.deepcopy(files)
    texts: dict[str, str] = {}
    for _ in range(draw(st.sampled_from([1, 1, 1, 2, 2, 3, 4]))):
        name = draw(st.sampled_from(sorted(files)))
        tree = files[name]
        places = _places(tree)
        kind = draw(st.sampled_from(["nearby", "nearby", "nearby", "drop", "replace", "replace", "rename",
                                     "duplicate", "text"]))
        if kind == "text" or not places:
            texts[name] = _edit_text(draw, yaml.safe_dump(tree, allow_unicode=True, sort_keys=False))
            continue
        loc = draw(st.sampled_from(places))
        parent, key = _parent(tree, loc), loc[-1]
        if kind == "drop":
            del parent[key]
        elif kind == "replace":
            parent[key] = copy.deepcopy(draw(HOSTILE))      # st.just gives the same object each time
        elif kind == "nearby":
            parent[key] = _nearby(draw, parent[key])
        elif isinstance(parent, dict) and kind == "rename":
            parent[draw(st.sampled_from([f"{key}x", str(key)[:-1], str(key).upper(), 7, "<<"]))] = parent.pop(key)
        elif isinstance(parent, dict):
            parent[f"{key}_2"] = copy.deepcopy(parent[key])
        else:
            parent.insert(key, copy.deepcopy(parent[key]))
        texts.pop(name, None)
    return {name: texts.get(name) or yaml.safe_dump(data, allow_unicode=True, sort_keys=False, width=4096)
            for name, data in files.items()}


_QUANTITY = re.compile(r"^\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*(.*?)\s*$")
_FACTORS = [0, -1, 1e-6, 1e-3, 0.5, 1.5, 1e3, 1e6, 1e300]


def _nearby(draw, value):
    """``value`` changed the way a careless edit changes it: a number scaled, zeroed or
    negated (its unit kept), a list or mapping one item short or long, a name misspelt."""
    if isinstance(value, bool):
        return not value
    if isinstance(value, int):          # exact: an integer of 400 digits (10**400) scales too
        changed = value * Fraction(draw(st.sampled_from(_FACTORS)))
        if abs(changed) < 2**63:
            return int(changed)
        try:
            return float(changed)
        except OverflowError:           # beyond a float: stays an integer
            return int(changed)
    if isinstance(value, float):
        return value * draw(st.sampled_from(_FACTORS))
    if isinstance(value, str):
        quantity = _QUANTITY.match(value)
        if quantity:
            number = float(quantity.group(1)) * draw(st.sampled_from(_FACTORS))
            return f"{number!r} {draw(st.sampled_from([quantity.group(2)] * 3 + _UNITS))}".strip()
        return draw(st.sampled_from([value + "x", value.upper(), value[:-1], value * 2]))
    if isinstance(value, list) and value:
        i = draw(st.integers(0, len(value) - 1))
        return value[:i] + value[i + 1:] if draw(st.booleans()) else value[:i] + [value[i]] + value[i:]
    if isinstance(value, dict) and value:
        drop = draw(st.sampled_from(sorted(value, key=str)))
        return {k: v for k, v in value.items() if k != drop}
    return value


def _edit_text(draw, text: str) -> str:
    lines = text.splitlines(keepends=True) or ["\n"]
    at = draw(st.integers(0, len(lines) - 1))
    kind = draw(st.sampled_from(["repeat", "cut", "anchor", "char"]))
    if kind == "repeat":                # the same key twice in a mapping
        lines.insert(at, lines[at])
    elif kind == "cut":
        lines = lines[:at] + [lines[at][:draw(st.integers(0, len(lines[at])))]]
    elif kind == "anchor":
        lines = ["x: &x [1, 2, 3]\n"] + lines[:at] + [lines[at].rstrip("\n") + " *x\n"] + lines[at + 1:]
    else:
        line = lines[at]
        i = draw(st.integers(0, len(line)))
        lines[at] = line[:i] + draw(st.sampled_from(list(":-[]{}&*!|>'\"%@`#,? \t\u00a0\ufeff"))) + line[i:]
    return "".join(lines)


@settings(max_examples=examples(8))
@given(mutated())
def test_a_mutated_file_flies_or_is_refused_at_its_line(case_files):
    case, files = case_files
    with tempfile.TemporaryDirectory() as folder:
        folder = Path(folder)
        write_files(folder, files)
        with bounded("files"):
            code, output = invoke("validate", folder / "scenario.yaml")
            assert code in (0, 2), output
            if code == 2:
                assert AT_LINE.search(output), output
                return
            code, output = invoke("fly", folder / "scenario.yaml", "-o", folder / "run.mcap",
                                  "--duration", "0.1")
        assert code == 0 or (code == 2 and AT_LINE.search(output)), output


def test_a_careless_edit_scales_an_integer_beyond_a_float_exactly():
    # found by the long profile: the generator itself overflowed scaling 10**400 (a value
    # an earlier change had put there) by a float factor
    scaled = {_nearby(lambda strategy: factor, 10**400) for factor in _FACTORS}
    assert 0 in scaled and -10**400 in scaled and 10**400 * 1000 in scaled
    assert _nearby(lambda strategy: 0.5, 7) == 3 and _nearby(lambda strategy: 1e6, 2**62) == 2.0**62 * 1e6
