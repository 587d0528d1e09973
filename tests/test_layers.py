"""The library's layers hold: no module imports from a layer above its own.

The layers, bottom to top, are those of docs/architecture.md. Every import
of every module under ``rocketsim/`` and ``cli/`` counts: at module level,
inside functions and under ``TYPE_CHECKING`` alike (a name imported only for
a type still ties the module to the layer it comes from). The checks parse
the source (nothing is imported), so they also run on a planted tree.
"""

from __future__ import annotations

import ast
import textwrap
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

# bottom to top; a module belongs to the longest prefix that names it
LAYERS = [
    ("rocketsim.constants", "rocketsim.errors", "rocketsim._jit", "rocketsim.version",
     "rocketsim.limits"),
    ("rocketsim.timescales", "rocketsim.frames", "rocketsim.layout"),
    ("rocketsim.bodies", "rocketsim.ephemeris", "rocketsim.atmosphere"),
    ("rocketsim.orbits",),
    ("rocketsim.vehicle",),
    ("rocketsim.dynamics",),
    ("rocketsim.transfer", "rocketsim.flight", "rocketsim.guidance"),
    ("rocketsim.scenario", "rocketsim.telemetry"),
    ("rocketsim.sim",),
    ("rocketsim.api", "rocketsim"),
    ("rocketsim_cli",),
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


def imports(name: str, path: Path) -> list[tuple[str, int, bool]]:
    """``(imported module, line, at module level)`` of every project import in ``path``."""
    tree = ast.parse(path.read_text(), str(path))
    top_level = {id(node) for node in tree.body}
    top_level |= {id(node) for node in ast.walk(tree)
                  if isinstance(node, (ast.Import, ast.ImportFrom)) and _under_module_if(tree, node)}
    package = name.split(".") if path.name == "__init__.py" else name.split(".")[:-1]
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
    return found


def _under_module_if(tree: ast.Module, node: ast.AST) -> bool:
    """True for an import inside a module-level ``if``/``try`` (run at import time)."""
    for statement in tree.body:
        if isinstance(statement, (ast.If, ast.Try)) and any(n is node for n in ast.walk(statement)):
            return True
    return False


def upward_imports(root: Path) -> list[str]:
    """Every import that runs up the layers, as ``module:line -> imported (layers)``."""
    found = []
    for name, path in modules(root).items():
        own = layer_of(name)
        for target, line, _ in imports(name, path):
            theirs = layer_of(target)
            if own is not None and theirs is not None and theirs > own:
                target = _module_of(target, modules(root)) or target
                found.append(f"{path.relative_to(root)}:{line}: {name} (layer {own + 1}) imports "
                             f"{target} (layer {theirs + 1})")
    return found


def import_cycles(root: Path) -> list[list[str]]:
    """The circles of module-level imports between modules (each a strongly connected
    component of two or more modules, Tarjan's algorithm)."""
    known = modules(root)
    graph = {name: sorted({_module_of(target, known) for target, _, top in imports(name, path) if top}
                          - {None, name})
             for name, path in known.items()}
    index, low, stack, on_stack, cycles = {}, {}, [], set(), []

    def visit(node: str) -> None:
        index[node] = low[node] = len(index)
        stack.append(node)
        on_stack.add(node)
        for nxt in graph[node]:
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

    for node in graph:
        if node not in index:
            visit(node)
    return cycles


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
    found = import_cycles(ROOT)
    assert not found, "import circles:\n" + "\n".join(" <-> ".join(c) for c in found)


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
               "(layer 9)" in line for line in found)
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
