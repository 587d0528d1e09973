"""The command line stands on the front door: ``cli/`` imports nothing of the library
but ``rocketsim.api``, ``rocketsim.plots`` and ``rocketsim.errors``.

Every import of every module under ``cli/`` counts: at module level, inside
functions, under ``TYPE_CHECKING``, and ``importlib.import_module`` of a constant
name. ``from rocketsim.api import X`` counts as the module ``rocketsim.api.X`` when
that module exists (a way round the front door), and a name it takes from the
front door must be one the front door exports. The checks parse the source (the
import check imports nothing), so they also run on a planted tree.
"""

from __future__ import annotations

import ast
import json
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
LIBRARY = "rocketsim"
ALLOWED = ("rocketsim.api", "rocketsim.plots", "rocketsim.errors")


def _is_module(root: Path, dotted: str) -> bool:
    """Whether ``dotted`` (``rocketsim...``) is a module or package of the library under ``root``."""
    path = root.joinpath(*dotted.split("."))
    return path.with_suffix(".py").is_file() or (path / "__init__.py").is_file()


def library_imports(root: Path) -> list[tuple[str, int, str, str | None]]:
    """``(file, line, module, name)`` of every import of the library in ``root/cli``: the
    module imported, and the name taken from it (``from module import name``; None for
    ``import module``), a name that is a module counted as that module."""
    found = []
    for path in sorted((root / "cli").rglob("*.py")):
        rel = path.relative_to(root).as_posix()
        for node in ast.walk(ast.parse(path.read_text(), rel)):
            if isinstance(node, ast.Import):
                found += [(rel, node.lineno, alias.name, None) for alias in node.names]
            elif isinstance(node, ast.ImportFrom) and not node.level and node.module:
                for alias in node.names:
                    module = f"{node.module}.{alias.name}"
                    if _is_module(root, module):
                        found.append((rel, node.lineno, module, None))
                    else:
                        found.append((rel, node.lineno, node.module, alias.name))
            elif (isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute)
                  and node.func.attr == "import_module" and node.args
                  and isinstance(node.args[0], ast.Constant) and isinstance(node.args[0].value, str)):
                found.append((rel, node.lineno, node.args[0].value, None))
    return [item for item in found if item[2] == LIBRARY or item[2].startswith(LIBRARY + ".")]


def imports_past_the_front_door(root: Path) -> list[str]:
    """Each library import in ``root/cli`` of anything but :data:`ALLOWED`, as
    ``file:line: module`` (``module.name`` for a name taken from the bare package)."""
    return [f"{file}:{line}: {module}" + (f" (name {name})" if name else "")
            for file, line, module, name in library_imports(root) if module not in ALLOWED]


def test_the_command_line_imports_only_the_front_door_plots_and_errors():
    found = imports_past_the_front_door(ROOT)
    assert not found, ("cli/ imports the library past rocketsim.api, rocketsim.plots and "
                       "rocketsim.errors:\n" + "\n".join(found))


def test_every_name_the_command_line_takes_is_exported():
    """A name the front door does not export would fail only when its command runs (the
    commands import inside their functions); every name, once read, is found in its home."""
    import rocketsim.api
    import rocketsim.errors
    import rocketsim.plots

    packages = {"rocketsim.api": rocketsim.api, "rocketsim.plots": rocketsim.plots,
                "rocketsim.errors": rocketsim.errors}
    taken = {(module, name) for _, _, module, name in library_imports(ROOT) if name}
    assert {module for module, _ in taken} == set(ALLOWED)
    missing = [f"{module}.{name}" for module, name in sorted(taken)
               if not hasattr(packages[module], name)]
    assert not missing


@pytest.mark.parametrize("package", ["rocketsim.api", "rocketsim.plots"])
def test_each_exported_name_is_found_and_none_is_a_module_name(package):
    """An exported name that is also one of the package's modules would be bound to the
    module as soon as the module is imported, hiding the function."""
    import importlib

    module = importlib.import_module(package)
    for name in module.__all__:
        assert getattr(module, name) is not None
        assert not _is_module(ROOT, f"{package}.{name}"), name


def test_the_front_door_and_the_plots_import_nothing_until_a_name_is_read():
    """What keeps ``rocketsim --help``, ``validate`` and ``schema`` light: the two packages
    the commands import cost no numpy, matplotlib, pydantic or simulator module (a fresh
    interpreter reports what it imported)."""
    heavy = ("numpy", "matplotlib", "pydantic", "numba", "rocketsim.scenario", "rocketsim.sim")
    code = ("import json, sys; import rocketsim.api, rocketsim.plots; "
            f"print(json.dumps([m for m in {heavy!r} if m in sys.modules]))")
    done = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True,
                          check=True)
    assert json.loads(done.stdout) == []


def _planted(tmp_path: Path, files: dict[str, str]) -> Path:
    for rel, text in files.items():
        target = tmp_path / rel
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_text(textwrap.dedent(text))
    return tmp_path


LIBRARY_TREE = {
    "rocketsim/__init__.py": "",
    "rocketsim/errors.py": "",
    "rocketsim/api/__init__.py": "",
    "rocketsim/api/flying.py": "",
    "rocketsim/plots/__init__.py": "",
    "rocketsim/sim/__init__.py": "",
    "rocketsim/sim/world.py": "",
}


def test_the_front_door_plots_and_errors_pass(tmp_path):
    root = _planted(tmp_path, {**LIBRARY_TREE, "cli/fine.py": """
        import click
        import rocketsim.api
        from rocketsim import api, plots
        from rocketsim.errors import InputError
        from rocketsim_cli.errors import reports_input_errors

        def command():
            from rocketsim.api import fly_to_file, load
            from rocketsim.plots import run
        """})
    assert len(library_imports(root)) == 7
    assert imports_past_the_front_door(root) == []


def test_a_planted_import_past_the_front_door_is_named(tmp_path):
    root = _planted(tmp_path, {**LIBRARY_TREE, "cli/fly.py": """
        from typing import TYPE_CHECKING

        from rocketsim.api import load

        if TYPE_CHECKING:
            from rocketsim.sim.world import World

        def fly():
            import importlib
            from rocketsim.api import flying
            from rocketsim import __version__
            world = importlib.import_module("rocketsim.sim.world")
        """})
    assert imports_past_the_front_door(root) == [
        "cli/fly.py:7: rocketsim.sim.world (name World)",
        "cli/fly.py:11: rocketsim.api.flying",
        "cli/fly.py:12: rocketsim (name __version__)",
        "cli/fly.py:13: rocketsim.sim.world",
    ]
