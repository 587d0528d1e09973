"""Shared test helpers: write small scenarios into a temporary folder; the fuzz profiles."""

from __future__ import annotations

import os
import textwrap
from pathlib import Path

import pytest
from click.testing import CliRunner
from hypothesis import HealthCheck, settings

from rocketsim.jit import beside

ROOT = Path(__file__).resolve().parents[1]

# no test queues kernels for a second compiling process: with one test worker per core every
# core compiles already, and tests wrap kernels in plain functions (timing, counting) that
# cannot be queued; tests/unit/jit/test_jit_beside.py tests the queue where it switches it on
beside.COMPILE_BESIDE = False

# Hypothesis profiles of tests/fuzz: "ci" (the default) replays the same examples every
# run (derandomize) on a fixed budget; "long", for a developer, draws 17 times as many
# fresh ones. Choose with --hypothesis-profile=long or ROCKETSIM_FUZZ_PROFILE=long.
# max_examples is a unit: each fuzz test runs a multiple of it (tests/fuzz/harness.py).
_FUZZ = dict(deadline=None, database=None, print_blob=True,
             suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large,
                                    HealthCheck.filter_too_much, HealthCheck.function_scoped_fixture])
settings.register_profile("ci", max_examples=100, derandomize=True, **_FUZZ)
settings.register_profile("long", max_examples=1700, derandomize=False, **_FUZZ)
settings.load_profile(os.environ.get("ROCKETSIM_FUZZ_PROFILE", "ci"))

VEHICLE = """\
name: probe
rigid_body:
  mass: 10 kg
  inertia: [0.15, 0.12, 0.05]
"""

MISSION = """\
epoch: 2026-11-26T12:00:00Z
start:
  orbit:
    altitude: 415 km
    inclination: 51.6 deg
duration: {duration}
"""


@pytest.fixture
def write(tmp_path):
    """write(name, text) -> Path: a dedented file in the test's folder."""

    def _write(name: str, text: str) -> Path:
        path = tmp_path / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(textwrap.dedent(text))
        return path

    return _write


@pytest.fixture
def scenario(write):
    """scenario(program_text=None, duration='10 s', extra='') -> Path of a coasting scenario."""

    def _scenario(program: str | None = None, duration: str = "10 s", extra: str = "") -> Path:
        write("vehicle.yaml", VEHICLE)
        write("mission.yaml", MISSION.format(duration=duration))
        text = "name: test\nvehicle: vehicle.yaml\nmission: mission.yaml\n" + extra
        if program is not None:
            write("program.py", program)
            text += "program: program.py\n"
        return write("scenario.yaml", text)

    return _scenario


@pytest.fixture
def probe_about(write):
    """probe_about(body, orbit, program=None, duration='0.1 s', epoch=...) -> Path of a
    scenario: the conftest probe starting in ``orbit`` (YAML flow text, e.g. ``altitude:
    100 km, inclination: 80 deg``) about ``body`` (earth, moon or mars) in the n-body field."""

    def _probe(body: str, orbit: str, program: str | None = None, duration: str = "0.1 s",
               epoch: str = "2026-11-26T12:00:00Z") -> Path:
        write("vehicle.yaml", VEHICLE)
        text = f"""\
            name: about {body}
            vehicle: vehicle.yaml
            mission:
              epoch: {epoch}
              start: {{orbit: {{body: {body}, {orbit}}}}}
              duration: {duration}
              gravity: n-body
            """
        if program is not None:
            write("program.py", program)
            text += "program: program.py\n"
        return write("scenario.yaml", text)

    return _probe


@pytest.fixture
def cli():
    """cli(*args) -> click Result of ``rocketsim *args``."""
    from rocketsim_cli.main import main

    def _run(*args):
        return CliRunner().invoke(main, [str(a) for a in args], catch_exceptions=False)

    return _run
