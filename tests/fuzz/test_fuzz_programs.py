"""Generated flight programs calling fc with hostile arguments: finished, or a program error.

Hypothesis writes programs of up to six fc calls (every public method, with
the arity of its signature or a wrong one) separated by steps, reading
properties in between, with arguments from a hostile alphabet: nan, inf,
-0, 1e308, 10**400, bools, None, strings (empty, long, unicode, a mode or an
engine's name), vectors of every length, numpy scalars and arrays, functions
returning anything, objects. Each program flies 0.1 s on one of three bodies:
the conftest probe (no engines), the Falcon 9 stack in orbit and standing on
its pad (engines, RCS, grid fins, legs, fairing, payload). The flight must
finish (exit 0) or stop with a program error naming a line of the program
(exit 2, ``program.py:<line>:``): never a traceback, a numba error, a hang.

Each body is flown once before the generated programs (:func:`warm`), outside
the watchdog and the memory bound: the kernels its flight needs are compiled or
loaded then, so an input's time and memory are its own, whatever the state of
the kernel cache or the load of the machine: compiling Falcon 9's kernels on a
cold cache inside an input took longer than the watchdog allows.
"""

from __future__ import annotations

import inspect
import re
import tempfile
from pathlib import Path

import pytest
from hypothesis import given, settings, strategies as st

from rocketsim.flight.fc import FlightComputer
from tests.conftest import ROOT, VEHICLE
from tests.fuzz.harness import bounded, examples, invoke

EPOCH = "epoch: 2026-11-26T12:00:00Z"
F9 = ROOT / "vehicles" / "falcon9-block5.yaml"
BODIES = {
    "probe": "vehicle: vehicle.yaml\nmission:\n  " + EPOCH + """
  start: {orbit: {altitude: 415 km, inclination: 51.6 deg}}
  duration: 0.1 s
""",
    "falcon9-orbit": f"vehicle: {F9}\nmission:\n  " + EPOCH + """
  start: {orbit: {altitude: 700 km, inclination: 28.5 deg}}
  duration: 0.1 s
""",
    "falcon9-pad": f"vehicle: {F9}\nsensors: realistic\n" + """site:
  {name: SLC-40, latitude: 28.5619 deg, longitude: -80.5774 deg, pad_azimuth: 44 deg}
mission:
  """ + EPOCH + """
  start: {site: {}}
  duration: 0.1 s
""",
}

_PUBLIC = {name: member for name, member in inspect.getmembers(FlightComputer) if not name.startswith("_")}
METHODS = {name: [p for p in list(inspect.signature(member).parameters.values())[1:]
                  if p.kind is not inspect.Parameter.VAR_KEYWORD]
           for name, member in sorted(_PUBLIC.items()) if inspect.isfunction(member)}
PROPERTIES = sorted(name for name, member in _PUBLIC.items() if isinstance(member, property))

# Python source of hostile values
HOSTILE = [
    "float('nan')", "float('inf')", "-float('inf')", "-0.0", "0", "1", "-1", "0.5", "1e308", "-1e308",
    "5e-324", "10**400", "2**63", "True", "False", "None", "''", "'x'", "'x' * 70000", "'\\u540d\\u524d'",
    "'\\u202e'", "'prograde'", "'retrograde'", "'local'", "'eci'", "'moon'", "'booster'", "'second stage'",
    "'Merlin 1D centre'", "[]", "[1.0]", "[1.0, 0.0]", "[1.0, 0.0, 0.0]", "[0.0, 0.0, 0.0]",
    "[float('nan'), 0.0, 0.0]", "[1e308, 1e308, 1e308]", "[[1.0]] * 3", "['a', 'b', 'c']",
    "(0, 'booster', 99)", "[True]", "{}", "{'a': 1}", "np.float32(0.5)", "np.int64(-3)",
    "np.bool_(True)", "np.zeros(3)", "np.ones(4)", "np.array(2.0)", "np.array([1.0, 2.0, 3.0])",
    "np.full(3, np.nan)", "lambda: None", "lambda: True", "lambda: False", "lambda: fc.altitude",
    "lambda: 1 / 0", "lambda: np.bool_(False)", "lambda x: x", "print", "object()", "fc", "math.pi",
    "3 * math.pi", "-math.pi / 2", "b'bytes'", "1j", "range(3)", "Ellipsis",
]
KEYWORDS = ["roll", "frame", "which", "at", "delta_v", "periapsis", "fold", "altitude_m", "time_s", "phase"]

