"""Which outputs a campaign's report draws as histograms
(:func:`rocketsim.plots.campaign_figures.histogram_columns`), on the synthetic campaign of
tests/unit/campaigns/test_campaign_report.py: the campaign's own outputs first, then per body what
became of it (a body that came down: its miss distance and touchdown; one that never did:
its orbit), a body on the ground never by its orbital elements, and a column the
campaign asked by its path that equals one already drawn only once."""

import json

import pandas as pd

from rocketsim.campaigns.report import report
from rocketsim.plots.campaign_figures import histogram_columns
from tests.unit.campaigns.test_campaign_report import synthetic


def test_histograms_are_chosen_by_what_became_of_each_body(tmp_path):
    directory, truth = synthetic(tmp_path / "dir", n=40, errors=(), timeouts=())
    results = pd.read_parquet(directory / "results.parquet")
    # the fairing came down: its orbital elements (as if read on the ground) are noise
    results["fairing.orbit.periapsis_altitude_m"] = -6.3e6 + results["fairing.landing.latitude_deg"]
    results["stage2.orbit.periapsis_altitude_m"] = truth["periapsis"]      # in orbit, never down
    # an output the campaign asks by its path, the same numbers as the touchdown's column
    asked = "bodies.booster.events[touchdown].vertical_speed_m_s"
    results[asked] = results["booster.touchdown.vertical_speed_m_s"]
    results.to_parquet(directory / "results.parquet")
    meta = json.loads((directory / "meta.json").read_text())
    (directory / "meta.json").write_text(json.dumps({**meta, "outputs": ["summary.mission_time_s", asked]}))

    drawn = histogram_columns(report(directory))

    assert drawn[:2] == ["summary.mission_time_s", asked]           # the campaign's own, first
    assert "booster.touchdown.vertical_speed_m_s" not in drawn       # the same numbers: once
    for column in ("booster.landing.offset_m", "fairing.landing.offset_m", "stage2.orbit.periapsis_altitude_m"):
        assert column in drawn, column
    assert not any(c.startswith(("fairing.orbit.", "booster.orbit.")) for c in drawn)
    assert not any(c.startswith("stage2.landing.") for c in drawn)
