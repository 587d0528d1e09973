"""The documentation site (docs/) builds with warnings as errors, its reference is the
code's and its links resolve (the pages a reader runs are run by test_docs_pages.py).

* The build is ``python -m sphinx -W --keep-going -n`` (every warning an error, every
  cross-reference resolved), as CI builds it on a fresh clone.
* The reference is generated: every command and option of the command line is on its
  page, every field of every file format on theirs, and a field added to a model
  appears on the page without editing it.
* Every link between the built pages leads to a page and an anchor that exist.
* The README stays a front page, and its test command is the one CI (``.ci/run``) runs.
"""

from __future__ import annotations

import functools
import html.parser
import os
import subprocess
import sys
from pathlib import Path
from urllib.parse import unquote, urlsplit

import click
import pytest

ROOT = Path(__file__).resolve().parents[2]
DOCS = ROOT / "docs"
sys.path.insert(0, str(DOCS / "_ext"))

import rocketsim_docs  # noqa: E402  (docs/_ext, what conf.py loads)


@pytest.fixture(scope="module")
def site(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("site")
    built = subprocess.run(
        [sys.executable, "-m", "sphinx", "-W", "--keep-going", "-n", "-q", "-b", "html",
         "-d", str(out / "doctrees"), str(DOCS), str(out / "html")],
        capture_output=True, text=True, timeout=900)
    assert built.returncode == 0 and "WARNING" not in built.stderr, built.stderr[-5000:]
    return out / "html"


class _Page(html.parser.HTMLParser):
    """A built page's text, its ids and its links."""

    def __init__(self, text: str):
        super().__init__()
        self.text, self.ids, self.links = [], set(), []
        self.feed(text)

    def handle_starttag(self, tag, attrs):
        attrs = dict(attrs)
        if attrs.get("id"):
            self.ids.add(attrs["id"])
        if tag == "a" and attrs.get("href"):
            self.links.append(attrs["href"])

    def handle_data(self, data):
        self.text.append(data)


@functools.cache
def _page(site: Path, name: str) -> _Page:
    return _Page((site / name).read_text())


def test_the_site_builds_with_warnings_as_errors(site):
    for page in ["index.html", "getting-started.html", "reference/cli.html",
                 "reference/python.html", "reference/files/vehicle.html", "physics.html"]:
        assert (site / page).is_file(), page


def _commands(group: click.Group, path=("rocketsim",)):
    yield path, group
    for name, command in getattr(group, "commands", {}).items():
        yield from _commands(command, (*path, name))


def test_every_command_and_option_is_in_the_cli_reference(site):
    from rocketsim_cli.main import main
    text = " ".join(_page(site, "reference/cli.html").text)
    missing = []
    for path, command in _commands(main):
        if " ".join(path) not in text:
            missing.append(" ".join(path))
        for param in command.params:
            names = param.opts if isinstance(param, click.Option) else [param.human_readable_name]
            missing += [f"{' '.join(path)} {name}" for name in names if name not in text]
    assert missing == []


def _fields(schema: dict):
    for model in [schema, *schema.get("$defs", {}).values()]:
        yield from model.get("properties", {})


def test_every_field_of_every_file_is_in_the_file_reference(site):
    from rocketsim import api
    from rocketsim.campaigns.spec import CampaignSpec
    text = " ".join(t for kind in rocketsim_docs.KINDS
                    for t in _page(site, f"reference/files/{kind}.html").text)
    schemas = [api.schema(kind) for kind in api.schema_kinds()] + [CampaignSpec.model_json_schema()]
    missing = sorted({f for schema in schemas for f in _fields(schema) if f not in text})
    assert missing == []


def test_a_new_field_is_documented_without_editing_a_page(monkeypatch):
    from pydantic import Field

    from rocketsim.api import scenario_files

    class Wider(scenario_files.Scenario):
        launch_commit_margin: float = Field(2.5, description="a field no page mentions")

    assert "launch_commit_margin" not in rocketsim_docs.file_pages()["scenario"]
    monkeypatch.setattr(scenario_files, "Scenario", Wider)
    page = rocketsim_docs.file_pages()["scenario"]
    assert "- ``launch_commit_margin`` (number; default ``2.5``): a field no page mentions" in page


def _reference(target: str, module: str = "rocketsim.api", source: str = ""):
    from docutils import nodes
    from sphinx.addnodes import pending_xref
    node = pending_xref("", refdomain="py", reftype="func", reftarget=target)
    node["py:module"] = module
    node.source = source
    return node, nodes.literal(target, target)


def test_a_reference_to_code_off_the_site_is_shown_as_code_only_if_it_exists():
    for target, module, source in [
            ("rocketsim.flight.autopilot", "rocketsim.api", ""),              # a module
            ("COLUMNS", "rocketsim.api",                                      # in the docstring's module
             "rocketsim/api/air_profile.py:docstring of rocketsim.api.air_profile.AirProfile"),
            ("rocketsim.sim.world.World.phase", "rocketsim.api", "")]:        # an instance's attribute
        node, code = _reference(target, module, source)
        assert rocketsim_docs.code_reference(None, None, node, code) is code, target
    for target in ["rocketsim.flight.autopilot.no_such_law", "no_such_function",
                   "rocketsim.sim.world.World.no_such_phase"]:
        node, code = _reference(target)
        assert rocketsim_docs.code_reference(None, None, node, code) is None, target


def test_every_link_between_pages_resolves(site):
    broken = []
    for path in sorted(site.rglob("*.html")):
        for href in _page(site, path.relative_to(site).as_posix()).links:
            parts = urlsplit(href)
            if parts.scheme or href.startswith("mailto:"):
                continue
            target = Path(os.path.normpath(path.parent / unquote(parts.path))) if parts.path else path
            if not target.exists():
                broken.append(f"{path.relative_to(site)}: {href}")
            elif parts.fragment and target.suffix == ".html" and \
                    parts.fragment not in _page(site, target.relative_to(site).as_posix()).ids:
                broken.append(f"{path.relative_to(site)}: {href}")
    assert broken == []


def test_the_readme_is_a_front_page_holding_the_command_ci_runs():
    readme = (ROOT / "README.md").read_text()
    assert len(readme.splitlines()) <= 200                  # the manual is the site
    ci = (ROOT / ".ci" / "run").read_text().strip().splitlines()[-1]
    assert ci.startswith("python -m pytest")
    assert f'pip install -e ".[test]" && {ci}' in readme.splitlines()[readme.splitlines().index(
        "Install the test extras and run the whole test suite:") + 2]


def test_the_version_is_the_one_pyproject_states_and_the_changelog_releases():
    import re
    import tomllib

    from rocketsim.version import __version__
    assert tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["version"] == __version__
    releases = re.findall(r"^## (\d+\.\d+\.\d+) - \d{4}-\d{2}-\d{2}$",
                          (ROOT / "CHANGELOG.md").read_text(), re.M)
    assert releases and releases[0] == __version__
