"""No hand-written module of the library or the command line grows past :data:`LIMIT` lines.

A module that long holds more than one job: split it by job, each part named for what
it computes (docs/architecture.md). Not counted: the ``fc`` façade, which is every call
a flight program makes, in one page a program's author reads; and generated files (their
docstring's first line says ``GENERATED FILE``). A module over the limit whose split is
under way stands in :data:`PENDING` with the reason; one that has come under the limit
fails the check until its line is taken out, so no exemption outlives its reason.
"""

from __future__ import annotations

from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
LIMIT = 450         # lines
FOLDERS = ("rocketsim", "cli")
FACADE = {"rocketsim/flight/fc.py": "the fc façade: every call a flight program makes, one page"}
PENDING: dict[str, str] = {}    # a module being split by its owner, and why it may wait


def _generated(text: str) -> bool:
    return "GENERATED FILE" in text.split("\n", 1)[0]


def sizes(root: Path) -> dict[str, int]:
    """Lines of every hand-written module under :data:`FOLDERS` of ``root``, by path."""
    found = {}
    for folder in FOLDERS:
        for path in sorted((root / folder).rglob("*.py")):
            text = path.read_text()
            if not _generated(text):
                found[path.relative_to(root).as_posix()] = len(text.splitlines())
    return found


def too_long(root: Path, limit: int = LIMIT) -> list[str]:
    """Each module over ``limit`` lines but the façade and those pending, as ``path: lines``."""
    return [f"{path}: {lines} lines" for path, lines in sizes(root).items()
            if lines > limit and path not in FACADE and path not in PENDING]


def test_no_hand_written_module_is_longer_than_the_limit():
    found = too_long(ROOT)
    assert not found, f"modules over {LIMIT} lines (split each by job):\n" + "\n".join(found)


def test_every_exemption_still_has_its_reason():
    known = sizes(ROOT)
    gone = [f"{path}: {known.get(path, 'no such module')}" for path in {**FACADE, **PENDING}
            if known.get(path, 0) <= LIMIT]
    assert not gone, f"exempt, but no longer over {LIMIT} lines (take them off the list):\n" + "\n".join(gone)


def test_a_planted_long_module_is_named_and_a_generated_one_is_not(tmp_path):
    (tmp_path / "rocketsim" / "sim").mkdir(parents=True)
    (tmp_path / "cli").mkdir()
    (tmp_path / "rocketsim" / "sim" / "long.py").write_text('"""Two jobs."""\n' + "x = 1\n" * 12)
    (tmp_path / "rocketsim" / "tables.py").write_text('"""Tables. GENERATED FILE."""\n' + "x = 1\n" * 40)
    (tmp_path / "cli" / "short.py").write_text("x = 1\n" * 10)
    assert sizes(tmp_path) == {"cli/short.py": 10, "rocketsim/sim/long.py": 13}
    assert too_long(tmp_path, limit=10) == ["rocketsim/sim/long.py: 13 lines"]
