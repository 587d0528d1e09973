"""The library's layers hold: no module imports from a layer above its own.

The layers, bottom to top, are those of docs/architecture.md. Every import
of every module under ``rocketsim/`` and ``cli/`` counts: at module level,
inside functions and under ``TYPE_CHECKING`` alike (a name imported only for
a type still ties the module to the layer it comes from). Every import also
counts toward circles: two modules that import each other, whether at module
level or inside a function, are one circle, named with the lines that close
it. A package whose names load on first use (``rocketsim.exports.lazy``) imports each
name's home when the name is read: those homes count as imports inside a function. The
checks parse the source (nothing is imported), so they also run on a planted tree.
"""

from __future__ import annotations

import ast
import functools
import textwrap
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]

# bottom to top; a module belongs to the longest prefix that names it
LAYERS = [
    ("rocketsim.constants", "rocketsim.errors", "rocketsim.argument_checks", "rocketsim.jit",
     "rocketsim.version", "rocketsim.limits", "rocketsim.extras"),
    ("rocketsim.timescales", "rocketsim.frames", "rocketsim.layout"),
    ("rocketsim.bodies", "rocketsim.ephemeris", "rocketsim.atmosphere"),
    ("rocketsim.orbits",),
    ("rocketsim.vehicle",),
    ("rocketsim.dynamics",),
    ("rocketsim.transfer", "rocketsim.flight", "rocketsim.guidance"),
    ("rocketsim.stepping",),
    ("rocketsim.scenario", "rocketsim.telemetry"),
    ("rocketsim.sim",),
    ("rocketsim.api", "rocketsim"),
    ("rocketsim_cli", "rocketsim.__main__"),         # python -m rocketsim is the command line
]
PACKAGES = {"rocketsim": "rocketsim", "cli": "rocketsim_cli"}


def layer_of(module: str) -> int | None:
    """Index in :data:`LAYERS` of ``module`` (None outside the project)."""
    best = None
    for index, prefixes in enumerate(LAYERS):
        for prefix in prefixes:
            if (module == prefix or module.startswith(prefix + ".")) and (best is None or len(prefix) > best[1]):
                best = (index, len(prefix))
    return None if best is None else best[0]


def modules(root: Path) -> dict[str, Path]:
    """Dotted name -> source file of every module of the project under ``root``."""
    found = {}
    for folder, package in PACKAGES.items():
        for path in sorted((root / folder).rglob("*.py")):
            parts = [package, *path.relative_to(root / folder).with_suffix("").parts]
            if parts[-1] == "__init__":
                parts.pop()
            found[".".join(parts)] = path
    return found


def imports(name: str, path: Path) -> tuple[tuple[str, int, bool], ...]:
    """``(imported module, line, at module level)`` of every project import in ``path``."""
    return _imports(name, path.name == "__init__.py", path.read_text())


