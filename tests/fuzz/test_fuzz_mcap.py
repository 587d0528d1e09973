"""Damaged MCAP files: replay, --export and --plot work or exit 2 with a message, never a traceback.

A run file downloaded from a forum may be cut short (a transfer that broke
off) or have bytes changed (a bad disk, a hand-edit). Hypothesis cuts the
runs of two short flights at any byte, changes bytes anywhere (header,
chunks, the summary section, lengths and CRCs alike), and zeroes or repeats
ranges of them; ``rocketsim replay`` must summarise what is readable and
exit 0 (the damage is where nothing is read) or 2 with ``error:``.

The runs: the conftest probe coasting 1 s with a program that logs and
records an event every step (so the file has every channel: states, logs,
events, attachments, metadata), and the same flight ended by the program
raising at 0.5 s (a file with an error record and no summary).
"""

from __future__ import annotations

import tempfile
from pathlib import Path

import pytest
from hypothesis import given, settings, strategies as st

from rocketsim.scenario.load import load
from rocketsim.api.telemetry_flight import fly_to_file as fly
from tests.conftest import MISSION, VEHICLE
from tests.fuzz.harness import bounded, examples, invoke

PROGRAM = """\
def main(fc):
    while fc.time < {stop}:
        fc.log("altitude", fc.altitude)
        fc.event("tick", altitude_m=fc.altitude, phase="coast")
        fc.step()
    raise RuntimeError("stopped on purpose")
"""


class Runs(list):
    """The run files' bytes, shown by their sizes (Hypothesis prints its strategies' arguments)."""

    def __repr__(self) -> str:
        return f"Runs({', '.join(f'{len(b)} bytes' for b in self)})"


@pytest.fixture(scope="module")
def runs(tmp_path_factory) -> Runs:
    """The bytes of the two run files (a complete one, one ended by a program error)."""
    folder = tmp_path_factory.mktemp("runs")
    (folder / "vehicle.yaml").write_text(VEHICLE)
    (folder / "mission.yaml").write_text(MISSION.format(duration="1 s"))
    files = []
    for stop in (2.0, 0.5):
        (folder / "program.py").write_text(PROGRAM.format(stop=stop))
        (folder / "scenario.yaml").write_text("name: fuzz\nvehicle: vehicle.yaml\n"
                                              "mission: mission.yaml\nprogram: program.py\n")
        out = folder / f"run-{stop}.mcap"
        try:
            fly(load(folder / "scenario.yaml"), out)
        except Exception:           # the second run ends by the program's error, as meant
            pass
        files.append(out.read_bytes())
    return Runs(files)


@st.composite
def damaged(draw, runs: list[bytes]) -> bytes:
    """One of ``runs`` cut, with bytes changed, zeroed or repeated."""
    data = bytearray(runs[draw(st.integers(0, len(runs) - 1))])
    for _ in range(draw(st.integers(1, 4))):
        if not data:
            break
        kind = draw(st.sampled_from(["flip", "flip", "zero", "repeat", "cut"]))
        at = draw(st.integers(0, len(data) - 1))
        if kind == "flip":
            data[at] ^= draw(st.integers(1, 255))
        elif kind == "zero":
            n = draw(st.integers(1, 64))
            data[at:at + n] = bytes(len(data[at:at + n]))
        elif kind == "repeat":
            n = draw(st.integers(1, 256))
            data[at:at] = data[at:at + n]
        else:
            del data[at:]
    return bytes(data)


def _replay(runs, data, *options) -> None:
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "run.mcap"
        path.write_bytes(data)
        with bounded("mcap"):
            code, output = invoke("replay", path, *options)
        assert code in (0, 2), output
        if code == 2:
            assert "error:" in output, output


@settings(max_examples=examples(18))
@given(st.data())
def test_a_damaged_run_is_summarised_and_exported_or_refused(runs, data):
    file = data.draw(damaged(runs))
    with tempfile.TemporaryDirectory() as tables:
        _replay(runs, file, "--export", "csv", tables)


@settings(max_examples=examples(0.03))
@given(st.data())
def test_a_damaged_run_is_plotted_or_refused(runs, data):
    # a plot takes about 2 s to draw: a few examples in CI, fifty in the long profile
    file = data.draw(damaged(runs))
    with tempfile.TemporaryDirectory() as folder:
        _replay(runs, file, "--plot", Path(folder) / "run.png")
