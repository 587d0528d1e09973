"""Mutated campaign files: they fly, or ``rocketsim campaign run`` exits 2 at file:line.

Hypothesis starts from a campaign of the vacuum arc (:mod:`tests.campaign_files`)
that uses every field of a campaign file: fixed overrides (a target orbit), each
kind of dispersion, a correlated group, extra outputs reading the landing
(``bodies.slug.landing.outcome``, an event's figure), the insertion's
tolerances, the telemetry kept, a timeout and retries; and changes one to four
things in it or in the scenario as :mod:`tests.fuzz.test_fuzz_files` does.
Two runs are flown in this process (``--runs 2 --workers 1``: the arc flies in
milliseconds): the command must exit 0 (every run flew), 1 (a run failed: its
row says why) or 2 naming a file and line; never a traceback, a hang or a
gigabyte. The arc is flown once before the inputs (:func:`warm`), so no input
compiles its kernels.
"""

from __future__ import annotations

import tempfile
from pathlib import Path

import pytest
import yaml
from hypothesis import given, settings, strategies as st

from tests.campaign_files import SCENARIO
from tests.fuzz.harness import AT_LINE, bounded, examples, invoke, write_files
from tests.fuzz.test_fuzz_files import mutate

CAMPAIGN = {
    "name": "fuzz", "scenario": "arc.yaml", "runs": 4, "seed": 7, "sampling": "sobol",
    "overrides": {"mission.target.orbit": {"altitude": "400 km", "inclination": "51.6 deg"},
                  "mission.initial_rates": [0, 0, 0]},
    "dispersions": {
        "mass": {"path": "vehicle.rigid_body.mass", "kind": "normal", "sigma": "5 kg", "min": "290 kg",
                 "max": "310 kg"},
        "elevation": {"path": "mission.start.site.elevation", "kind": "uniform", "low": "58 deg",
                      "high": "62 deg"},
        "step": {"path": "step", "kind": "choice", "values": [0.05, 0.1], "weights": [3, 1]},
        "noise": {"path": "seed", "kind": "seed", "low": 1, "high": 9},
        "slip": {"kind": "slip", "low": "-10 min", "high": "20 min"},
        "rate_x": {"path": "mission.initial_rates[0]", "kind": "normal", "mean": 0, "sigma": 0.01},
        "rate_y": {"path": "mission.initial_rates[1]", "kind": "normal", "mean": 0, "sigma": 0.01},
    },
    "correlations": [{"names": ["rate_x", "rate_y"], "correlation": [[1, 0.5], [0.5, 1]]}],
    "outputs": ["bodies.slug.landing.outcome", "bodies.slug.events[impact].t_s"],
    "insertion": {"periapsis": "2 km", "apoapsis": "2 km", "inclination": "0.02 deg"},
    "telemetry": [1],
    "timeout": "1 min",
    "retries": 1,
}
FILES = {"campaign.yaml": CAMPAIGN, "arc.yaml": yaml.safe_load(SCENARIO)}


def _run(files: dict[str, str], folder: Path) -> tuple[int, str]:
    write_files(folder, files)
    return invoke("campaign", "run", folder / "campaign.yaml", "-o", folder / "out", "--runs", "2",
                  "--workers", "1")


@pytest.fixture(scope="module")
def warm(tmp_path_factory):
    """The unmutated campaign flown (its kernels compiled or loaded): every run flies."""
    code, output = _run({name: yaml.safe_dump(data, sort_keys=False) for name, data in FILES.items()},
                        tmp_path_factory.mktemp("warm"))
    assert code == 0 and "2 of 2 runs flew" in output, output


@st.composite
def campaigns(draw) -> dict[str, str]:
    return mutate(draw, FILES)


@settings(max_examples=examples(0.3))
@given(campaigns())
def test_a_mutated_campaign_flies_or_is_refused_at_its_line(warm, files):
    with tempfile.TemporaryDirectory() as folder:
        with bounded("campaigns"):
            code, output = _run(files, Path(folder))
    assert code in (0, 1) or (code == 2 and AT_LINE.search(output)), output