@functools.lru_cache(maxsize=None)      # a text is parsed once, whichever tree holds it
def _imports(name: str, is_package: bool, text: str) -> tuple[tuple[str, int, bool], ...]:
    tree = ast.parse(text)
    # run at import time: a module-level statement, or one inside a module-level if/try
    top_level = {id(node) for node in tree.body}
    top_level |= {id(node) for statement in tree.body if isinstance(statement, (ast.If, ast.Try))
                  for node in ast.walk(statement)}
    package = name.split(".") if is_package else name.split(".")[:-1]
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            targets = [alias.name for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                base = ".".join(package[:len(package) - node.level + 1] + ([base] if base else []))
            # ``from a.b import c`` names the module a.b.c when there is one, else a.b
            targets = [f"{base}.{alias.name}" if alias.name != "*" else base for alias in node.names]
        else:
            continue
        for target in targets:
            if target.split(".")[0] in PACKAGES.values():
                found.append((target, node.lineno, id(node) in top_level))
    found += [(home if attribute is None else f"{home}.{attribute}", line, False)
              for _, home, attribute, line in _lazy_homes(tree)]
    return tuple(found)


def _lazy_homes(tree: ast.Module) -> list[tuple[str, str, str, int]]:
    """``(exported name, home module, its name there, line)`` of every name a module
    exports through ``lazy(globals(), homes)`` (:mod:`rocketsim.exports`): ``homes`` a
    dict (or dict comprehension) written in the call or assigned at module level, each
    value a module's dotted name or a ``(module, name)`` pair."""
    assigned = {target.id: node.value for node in tree.body if isinstance(node, ast.Assign)
                for target in node.targets if isinstance(target, ast.Name)}
    found = []
    for call in ast.walk(tree):
        if not (isinstance(call, ast.Call) and isinstance(call.func, ast.Name) and call.func.id == "lazy"
                and len(call.args) == 2):
            continue
        homes = call.args[1]
        if isinstance(homes, ast.Name):
            homes = assigned.get(homes.id)
        if isinstance(homes, ast.Dict):
            pairs = [(key.value if isinstance(key, ast.Constant) else None, value)
                     for key, value in zip(homes.keys, homes.values)]
        elif isinstance(homes, ast.DictComp):
            pairs = [(None, homes.value)]           # every name read from one home
        else:
            continue
        for name, value in pairs:
            if isinstance(value, ast.Constant) and isinstance(value.value, str):
                home, attribute = value.value, name
            elif (isinstance(value, ast.Tuple) and len(value.elts) == 2
                  and all(isinstance(e, ast.Constant) and isinstance(e.value, str) for e in value.elts)):
                home, attribute = value.elts[0].value, value.elts[1].value
            else:
                continue
            if home.split(".")[0] in PACKAGES.values():
                found.append((name, home, attribute, value.lineno))
    return found


def missing_lazy_homes(root: Path) -> list[str]:
    """Every name exported through ``lazy`` whose home is not a module of the project or
    does not define it (a def, a class, an assignment or an import at its module level),
    as ``file:line: package.name -> home.name``."""
    known, found = modules(root), []
    for name, path in known.items():
        for exported, home, attribute, line in _lazy_homes(ast.parse(path.read_text())):
            if attribute is None:
                continue
            defined = home in known and attribute in _defined(known[home])
            if not defined:
                found.append(f"{path.relative_to(root)}:{line}: {name}.{exported} -> {home}.{attribute}")
    return found


def _defined(path: Path) -> set[str]:
    """The names a module binds at its module level."""
    names = set()
    for node in ast.parse(path.read_text()).body:
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            names.add(node.name)
        elif isinstance(node, (ast.Assign, ast.AnnAssign)):
            for target in (node.targets if isinstance(node, ast.Assign) else [node.target]):
                names |= {n.id for n in ast.walk(target) if isinstance(n, ast.Name)}
        elif isinstance(node, (ast.Import, ast.ImportFrom)):
            names |= {(alias.asname or alias.name).split(".")[0] for alias in node.names}
    return names


def upward_imports(root: Path) -> list[str]:
    """Every import that runs up the layers, as ``module:line -> imported (layers)``."""
    found, known = [], modules(root)
    for name, path in known.items():
        own = layer_of(name)
        for target, line, _ in imports(name, path):
            theirs = layer_of(target)
            if own is not None and theirs is not None and theirs > own:
                target = _module_of(target, known) or target
                found.append(f"{path.relative_to(root)}:{line}: {name} (layer {own + 1}) imports "
                             f"{target} (layer {theirs + 1})")
    return found


def import_graph(root: Path) -> dict[str, dict[str, list[tuple[int, bool]]]]:
    """``module -> {imported module -> [(line, at module level), ...]}`` over every import
    of the project, at module level and inside functions alike."""
    known = modules(root)
    graph: dict[str, dict[str, list[tuple[int, bool]]]] = {}
    for name, path in known.items():
        edges = graph.setdefault(name, {})
        for target, line, top in imports(name, path):
            imported = _module_of(target, known)
            if imported is not None and imported != name and (line, top) not in edges.get(imported, []):
                edges.setdefault(imported, []).append((line, top))
    return graph


def import_cycles(root: Path) -> list[list[str]]:
    """The circles of imports between modules, module-level and inside functions alike:
    each a strongly connected component of two or more modules (Tarjan's algorithm),
    its modules sorted. An import inside a function closes a circle as surely as one at
    module level: the two modules cannot be understood, tested or moved one without the
    other."""
    return _cycles(import_graph(root))


def _cycles(graph: dict[str, dict]) -> list[list[str]]:
    index, low, stack, on_stack, cycles = {}, {}, [], set(), []

    def visit(node: str) -> None:
        index[node] = low[node] = len(index)
        stack.append(node)
        on_stack.add(node)
        for nxt in sorted(graph[node]):
            if nxt not in index:
                visit(nxt)
                low[node] = min(low[node], low[nxt])
            elif nxt in on_stack:
                low[node] = min(low[node], index[nxt])
        if low[node] == index[node]:
            component = []
            while True:
                member = stack.pop()
                on_stack.discard(member)
                component.append(member)
                if member == node:
                    break
            if len(component) > 1:
                cycles.append(sorted(component))

    for node in sorted(graph):
        if node not in index:
            visit(node)
    return sorted(cycles)


def describe_cycles(root: Path) -> list[str]:
    """Each circle of :func:`import_cycles` named by its files, then every import that
    ties its modules together, as ``file:line: module imports module``."""
    graph, known = import_graph(root), modules(root)
    described = []
    for cycle in _cycles(graph):
        files = [str(known[name].relative_to(root)) for name in cycle]
        lines = [" <-> ".join(files)]
        for name in cycle:
            for imported, places in sorted(graph[name].items()):
                if imported in cycle:
                    for line, top in places:
                        where = "" if top else " (inside a function)"
                        lines.append(f"    {known[name].relative_to(root)}:{line}: {name} imports "
                                     f"{imported}{where}")
        described.append("\n".join(lines))
    return described


def _module_of(target: str, known: dict[str, Path]) -> str | None:
    """The module an import names: the longest known prefix of ``target``."""
    parts = target.split(".")
    for end in range(len(parts), 0, -1):
        if ".".join(parts[:end]) in known:
            return ".".join(parts[:end])
    return None


def test_no_import_runs_up_the_layers():
    found = upward_imports(ROOT)
    assert not found, "imports that run up the layers:\n" + "\n".join(found)


def test_no_import_circles():
    found = describe_cycles(ROOT)
    assert not found, "import circles:\n" + "\n".join(found)


def test_every_lazily_exported_name_has_a_home():
    # a name moved to another module with its lazy export left behind fails only when read
    found = missing_lazy_homes(ROOT)
    assert not found, "names exported through lazy() that their home does not define:\n" + "\n".join(found)


def test_every_module_has_a_layer():
    unplaced = [name for name in modules(ROOT) if layer_of(name) is None]
    assert not unplaced


def _planted(tmp_path: Path, files: dict[str, str]) -> Path:
    for rel, text in files.items():
        target = tmp_path / rel
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_text(textwrap.dedent(text))
    (tmp_path / "cli").mkdir(exist_ok=True)
    return tmp_path


def test_a_planted_upward_import_is_named(tmp_path):
    root = _planted(tmp_path, {
        "rocketsim/__init__.py": "",
        "rocketsim/frames/__init__.py": "",
        "rocketsim/frames/geodetic.py": "def f():\n    from rocketsim.sim.world import World\n",
        "rocketsim/sim/__init__.py": "",
        "rocketsim/sim/world.py": "from rocketsim.frames.geodetic import f\n",
        "rocketsim/dynamics/__init__.py": "",
        "rocketsim/dynamics/rk4.py": "from ..flight import fc\n",
        "rocketsim/flight/__init__.py": "",
        "rocketsim/flight/fc.py": "",
    })
    found = upward_imports(root)
    assert len(found) == 2
    assert any("frames/geodetic.py:2: rocketsim.frames.geodetic (layer 2) imports rocketsim.sim.world "
               "(layer 10)" in line for line in found)
    assert any("rocketsim.dynamics.rk4 (layer 6) imports rocketsim.flight" in line for line in found)


def test_a_planted_circle_is_reported(tmp_path):
    root = _planted(tmp_path, {
        "rocketsim/__init__.py": "",
        "rocketsim/sim/__init__.py": "",
        "rocketsim/sim/a.py": "from rocketsim.sim import b\n",
        "rocketsim/sim/b.py": "import rocketsim.sim.c\n",
        "rocketsim/sim/c.py": "from rocketsim.sim.a import x\n",
        "rocketsim/sim/d.py": "def late():\n    from rocketsim.sim import a\n",
    })
    assert import_cycles(root) == [["rocketsim.sim.a", "rocketsim.sim.b", "rocketsim.sim.c"]]


def test_a_circle_closed_inside_a_function_is_reported(tmp_path):
    # load.py imports weather.py at module level; weather.py imports load.py back inside a
    # function, by a relative import: one circle, named by its files and the import's line
    root = _planted(tmp_path, {
        "rocketsim/__init__.py": "",
        "rocketsim/scenario/__init__.py": "",
        "rocketsim/scenario/load.py": "from rocketsim.scenario.weather import load_weather\n",
        "rocketsim/scenario/weather.py": "import math\n\n\ndef load_weather():\n"
                                         "    from .load import validate\n",
        "rocketsim/scenario/units.py": "from . import load\n",
    })
    assert import_cycles(root) == [["rocketsim.scenario.load", "rocketsim.scenario.weather"]]
    [described] = describe_cycles(root)
    assert described.splitlines() == [
        "rocketsim/scenario/load.py <-> rocketsim/scenario/weather.py",
        "    rocketsim/scenario/load.py:1: rocketsim.scenario.load imports rocketsim.scenario.weather",
        "    rocketsim/scenario/weather.py:5: rocketsim.scenario.weather imports rocketsim.scenario.load"
        " (inside a function)",
    ]


def test_the_checks_fail_on_a_planted_copy_of_the_library(tmp_path):
    # the same checks over a copy of this tree with an upward import planted in a new
    # module, and a circle closed inside functions between two modules that do not import
    # each other (timescales, frames.quaternion): each is named
    import shutil
    for folder in PACKAGES:
        shutil.copytree(ROOT / folder, tmp_path / folder,
                        ignore=shutil.ignore_patterns("__pycache__", "*.npz", "*.json", "*.txt"))
    (tmp_path / "rocketsim/frames/planted.py").write_text(
        "def late():\n    from ..sim.world import World\n")
    with open(tmp_path / "rocketsim/timescales.py", "a") as timescales:
        timescales.write("\n\ndef _planted():\n    from rocketsim.frames import quaternion\n")
    with open(tmp_path / "rocketsim/frames/quaternion.py", "a") as quaternion:
        quaternion.write("\n\ndef _planted():\n    import rocketsim.timescales\n")
    assert ("rocketsim/frames/planted.py:2: rocketsim.frames.planted (layer 2) imports "
            "rocketsim.sim.world (layer 10)") in upward_imports(tmp_path)
    assert ["rocketsim.frames.quaternion", "rocketsim.timescales"] in import_cycles(tmp_path)


def test_lazy_exports_count_as_imports(tmp_path):
    # a package whose names load on first use imports their homes: a lower package exporting
    # a name of a higher one runs up the layers, and a home that imports the package back
    # closes a circle; a name its home does not define is named
    root = _planted(tmp_path, {
        "rocketsim/__init__.py": "",
        "rocketsim/frames/__init__.py": (
            "_HOMES = {\"World\": \"rocketsim.sim.world\", \"f\": (\"rocketsim.frames.geodetic\", \"g\")}\n"
            "__getattr__, __dir__ = lazy(globals(), _HOMES)\n\n\n"
            "def lazy(namespace, homes):\n    return None, None\n"),
        "rocketsim/frames/geodetic.py": "from rocketsim import frames\n\n\ndef f():\n    pass\n",
        "rocketsim/sim/__init__.py": "",
        "rocketsim/sim/world.py": "class World:\n    pass\n",
    })
    assert upward_imports(root) == [
        "rocketsim/frames/__init__.py:1: rocketsim.frames (layer 2) imports rocketsim.sim.world (layer 10)"]
    assert import_cycles(root) == [["rocketsim.frames", "rocketsim.frames.geodetic"]]
    assert missing_lazy_homes(root) == ["rocketsim/frames/__init__.py:1: rocketsim.frames.f -> "
                                        "rocketsim.frames.geodetic.g"]
