"""The glossary of docs/architecture.md names modules and names that exist.

Every module, folder and name in the glossary's "where" column is looked up in
the source (parsed, nothing imported): a file or folder under ``rocketsim/``, a
``constants.NAME``, and each name in parentheses after a file (``Class``,
``function``, ``Class.method``) defined there, so a move or a rename that leaves
the glossary behind fails here.
"""

from __future__ import annotations

import ast
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
LIBRARY = ROOT / "rocketsim"


def glossary_rows() -> list[tuple[str, str]]:
    """``(word, where)`` of each row of the glossary's table."""
    text = (ROOT / "docs" / "architecture.md").read_text()
    section = text.split("\n## Glossary\n", 1)[1].split("\n## ", 1)[0]
    rows = []
    for line in section.splitlines():
        cells = [cell.strip() for cell in line.strip().strip("|").split("|")]
        if len(cells) == 3 and cells[0] not in ("word", "---"):
            rows.append((cells[0], cells[2]))
    return rows


def defined(path: Path, name: str) -> bool:
    """Whether ``name`` (``a`` or ``Class.attribute``) is defined at the top of ``path``."""
    tree = ast.parse(path.read_text())
    head, _, attribute = name.partition(".")
    for node in tree.body:
        if _names(node, head):
            if not attribute:
                return True
            return isinstance(node, ast.ClassDef) and any(_names(n, attribute) for n in node.body)
    return False


def _names(node: ast.AST, name: str) -> bool:
    if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
        return node.name == name
    if isinstance(node, ast.Assign):
        return any(isinstance(t, ast.Name) and t.id == name for t in node.targets)
    if isinstance(node, ast.AnnAssign):
        return isinstance(node.target, ast.Name) and node.target.id == name
    return False


def missing_references() -> list[str]:
    missing = []
    for word, where in glossary_rows():
        current = None
        for token in re.findall(r"`([^`]+)`", where):
            if token.endswith(".py"):
                current = LIBRARY / token
                if not current.is_file():
                    missing.append(f"{word}: no module {token}")
                    current = False         # its names are not looked for
            elif token.endswith("/"):
                current = None
                if not (LIBRARY / token).is_dir():
                    missing.append(f"{word}: no folder {token}")
            elif re.fullmatch(r"[a-z_]+\.[A-Z_0-9]+", token):
                module, name = token.split(".")
                if not defined(LIBRARY / f"{module}.py", name):
                    missing.append(f"{word}: no {name} in {module}.py")
            elif current is False:
                continue
            elif current is None or not defined(current, token):
                missing.append(f"{word}: no {token} in {current.relative_to(LIBRARY) if current else '?'}")
    return missing


def test_the_glossary_has_its_words():
    words = {word.strip("*") for word, _ in glossary_rows()}
    assert {"window", "run", "batch", "segment", "rails", "fold", "watch", "carry", "twin", "body",
            "part", "vehicle", "sample"} <= words


def test_every_module_and_name_the_glossary_gives_exists():
    assert not missing_references(), "\n".join(missing_references())
