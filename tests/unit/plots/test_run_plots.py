"""``rocketsim replay --plot`` of shipped scenarios: panels chosen for the flight, labels that
do not overlap (the figure's own text boxes after a draw), no warning printed, every event
listed (tests/plot_checks.py).

The flights of the other shipped scenarios are drawn by the tests that fly them whole
(test_hobby_rocket, test_falcon9_ascent, test_falcon9_realistic, test_hop, test_electron_sso,
test_classic_range, test_mars_entry, test_mars_mission, test_moon_mission,
test_missions_from_pad, test_measured_flights). Here: the ISS coast and the ballistic arc
(seconds each), the classic range's booster landing (not flown whole elsewhere: at a
0.1 s step to keep it short, the picture and not the landing being checked), and a
picture of 40 events in a second, which must share labels rather than print over each
other.
"""

import numpy as np
import pytest
from click.testing import CliRunner

import rocketsim
from rocketsim.api.run import Run
from tests.conftest import ROOT
from tests.plot_checks import assert_the_plot_reads, overlapping_labels

SCENARIOS = ROOT / "scenarios"


# panels a flight must have and must not: a coast in orbit feels no load, meets no air and
# burns nothing; a payload's free arc (a rigid body: the air does not act on it) has no
# engine, feels no load and meets no air; a booster coming back burns and feels its burns
PANELS = {"iss-coast": ({"height", "speed", "orbit, while above the ground"},
                        {"load", "air: q and Mach", "propulsion: throttle and propellant"}),
          "spaceport-ballistic": ({"height", "speed", "ground track (^ start, x end)"},
                                  {"load", "air: q and Mach", "propulsion: thrust and propellant",
                                   "propulsion: throttle and propellant"}),
          "classic-booster-landing": ({"height", "speed", "air: q and Mach", "load",
                                       "propulsion: throttle and propellant", "attitude of the nose"}, set())}


@pytest.mark.parametrize("name, options", [("iss-coast", {}), ("spaceport-ballistic", {}),
                                           ("classic-booster-landing", {"step": 0.1})])
def test_a_shipped_scenarios_plot_reads(name, options, tmp_path):
    out = tmp_path / f"{name}.mcap"
    rocketsim.fly(SCENARIOS / f"{name}.yaml", out, **options)
    titles = set(assert_the_plot_reads(out, name))
    has, lacks = PANELS[name]
    assert has <= titles and not lacks & titles, titles
    from rocketsim_cli.main import main
    result = CliRunner().invoke(main, ["replay", str(out), "--plot", str(tmp_path / "p.png")])
    assert result.exit_code == 0, result.output
    assert "Warning" not in result.output and (tmp_path / "p.png").stat().st_size > 10_000


def test_events_too_close_to_tell_apart_share_a_label():
    """40 events within a second of a 100 s flight: their numbers are grouped on the height
    panel (``1-40``), all 40 listed."""
    from rocketsim.plots import flight_panels
    from rocketsim.plots.canvas import pyplot
    run = rocketsim.fly(SCENARIOS / "spaceport-ballistic.yaml", duration=100.0)
    file = run.file
    file.events[:] = [{"t": 10.0 + 0.02 * k, "body": "sounding-payload", "name": f"event {k}", "figures": {}}
                      for k in range(40)]
    figure = flight_panels.figure(Run(file, {n: b.samples for n, b in run.bodies.items()}))
    try:
        assert not overlapping_labels(figure)
        labels = [t.get_text() for t in figure.axes[0].texts]
        assert "1-40" in labels and len(labels) == 1
    finally:
        pyplot().close(figure)
    assert np.isfinite(run.bodies["sounding-payload"].table()["altitude_m"]).all()
