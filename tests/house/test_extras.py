"""Dependencies are declared once, each where it is needed, and a command that needs a
missing extra says so.

``pyproject.toml`` is read as data: every third-party module the library and the
command line import is declared (in the dependencies or an extra), nothing is listed
twice, the heavy dependencies only some commands need (Dask, pyarrow, xarray/netCDF4)
are extras whose modules are those :data:`rocketsim.extras.EXTRAS` checks for, and
the ``test`` extra installs every other extra. The commands are then run with those
modules hidden (``sys.modules[name] = None``, what Python does for a module that is
not installed): one line naming the extra's pip command, exit status 2, nothing written.
"""

from __future__ import annotations

import ast
import importlib.metadata
import re
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

from rocketsim.extras import EXTRAS, MissingExtra, needs

ROOT = Path(__file__).resolve().parents[2]
PROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]
# the module each heavy requirement is imported as (``dask[distributed]``: distributed)
HEAVY = {"dask": "distributed", "pyarrow": "pyarrow", "xarray": "xarray", "netcdf4": "netCDF4"}


def _name(requirement: str) -> str:
    """The normalised distribution name of a requirement (PEP 503)."""
    return re.sub(r"[-_.]+", "-", re.match(r"[A-Za-z0-9_.-]+", requirement).group(0)).lower()


def _extras_of(requirement: str) -> list[str]:
    found = re.search(r"\[([^\]]*)\]", requirement)
    return [e.strip() for e in found.group(1).split(",")] if found else []


def resolved(extra: str) -> list[str]:
    """The requirements ``extra`` installs, following its ``rocketsim[...]`` references."""
    found = []
    for requirement in PROJECT["optional-dependencies"][extra]:
        if _name(requirement) == "rocketsim":
            found += [r for inner in _extras_of(requirement) for r in resolved(inner)]
        else:
            found.append(requirement)
    return found


def test_nothing_is_listed_twice():
    listed = PROJECT["dependencies"] + [r for extra in PROJECT["optional-dependencies"].values()
                                        for r in extra if _name(r) != "rocketsim"]
    names = [_name(r) for r in listed]
    assert sorted({n for n in names if names.count(n) > 1}) == []


def test_the_heavy_dependencies_are_extras_checked_by_the_library():
    core = {_name(r) for r in PROJECT["dependencies"]}
    assert not core & set(HEAVY)
    for extra, modules in EXTRAS.items():
        assert sorted(HEAVY[_name(r)] for r in resolved(extra)) == sorted(modules), extra


def test_the_test_extra_installs_every_extra_but_the_generator():
    installed = {_name(r) for r in resolved("test")}
    for extra in EXTRAS:
        assert {_name(r) for r in resolved(extra)} <= installed, extra


def _third_party_imports() -> dict[str, str]:
    """``top-level module -> a file importing it`` over rocketsim/ and cli/ (parsed)."""
    found = {}
    for path in sorted([*(ROOT / "rocketsim").rglob("*.py"), *(ROOT / "cli").rglob("*.py")]):
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.Import):
                names = [alias.name for alias in node.names]
            elif isinstance(node, ast.ImportFrom) and not node.level and node.module:
                names = [node.module]
            else:
                continue
            for name in names:
                top = name.split(".")[0]
                if top not in sys.stdlib_module_names and top not in ("rocketsim", "rocketsim_cli"):
                    found.setdefault(top, str(path.relative_to(ROOT)))
    return found


def test_every_imported_library_is_declared():
    declared = set()
    for requirement in PROJECT["dependencies"] + [r for extra in PROJECT["optional-dependencies"]
                                                  for r in resolved(extra)]:
        declared.add(_name(requirement))
        declared.update(_name(e) for e in _extras_of(requirement))     # dask[distributed]
    distributions = importlib.metadata.packages_distributions()
    undeclared = [f"{module} (imported by {where})" for module, where in _third_party_imports().items()
                  if not {_name(d) for d in distributions.get(module, [module])} & declared]
    assert not undeclared


