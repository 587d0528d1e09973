"""The progress bar of a long flight: mission time, real-time factor and
phase on a terminal; nothing when stderr is not a terminal or the flight is short."""

import io
import sys

from rocketsim.scenario.load import load
from rocketsim.api.telemetry_flight import fly_to_file as fly
from rocketsim_cli.progress import MIN_MISSION_SECONDS, flight_progress

PROGRAM = """
def main(fc):
    fc.sleep(30.0)
    fc.event("halfway")
"""


class Terminal(io.StringIO):
    """A stderr that says it is a terminal."""

    def isatty(self):
        return True


def test_a_long_flight_on_a_terminal_shows_time_speed_and_phase(scenario, tmp_path, monkeypatch):
    terminal = Terminal()
    monkeypatch.setattr(sys, "stderr", terminal)
    loaded = load(scenario(PROGRAM, duration="70 s"))
    with flight_progress(70.0) as on_progress:
        fly(loaded, tmp_path / "run.mcap", on_progress=on_progress)
    shown = terminal.getvalue()
    assert "flying" in shown and "x real time" in shown
    assert "T+70 s" in shown                     # the bar reached the mission's end
    assert "probe: halfway" in shown             # the phase: the latest event


def test_no_bar_off_a_terminal_or_for_a_short_flight(monkeypatch):
    monkeypatch.setattr(sys, "stderr", io.StringIO())
    with flight_progress(3600.0) as on_progress:
        assert on_progress is None
    monkeypatch.setattr(sys, "stderr", Terminal())
    with flight_progress(MIN_MISSION_SECONDS / 2) as on_progress:
        assert on_progress is None
