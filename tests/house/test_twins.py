"""Every decision of the Python side after a step has a compiled twin in each run, or a reason.

The decisions are read from the source of ``rocketsim/sim/`` (nothing is
imported to find them), independently of the map they are checked against
(:data:`rocketsim.stepping.twins.TWINS`):

* every event the world records: each call ``<x>.event(body, name, figures)``
  or ``<x>.end_flight(body, name, figures)`` (the world's: the event, then the
  body's flight ends), its name the string it is given, or the strings assigned
  to the name it is given in the same function; a name given by the caller (a
  parameter) counts as a decision of that function, except in ``end_flight``,
  which passes its caller's on (the decision is read at each call);
* every stop with no event of its own: a ``raise InputError(...)`` (or of its
  subclass ``ArgumentError``), and a ``<body>.flying = False`` that no recorded
  event precedes in its block or the blocks around it.

A decision missing from the map, one in the map whose function no longer makes
it, a twin whose docstring does not name the Python function it mirrors, a test
of :mod:`rocketsim.stepping.quiet` that is nobody's twin and a compiled run with
no column in the map all fail, each named; so do a planted event and a planted
stop without a twin.
"""

from __future__ import annotations

import ast
import importlib
import shutil
from pathlib import Path

from rocketsim.jit import Kernel
from rocketsim.stepping import quiet, runs
from rocketsim.stepping.twins import TWINS, Twin

ROOT = Path(__file__).resolve().parents[2]
SIM = ROOT / "rocketsim" / "sim"
RUNS = Twin._fields[1:]
INPUT_ERRORS = ("InputError", "ArgumentError")     # raising one stops the flight on bad input
RECORDS = ("event", "end_flight")       # a call of either records the event it names
# the functions that record the event their caller names, read at each call (not a decision of their own)
RELAYS = ("world.World.end_flight",)


def _functions(tree: ast.AST, prefix: str = ""):
    """``(qualified name, node)`` of every function in ``tree``, nested ones included."""
    for child in ast.iter_child_nodes(tree):
        if isinstance(child, (ast.FunctionDef, ast.AsyncFunctionDef)):
            yield prefix + child.name, child
            yield from _functions(child, prefix + child.name + ".")
        elif isinstance(child, ast.ClassDef):
            yield from _functions(child, prefix + child.name + ".")
        else:
            yield from _functions(child, prefix)


def _own(node: ast.AST):
    """The nodes of a function's body, not those of the functions and classes it defines."""
    for child in ast.iter_child_nodes(node):
        if not isinstance(child, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            yield child
            yield from _own(child)


def _records(node: ast.AST) -> bool:
    """Whether ``node`` is a call that records an event: ``<x>.event(body, name, figures)``
    or ``<x>.end_flight(body, name, figures)``."""
    return (isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) and node.func.attr in RECORDS
            and len(node.args) == 3 and not node.keywords
            and not any(isinstance(a, ast.Starred) for a in node.args))


def _strings(value: ast.expr) -> list[str]:
    """The strings an expression can evaluate to: a string, either branch of ``a if c
    else b`` or ``a or b``, a dictionary's values and a ``.get`` of one with its default;
    none for anything else."""
    if isinstance(value, ast.Constant) and isinstance(value.value, str):
        return [value.value]
    if isinstance(value, ast.IfExp):
        return _strings(value.body) + _strings(value.orelse)
    if isinstance(value, ast.BoolOp):
        return [s for v in value.values for s in _strings(v)]
    if isinstance(value, ast.Dict):
        return [s for v in value.values for s in _strings(v)]
    if isinstance(value, ast.Call) and isinstance(value.func, ast.Attribute) and value.func.attr == "get":
        return _strings(value.func.value) + [s for v in value.args[1:2] for s in _strings(v)]
    return []


def _event_names(name: ast.expr, nodes: list[ast.AST]) -> list[str]:
    """The names an event call's ``name`` argument can take: the string itself, or the
    strings assigned to that variable in the function (:func:`_strings`); none when the
    caller gives it, or when they cannot be read."""
    if not isinstance(name, ast.Name):
        return _strings(name)
    return [s for node in nodes if isinstance(node, ast.Assign)
            and any(isinstance(t, ast.Name) and t.id == name.id for t in node.targets)
            for s in _strings(node.value)]


def _relayed(site: str, function: ast.AST, name: ast.expr) -> bool:
    """Whether the event's ``name`` in the function ``site`` is one of :data:`RELAYS` passing
    on its parameter: the decision is its caller's, read at the call."""
    return site in RELAYS and isinstance(name, ast.Name) and name.id in {a.arg for a in function.args.args}


