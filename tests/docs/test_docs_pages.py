"""The pages a reader follows step by step run as the reader runs them, and print and draw
what they show: the getting-started page, the tutorials and the telemetry how-to.

Each page runs from a folder holding the repository's scenarios, vehicles, motors and
campaigns: each ``$ rocketsim ...`` line of its ``console`` blocks, in order, then its
``python`` blocks as one script, in new processes (as a reader's shell and Python).

What a page shows its reader is what its code gives now, so it cannot drift from it:

* an ``{output}`` block is what the ``console`` or ``python`` block just before it
  prints (its standard output), line for line; ``...`` stands for any text (doctest's
  ELLIPSIS: a path, a time that differs from run to run);
* an image under ``docs/outputs/<page>/`` (``<page>`` the page's path without ``.md``)
  is the file the page's code writes at the same path in the reader's folder, compared
  as matplotlib compares its own figures (an RMS difference of the pixels within
  ``IMAGE_TOLERANCE``: a rendering's anti-aliasing, not a moved curve).

A page whose code no longer runs (a renamed function, a moved file, a changed column)
or prints or draws something else fails here, with the difference. The flights are the
pages' own, chosen small for a reader as for the suite (each page says so where the real
one is bigger): a 0.1 s step and a shortened duration for the ascent, a campaign of a
few runs on one worker, the lunar orbiter at its scenario's 0.1 s step and 1 Hz
telemetry, the guidance tutorial's hop of a few hundred metres. Apart from
test_docs_site.py so that the suite's processes share the two.
"""

from __future__ import annotations

import doctest
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
DOCS = ROOT / "docs"
OUTPUTS = DOCS / "outputs"
# The pages a reader follows by running them, and the repository folders they read.
RUNNABLE = ["getting-started.md", *sorted(p.relative_to(DOCS).as_posix()
                                          for p in (DOCS / "tutorials").glob("*.md")),
            "how-to/telemetry.md"]
INPUTS = ["scenarios", "vehicles", "motors", "campaigns"]
# the ``rocketsim`` command installed beside this Python (pip's console script)
ROCKETSIM = str(Path(sys.executable).parent / "rocketsim")
IMAGE_TOLERANCE = 1.0           # RMS of the pixels' difference, 0-255

_FENCE = re.compile(r"^```(\{output\}|\w+)\n(.*?)^```", re.S | re.M)
_IMAGE = re.compile(r"!\[[^\]]*\]\(([^)\s]+\.png)\)")
# printed between the page's python blocks, to tell what each printed
_MARK = "\x1eend of a block\x1e"


def _steps(page: str) -> list[list]:
    """The page's ``console`` and ``python`` blocks in order: ``[language, body, output]``,
    ``output`` the ``{output}`` block shown under it (None if none)."""
    steps: list[list] = []
    for language, body in _FENCE.findall((DOCS / page).read_text()):
        if language == "{output}":
            assert steps and steps[-1][2] is None, f"{page}: an output block under no code block"
            steps[-1][2] = body
        elif language in ("console", "python"):
            steps.append([language, body, None])
    return steps


def _tidy(text: str) -> str:
    return "\n".join(line.rstrip() for line in text.strip("\n").splitlines()) + "\n"


def _difference(shown: str, printed: str) -> str | None:
    """None if ``printed`` is the ``shown`` output (``...`` matching any text), else a diff."""
    checker, flags = doctest.OutputChecker(), doctest.ELLIPSIS
    want, got = _tidy(shown), _tidy(printed)
    if checker.check_output(want, got, flags):
        return None
    return checker.output_difference(doctest.Example("", want), got, flags | doctest.REPORT_UDIFF)


def _run(page: str, steps: list[list], folder: Path) -> list[str]:
    """Run the page's steps in ``folder`` as its reader does; what each step printed."""
    env = {**os.environ, "MPLBACKEND": "Agg"}
    printed = [""] * len(steps)
    for i, (language, body, _) in enumerate(steps):
        if language != "console":
            continue
        for command in [line[2:] for line in body.splitlines() if line.startswith("$ rocketsim ")]:
            done = subprocess.run([ROCKETSIM, *command.split()[1:]], cwd=folder,
                                  env=env, capture_output=True, text=True, timeout=900)
            assert done.returncode == 0, f"{page}: $ {command}\n{done.stdout[-2000:]}\n{done.stderr[-3000:]}"
            printed[i] += done.stdout
    scripts = [i for i, (language, _, _) in enumerate(steps) if language == "python"]
    if scripts:
        (folder / "page.py").write_text(f"\nprint({_MARK!r}, flush=True)\n".join(
            steps[i][1] for i in scripts) + f"\nprint({_MARK!r}, flush=True)\n")
        done = subprocess.run([sys.executable, "page.py"], cwd=folder, env=env,
                              capture_output=True, text=True, timeout=900)
        assert done.returncode == 0, f"{page}\n{done.stdout[-2000:]}\n{done.stderr[-3000:]}"
        for i, text in zip(scripts, done.stdout.split(_MARK + "\n")):
            printed[i] = text
    return printed


@pytest.mark.parametrize("page", RUNNABLE)
def test_a_page_runs_as_its_reader_runs_it_and_shows_what_it_gives(page, tmp_path):
    from matplotlib.testing.compare import compare_images

    for name in INPUTS:
        (tmp_path / name).symlink_to(ROOT / name)
    steps = _steps(page)
    assert any("$ rocketsim " in body or language == "python" for language, body, _ in steps), \
        f"{page} has nothing to run"
    printed = _run(page, steps, tmp_path)
    stale = [f"{page}, block {i + 1} ({language}):\n{diff}"
             for i, ((language, _, shown), text) in enumerate(zip(steps, printed))
             if shown is not None and (diff := _difference(shown, text))]
    assert stale == [], "\n".join(stale)

    outputs = OUTPUTS / Path(page).with_suffix("")
    for reference in _IMAGE.findall((DOCS / page).read_text()):
        shown = Path(os.path.normpath((DOCS / page).parent / reference))
        if outputs not in shown.parents:
            continue
        drawn = tmp_path / shown.relative_to(outputs)
        assert drawn.is_file(), f"{page} shows {reference}, which its code no longer draws"
        differs = compare_images(str(shown), str(drawn), tol=IMAGE_TOLERANCE)
        assert differs is None, f"{page} shows {reference}, not what its code draws now: {differs}"


def test_an_output_block_is_compared_line_for_line_with_ellipses():
    assert _difference("apogee 1.2 km\nat ... UTC\n", "apogee 1.2 km  \nat 12:00:01 UTC\n\n") is None
    assert "apogee 1.3 km" in _difference("apogee 1.2 km\n", "apogee 1.3 km\n")
    assert _difference("a\nb\n", "a\n") is not None