def test_a_missing_module_names_its_extra():
    with pytest.raises(MissingExtra) as caught:
        needs("weather", "a reanalysis weather file", "a_module_that_is_not_installed")
    assert str(caught.value) == ("a reanalysis weather file needs a_module_that_is_not_installed, which "
                                 "is not installed here: pip install 'rocketsim[weather]'")
    assert isinstance(caught.value, ImportError)
    needs("parquet", "the Parquet export")          # installed here: nothing raised


def _without(modules: list[str], *args: str, cwd: Path) -> subprocess.CompletedProcess:
    """``rocketsim ARGS`` in a new process where ``modules`` cannot be imported."""
    code = (f"import sys; sys.modules.update(dict.fromkeys({modules!r})); "
            "from rocketsim_cli.main import main; main()")
    return subprocess.run([sys.executable, "-c", code, *args], cwd=cwd, capture_output=True,
                          text=True, timeout=300)


def test_a_campaign_without_its_extra_says_so_and_writes_nothing(tmp_path):
    out = tmp_path / "campaign"
    ran = _without(["distributed", "pyarrow"], "campaign", "run",
                   str(ROOT / "campaigns" / "spaceport-ballistic.yaml"), "-o", str(out), cwd=tmp_path)
    assert ran.returncode == 2, ran.stderr
    assert ran.stderr.strip().splitlines() == [
        "error: a campaign needs pyarrow, which is not installed here: pip install 'rocketsim[campaign]'"]
    assert not out.exists()
    report = _without(["pyarrow"], "campaign", "report", str(tmp_path), cwd=tmp_path)
    assert report.returncode == 2
    assert "pip install 'rocketsim[campaign]'" in report.stderr and "Traceback" not in report.stderr


def test_a_campaign_in_this_process_needs_pyarrow_only(tmp_path):
    # --workers 1 flies without Dask: with Dask hidden it gets past the check (and then
    # fails on the bad file given, not on the missing Dask)
    bad = tmp_path / "bad.yaml"
    bad.write_text("runs: 2\n")
    ran = _without(["distributed"], "campaign", "run", str(bad), "-o", str(tmp_path / "c"), "--workers", "1",
                   cwd=tmp_path)
    assert ran.returncode == 2 and "distributed" not in ran.stderr and "bad.yaml" in ran.stderr


def test_reanalysis_weather_without_its_extra_says_so(tmp_path):
    day = tmp_path / "day.yaml"
    day.write_text(f"kind: reanalysis\nfile: {ROOT / 'scenarios/measured/weather/ndrt_2020_weather_data_ERA5.nc'}\n")
    ran = _without(["xarray", "netCDF4"], "atmosphere", "--weather", str(day), "--latitude", "41.78 deg",
                   "--longitude", "-86.57 deg", "--epoch", "2020-02-23T16:00Z", cwd=tmp_path)
    assert ran.returncode == 2, ran.stderr
    assert ran.stderr.strip().splitlines() == [
        "error: a reanalysis weather file needs xarray, which is not installed here: "
        "pip install 'rocketsim[weather]'"]


def test_a_plain_install_flies_and_replays(tmp_path):
    # what `pip install -e .` gives: none of the extras' modules; a short coast (10 s) and
    # its CSV export run as with everything installed
    hidden = ["distributed", "dask", "pyarrow", "xarray", "netCDF4"]
    flown = _without(hidden, "fly", str(ROOT / "scenarios" / "iss-coast.yaml"), "--duration", "10s",
                     "-o", "coast.mcap", cwd=tmp_path)
    assert flown.returncode == 0, flown.stderr
    replayed = _without(hidden, "replay", "coast.mcap", "--export", "csv", "tables", cwd=tmp_path)
    assert replayed.returncode == 0, replayed.stderr
    assert (tmp_path / "tables" / "events.csv").is_file()