def _ends_flight(node: ast.AST) -> bool:
    """``<body>.flying = False``."""
    return (isinstance(node, ast.Assign) and isinstance(node.value, ast.Constant) and node.value.value is False
            and any(isinstance(t, ast.Attribute) and t.attr == "flying" for t in node.targets))


def _raises_input_error(node: ast.AST) -> bool:
    """``raise InputError(...)`` or ``ArgumentError(...)``: the flight stops with the error of bad input."""
    if not (isinstance(node, ast.Raise) and isinstance(node.exc, ast.Call)):
        return False
    called = node.exc.func
    return (called.id if isinstance(called, ast.Name) else getattr(called, "attr", None)) in INPUT_ERRORS


def _silent_ends(body: list[ast.stmt], recorded: bool = False):
    """The ``flying = False`` statements of the block ``body`` (and the blocks in it) that
    no event recorded earlier in the block, or in a block around it, precedes."""
    for statement in body:
        if isinstance(statement, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            continue                # a function of its own
        if _ends_flight(statement) and not recorded:
            yield statement
        blocks = [getattr(statement, field) for field in ("body", "orelse", "finalbody")
                  if isinstance(getattr(statement, field, None), list)]
        blocks += [handler.body for handler in getattr(statement, "handlers", [])]
        if blocks:                  # an event in one branch precedes nothing after the statement
            for block in blocks:
                yield from _silent_ends(block, recorded)
        elif any(_records(node) for node in ast.walk(statement)):
            recorded = True


def python_decisions(sim: Path) -> dict[str, dict[str, str]]:
    """``{decision: {function: where}}`` of the Python side in the folder ``sim``: each
    decision (an event's name; a stop, or an event named by its caller, by its function)
    with the functions (``module.qualified name``) that make it and where (``file:line``)."""
    found: dict[str, dict[str, str]] = {}
    for path in sorted(sim.glob("*.py")):
        tree = ast.parse(path.read_text(), str(path))
        for qualified, function in _functions(tree):
            site = f"{path.stem}.{qualified}"
            nodes = list(_own(function))
            for node in nodes:
                if _records(node) and not _relayed(site, function, node.args[1]):
                    for name in _event_names(node.args[1], nodes) or [site]:
                        found.setdefault(name, {}).setdefault(site, f"{path.name}:{node.lineno}")
                elif _raises_input_error(node):
                    found.setdefault(site, {}).setdefault(site, f"{path.name}:{node.lineno}")
            for node in _silent_ends(function.body):
                found.setdefault(site, {}).setdefault(site, f"{path.name}:{node.lineno}")
    return found


def problems(decisions: dict[str, dict[str, str]], twins: dict[str, Twin]) -> list[str]:
    """What does not match between the Python side's ``decisions`` and the map ``twins``."""
    found = []
    for decision, sites in sorted(decisions.items()):
        where = ", ".join(f"{site} ({line})" for site, line in sorted(sites.items()))
        twin = twins.get(decision)
        if twin is None:
            found.append(f"{decision!r}, made in {where}, has no compiled twin in rocketsim.stepping.twins "
                         "(nor a reason why no run needs one)")
        elif {"rocketsim.sim." + site for site in sites} != {twin.python}:
            found.append(f"{decision!r} is made in {where}, not in {twin.python} as rocketsim.stepping.twins says")
    for decision in sorted(set(twins) - set(decisions)):
        found.append(f"{decision!r} is in rocketsim.stepping.twins but no longer made by the Python side")
    return found


def test_every_decision_of_the_python_side_has_a_twin_or_a_reason():
    decisions = python_decisions(SIM)
    found = problems(decisions, TWINS)
    assert not found, "\n".join(found)
    # what the reading finds: the events of the checks and of the flight events, the stops
    assert {"liftoff", "max_q", "MECO", "orbit", "breakup", "touchdown", "tip-over", "impact"} <= set(decisions)
    assert set(decisions["world.World.check_finite"]) == {"world.World.check_finite"}


def test_each_twin_names_the_python_function_it_mirrors():
    named = []
    for decision, twin in TWINS.items():
        assert callable(_resolved(twin.python)), twin.python
        name = ".".join(twin.python.split(".")[-2:])
        for run in RUNS:
            kernel = getattr(twin, run)
            if isinstance(kernel, str):
                assert len(kernel) > 20, f"{decision} in {run}: a reason, in a sentence"
                continue
            assert isinstance(kernel, Kernel) and kernel.__module__.startswith("rocketsim.stepping."), kernel
            assert name in kernel.__doc__, f"{kernel.__qualname__} does not name {name}, whose twin it is"
            named.append(kernel)
    # every test of the quiet module is somebody's twin
    tests = {value for value in vars(quiet).values()
             if isinstance(value, Kernel) and value.__module__ == quiet.__name__}
    assert tests and tests <= set(named), f"not in rocketsim.stepping.twins: {tests - set(named)}"


def _resolved(dotted: str):
    """The object a dotted path names: a module's function or a class's method."""
    parts = dotted.split(".")
    for end in range(len(parts) - 1, 0, -1):
        try:
            found = importlib.import_module(".".join(parts[:end]))
        except ModuleNotFoundError:
            continue
        for part in parts[end:]:
            found = getattr(found, part)
        return found
    raise LookupError(dotted)


def test_every_compiled_run_has_a_column():
    kernels = {name for name, value in vars(runs).items() if isinstance(value, Kernel)
               and value.__module__ == runs.__name__ and not name.startswith("_")}
    assert kernels == set(RUNS)


def _planted(tmp_path: Path, module: str, old: str, new: str) -> Path:
    """A copy of ``rocketsim/sim`` with ``old`` replaced by ``new`` in ``module``."""
    sim = tmp_path / "sim"
    shutil.copytree(SIM, sim, ignore=shutil.ignore_patterns("__pycache__"))
    text = (sim / module).read_text()
    assert text.count(old) == 1
    (sim / module).write_text(text.replace(old, new))
    return sim


def test_a_planted_event_without_a_twin_is_named(tmp_path):
    # a new event recorded beside off_rail, its name given through a variable
    sim = _planted(tmp_path, "flight_events.py", '        self.world.event(self.body, "off_rail", figures)\n',
                   '        self.world.event(self.body, "off_rail", figures)\n'
                   '        name = "fins stalled" if figures["speed_m_s"] < 1.0 else "fins flying"\n'
                   '        self.world.event(self.body, name, {})\n')
    found = problems(python_decisions(sim), TWINS)
    assert len(found) == 2, found
    assert found[0].startswith("'fins flying', made in flight_events.FlightEvents._off_rail (flight_events.py:")
    assert found[1].startswith("'fins stalled', made in flight_events.FlightEvents._off_rail")
    assert all("has no compiled twin" in line for line in found)


def _with_check(tmp_path: Path, method: str) -> list[str]:
    """:func:`problems` of a copy of ``rocketsim/sim`` with the method ``method`` (its
    source) planted in :class:`~rocketsim.sim.vehicle_checks.VehicleChecks`."""
    anchor = "    def _tip_over_angle(self, body) -> float:\n"
    return problems(python_decisions(_planted(tmp_path, "vehicle_checks.py", anchor, method + "\n" + anchor)), TWINS)


def test_a_planted_stop_without_a_twin_is_named(tmp_path):
    # a check that ends the flight with no event: a new stop of its function
    found = _with_check(tmp_path, "    def _overheated(self, body) -> None:\n"
                                  "        if self.temperature > 3000.0:\n"
                                  "            body.flying = False\n")
    assert len(found) == 1 and found[0].startswith("'vehicle_checks.VehicleChecks._overheated', made in "
                                                   "vehicle_checks.VehicleChecks._overheated (vehicle_checks.py:")


def test_an_event_recorded_elsewhere_or_gone_is_named(tmp_path):
    # orbit recorded by another function than the map's; max_q no longer recorded
    sim = _planted(tmp_path, "flight_events.py", '"max_q", {"dynamic_pressure_Pa"',
                   '"max_q_passed", {"dynamic_pressure_Pa"')
    found = problems(python_decisions(sim), TWINS)
    assert "'max_q' is in rocketsim.stepping.twins but no longer made by the Python side" in found
    moved = dict(TWINS, orbit=TWINS["orbit"]._replace(python="rocketsim.sim.world.World.after_advance"))
    found = problems(python_decisions(SIM), moved)
    assert len(found) == 1 and found[0].startswith("'orbit' is made in flight_events.FlightEvents._orbit")


def test_an_event_that_ends_a_flight_is_read_where_it_is_named(tmp_path):
    # a check ending the flight through the world's end_flight: its event is the check's
    found = _with_check(tmp_path, "    def _overheated(self, world, body) -> None:\n"
                                  "        world.end_flight(body, \"overheated\", {})\n")
    assert len(found) == 1 and found[0].startswith("'overheated', made in vehicle_checks.VehicleChecks._overheated "
                                                   "(vehicle_checks.py:")
    # end_flight ending the flight with no event: a stop of its own
    sim = _planted(tmp_path / "silent", "world.py", "        self.event(body, name, figures)\n        body.flying",
                   "        body.flying")
    found = problems(python_decisions(sim), TWINS)
    assert len(found) == 1 and found[0].startswith("'world.World.end_flight', made in world.World.end_flight")
