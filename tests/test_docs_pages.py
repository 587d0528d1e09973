"""The pages a reader follows step by step run as the reader runs them: the getting-started
page, the tutorials and the telemetry how-to.

Each page runs from a folder holding the repository's scenarios, vehicles, motors and
campaigns: each ``$ rocketsim ...`` line of its ``console`` blocks, in order, then its
``python`` blocks as one script, in new processes (as a reader's shell and Python). The
flights are the pages' own, chosen small for a reader as for the suite: a 0.1 s step and
a shortened duration for the ascent, a 16-run campaign in Python beside the file's 64
flown on one worker, the lunar orbiter at its scenario's 0.1 s step and 1 Hz telemetry.
A page whose code no longer runs (a renamed function, a moved file, a changed column)
fails here. Apart from test_docs_site.py so that the suite's processes share the two.
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
DOCS = ROOT / "docs"
# The pages a reader follows by running them, and the repository folders they read.
RUNNABLE = ["getting-started.md", *sorted(p.relative_to(DOCS).as_posix()
                                          for p in (DOCS / "tutorials").glob("*.md")),
            "how-to/telemetry.md"]
INPUTS = ["scenarios", "vehicles", "motors", "campaigns"]
# the ``rocketsim`` command installed beside this Python (pip's console script)
ROCKETSIM = str(Path(sys.executable).parent / "rocketsim")


_FENCE = re.compile(r"^```(\w+)\n(.*?)^```", re.S | re.M)


def _blocks(page: str, language: str) -> list[str]:
    return [body for lang, body in _FENCE.findall((DOCS / page).read_text()) if lang == language]


@pytest.mark.parametrize("page", RUNNABLE)
def test_a_page_runs_as_its_reader_runs_it(page, tmp_path):
    for name in INPUTS:
        (tmp_path / name).symlink_to(ROOT / name)
    env = {**os.environ, "MPLBACKEND": "Agg"}
    commands = [line[2:] for body in _blocks(page, "console") for line in body.splitlines()
                if line.startswith("$ rocketsim ")]
    scripts = _blocks(page, "python")
    assert commands or scripts, f"{page} has nothing to run"
    for command in commands:
        args = command.split()[1:]
        done = subprocess.run([ROCKETSIM, *args], cwd=tmp_path,
                              env=env, capture_output=True, text=True, timeout=900)
        assert done.returncode == 0, f"{page}: $ {command}\n{done.stdout[-2000:]}\n{done.stderr[-3000:]}"
    if scripts:
        (tmp_path / "page.py").write_text("\n".join(scripts))
        done = subprocess.run([sys.executable, "page.py"], cwd=tmp_path, env=env,
                              capture_output=True, text=True, timeout=900)
        assert done.returncode == 0, f"{page}\n{done.stdout[-2000:]}\n{done.stderr[-3000:]}"