_FLOAT = st.floats(allow_nan=False, allow_infinity=False).map(repr)
_SMALL = st.floats(-10.0, 10.0).map(repr)
_VECTOR = st.lists(st.one_of(_SMALL, _FLOAT), min_size=3, max_size=3).map(lambda v: f"[{', '.join(v)}]")
# values a parameter of that name takes in a sensible program, to reach past the first
# check: boundary and extreme values that are accepted, and names the vehicles have
PLAUSIBLE = {
    "seconds": st.one_of(_SMALL.map(lambda x: x.lstrip("-")), st.sampled_from(
        ["0.0", "1e-300", "3155760000.0", "86400.0", "1e9"])),
    "pitch": st.one_of(_SMALL, st.sampled_from(["math.pi / 2", "-math.pi / 2", "math.radians(90.0)"])),
    "heading": st.one_of(_SMALL, st.sampled_from(["4 * math.pi", "-4 * math.pi"])),
    "roll": st.one_of(_SMALL, st.sampled_from(["None", "4 * math.pi"])),
    "vector": st.one_of(_VECTOR, st.sampled_from(["fc.prograde", "fc.radial", "-fc.air_velocity",
                                                  "np.array([5e-324, 0.0, 0.0])"])),
    "delta_v": st.one_of(_VECTOR, st.sampled_from(["None", "10.0 * fc.prograde", "[1e5, 0.0, 0.0]"])),
    "mode": st.sampled_from(["'prograde'", "'retrograde'", "'surface_prograde'", "'surface_retrograde'",
                             "'normal'", "'antinormal'", "'radial'", "'antiradial'"]),
    "frame": st.sampled_from(["'eci'", "'local'"]),
    "which": st.sampled_from(["None", "0", "8", "9", "'booster'", "'second stage'", "'Merlin 1D ring'",
                              "'booster/Merlin 1D ring/3'", "['booster', 9]", "()", "np.int64(1)"]),
    "value": st.one_of(_SMALL, _FLOAT, st.sampled_from(["0.0", "1.0", "-0.0", "1e308"])),
    "on": st.sampled_from(["True", "False", "np.bool_(True)"]),
    "periapsis": st.sampled_from(["True", "False"]),
    "fold": st.sampled_from(["True", "False"]),
    "predicate": st.sampled_from(["lambda: fc.altitude > 1e5", "lambda: fc.time > 0.05",
                                  "lambda: np.bool_(fc.mass > 0)", "lambda: False"]),
    "name": st.sampled_from(["'sun'", "'earth'", "'moon'", "'mars'", "'marker'", "''"]),
    "at": st.one_of(_FLOAT, st.sampled_from(["None", "fc.time", "-3155760000.0"])),
    "parts": st.sampled_from(["'altitude'", "fc.altitude", "fc.engines", "fc.orbit"]),
    "reading": st.sampled_from(["'altitude'", "'vertical_speed'", "'propellant'"]),
    "stage": st.sampled_from(["None", "'booster'", "'second stage'", "'payload'"]),
    "start": st.sampled_from(["None", "0.0", "33e3", "1e308"]),
    "end": st.sampled_from(["None", "49.5e3", "33e3", "1e308"]),
    "a": st.one_of(_SMALL, st.sampled_from(["1e308", "-1e308"])),
    "b": st.one_of(_SMALL, st.sampled_from(["1e308", "-1e-3"])),
    "cross": st.one_of(_SMALL, st.sampled_from(["1000.0", "-1000.0"])),
}


def _value(draw, parameter: str | None = None) -> str:
    if parameter in PLAUSIBLE and draw(st.integers(0, 9)) < 7:
        return draw(PLAUSIBLE[parameter])
    if draw(st.integers(0, 4)) == 0:
        return draw(_FLOAT)
    return draw(st.sampled_from(HOSTILE))


@st.composite
def calls(draw) -> str:
    """One line of a program: an fc call with hostile arguments, or a read of a property."""
    if draw(st.integers(0, 5)) == 0:
        return f"fc.log(fc.{draw(st.sampled_from(PROPERTIES))})"
    name = draw(st.sampled_from(sorted(METHODS)))
    parameters = METHODS[name]
    if parameters and parameters[0].kind is inspect.Parameter.VAR_POSITIONAL:
        arguments = [_value(draw, "parts") for _ in range(draw(st.integers(0, 3)))]
        optional = []
    else:
        required = [p.name for p in parameters if p.default is inspect.Parameter.empty]
        optional = [p.name for p in parameters if p.default is not inspect.Parameter.empty]
        n = len(required) if draw(st.integers(0, 9)) else draw(st.integers(0, 4))   # a wrong arity
        names = (required + optional + [None] * 4)[:n]
        arguments = [_value(draw, names[i]) for i in range(n)]
        optional = optional[max(0, n - len(required)):]
    keywords = KEYWORDS if draw(st.integers(0, 9)) == 0 else optional     # now and then a wrong one
    for keyword in draw(st.lists(st.sampled_from(keywords), max_size=2, unique=True)) if keywords else []:
        arguments.append(f"{keyword}={_value(draw, keyword)}")
    return f"fc.{name}({', '.join(arguments)})"


@st.composite
def programs(draw) -> str:
    lines = []
    for call in draw(st.lists(calls(), min_size=1, max_size=6)):
        lines.append(call)
        lines.extend(["fc.step()"] * draw(st.integers(0, 2)))
    return "import math\nimport numpy as np\n\n\ndef main(fc):\n" + "".join(f"    {line}\n" for line in lines)


def _fly(body: str, program: str) -> tuple[int, str]:
    with tempfile.TemporaryDirectory() as folder:
        folder = Path(folder)
        (folder / "vehicle.yaml").write_text(VEHICLE)
        (folder / "program.py").write_text(program)
        (folder / "scenario.yaml").write_text(f"name: fuzz\nprogram: program.py\n{BODIES[body]}")
        return invoke("fly", folder / "scenario.yaml", "-o", folder / "run.mcap")


@pytest.fixture(scope="module")
def warm():
    """Each body flown once with a program that steps (its kernels compiled or loaded)."""
    for body in BODIES:
        code, output = _fly(body, "def main(fc):\n    fc.step()\n")
        assert code == 0, output


@settings(max_examples=examples(6))
@given(body=st.sampled_from(["probe", "probe", "falcon9-orbit", "falcon9-pad"]), program=programs())
def test_a_generated_program_finishes_or_stops_with_a_program_error(warm, body, program):
    with bounded("programs"):
        code, output = _fly(body, program)
    assert code == 0 or (code == 2 and re.search(r"program\.py:\d+: ", output)), output
