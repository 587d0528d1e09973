"""The distribution ships every package folder (pyproject lists them by hand)."""

import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def test_every_package_folder_is_listed_in_pyproject():
    listed = set(tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]["packages"])
    found = {".".join(p.parent.relative_to(ROOT).parts) for p in (ROOT / "rocketsim").rglob("__init__.py")}
    found.add("rocketsim_cli")
    assert found == listed


def test_python_m_rocketsim_runs_the_command_line():
    """``python -m rocketsim --help`` prints the same help as the ``rocketsim`` command, and the
    package ships its PEP 561 marker (py.typed) for type checkers."""
    import subprocess
    import sys

    module = subprocess.run([sys.executable, "-m", "rocketsim", "--help"], capture_output=True, text=True,
                            timeout=120, cwd=ROOT)
    command = subprocess.run([str(Path(sys.executable).with_name("rocketsim")), "--help"], capture_output=True,
                             text=True, timeout=120, cwd=ROOT)
    assert module.returncode == 0 and command.returncode == 0, module.stderr + command.stderr
    assert module.stdout == command.stdout and "Usage: rocketsim" in module.stdout
    assert (ROOT / "rocketsim" / "py.typed").is_file()
    assert '"py.typed"' in (ROOT / "pyproject.toml").read_text()
