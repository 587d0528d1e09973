"""`rocketsim.campaigns.report` end to end on synthetic campaign directories written here
with the layout of the campaign interface (meta.json, inputs.parquet, results.parquet).

The synthetic runs are built from known laws (a booster that lands east/north of the pad
in proportion to the wind, a fairing that falls 30-60 km downrange, an upper stage whose
periapsis follows the thrust), so each figure of the report is checked against the
construction: the counts written, the numbers of the ok runs, the beta quantiles of
Clopper-Pearson, the landing offsets recomputed by pymap3d (the test-only WGS84 peer) and
the analytic SRC of the construction's linear law."""

import json
import math
import subprocess
import sys

import numpy as np
import pandas as pd
import pymap3d
import pytest
from scipy import stats

from rocketsim.campaigns.landing import geojson
from rocketsim.campaigns.report import report
from rocketsim.errors import InputError

TARGET = {"name": "LZ-1", "latitude_deg": 28.4858, "longitude_deg": -80.5444, "kind": "pad"}
N = 240
ERRORS, TIMEOUTS = (3, 50, 77), (120,)
PNG = b"\x89PNG\r\n\x1a\n"


def write_campaign(directory, meta: dict, inputs: pd.DataFrame, results: pd.DataFrame):
    """Write a campaign directory as the campaign engine does (the interface's three files)."""
    directory.mkdir(parents=True, exist_ok=True)
    (directory / "meta.json").write_text(json.dumps(meta, indent=1))
    inputs.to_parquet(directory / "inputs.parquet")
    results.to_parquet(directory / "results.parquet")
    return directory


def synthetic(directory, n: int = N, errors=ERRORS, timeouts=TIMEOUTS, seed: int = 7):
    """A campaign of ``n`` finished runs (3 more planned, not finished) and what it holds."""
    rng = np.random.default_rng(seed)
    run = np.arange(n, dtype=np.int64)
    wind = rng.normal(5.0, 2.0, n)
    thrust = rng.uniform(0.97, 1.03, n)
    inputs = pd.DataFrame({"run": run, "wind_speed": wind, "thrust_scale": thrust,
                           "weather_seed": rng.integers(0, 2 ** 31, n).astype(np.int64),
                           "engine": rng.choice(["merlin", "raptor"], n)})
    status = np.array(["ok"] * n, dtype=object)
    status[list(errors)] = "error"
    status[list(timeouts)] = "timeout"
    ok = status == "ok"
    impact = rng.random(n) < 0.1
    east = 60.0 * (wind - 5.0) + rng.normal(0.0, 40.0, n)          # var 3600 * 4 + 1600
    north = -30.0 * (wind - 5.0) + rng.normal(0.0, 25.0, n)
    lat, lon, _ = pymap3d.enu2geodetic(east, north, 0.0, TARGET["latitude_deg"], TARGET["longitude_deg"], 0.0)
    f_east, f_north = rng.uniform(30e3, 60e3, n), rng.normal(-5e3, 3e3, n)
    f_lat, f_lon, _ = pymap3d.enu2geodetic(f_east, f_north, 0.0, TARGET["latitude_deg"], TARGET["longitude_deg"], 0.0)
    periapsis = 200e3 + 5e6 * (thrust - 1.0) + rng.normal(0.0, 2e3, n)
    vertical = 2.0 + 0.1 * wind + rng.normal(0.0, 0.2, n)
    results = pd.DataFrame({
        "run": run, "status": status,
        "error": [{"error": "ValueError: state went non-finite at T+12 s\ntraceback", "timeout": None}.get(s)
                  for s in status],
        "wall_time_s": rng.uniform(1.0, 2.0, n),
        "outcome": np.where(ok, "ok", "ValueError: state went non-finite"),
        "booster.final.time_s": 400.0 + rng.normal(0.0, 5.0, n),
        "booster.touchdown.t_s": np.where(impact, np.nan, 400.0),
        "booster.touchdown.vertical_speed_m_s": np.where(impact, np.nan, vertical),
        "booster.impact.t_s": np.where(impact, 399.0, np.nan),
        "booster.landing.latitude_deg": lat, "booster.landing.longitude_deg": lon,
        "booster.landing.t_s": 400.0,
        "booster.landing.kind": np.where(impact, "impact", "touchdown").astype(object),
        "fairing.final.time_s": 300.0 + rng.normal(0.0, 5.0, n),
        "fairing.impact.t_s": 299.0,
        "fairing.landing.latitude_deg": f_lat, "fairing.landing.longitude_deg": f_lon,
        "fairing.landing.t_s": 299.0, "fairing.landing.kind": np.array(["impact"] * n, dtype=object),
        "stage2.final.altitude_m": 210e3 + rng.normal(0.0, 1e3, n),
        "stage2.orbit.periapsis_altitude": periapsis,
        "stage2.orbit.t_s": np.where(periapsis > 180e3, 500.0, np.nan),
        "stage2.max_q.dynamic_pressure_Pa": 30e3 + 1e3 * wind,
        "stage2.landing.latitude_deg": np.nan, "stage2.landing.longitude_deg": np.nan,
        "stage2.landing.t_s": np.nan, "stage2.landing.kind": np.array([None] * n, dtype=object),
        "summary.mission_time_s": 500.0 + rng.normal(0.0, 1.0, n),
    })
    # what an errored run left is nonsense the report must not count
    bad = ~ok
    results.loc[bad, "booster.touchdown.vertical_speed_m_s"] = 1e6
    results.loc[bad, "booster.touchdown.t_s"] = 1.0
    results.loc[bad, "booster.landing.latitude_deg"] = TARGET["latitude_deg"] + 1.0
    meta = {"name": "synthetic", "seed": seed, "runs": n + 3, "scenario": "/abs/scenario.yaml",
            "dispersions": [{"name": "wind_speed", "path": "weather.wind.speed", "kind": "normal"},
                            {"name": "thrust_scale", "path": "vehicle.thrust", "kind": "uniform"},
                            {"name": "weather_seed", "path": "weather.seed", "kind": "seed"},
                            {"name": "engine", "path": "vehicle.engine", "kind": "choice"}],
            "target": TARGET, "outputs": ["summary.mission_time_s"], "version": "0.1.0"}
    write_campaign(directory, meta, inputs, results)
    truth = {"ok": ok, "impact": impact, "east": east, "north": north, "lat": lat, "lon": lon,
             "vertical": vertical, "periapsis": periapsis}
    return directory, truth


@pytest.fixture(scope="module")
def campaign(tmp_path_factory):
    """The synthetic campaign, its report with plots, and the truth it was built from."""
    directory, truth = synthetic(tmp_path_factory.mktemp("campaign") / "dir")
    plots = directory.parent / "plots"
    return report(directory, plot_dir=plots), truth, plots


def test_counts_errored_and_exit_status(campaign):
    """The statuses written: 3 errors, 1 timeout, 3 runs not finished; the CLI's exit
    status is 1 when any run errored."""
    rep, truth, _ = campaign
    assert rep.errored == 4 and rep.exit_status == 1
    assert rep.counts == {"planned": N + 3, "finished": N, "ok": N - 4, "error": 3, "timeout": 1,
                          "other": 0, "missing": 3}
    assert f"runs: {N + 3} planned, {N} finished: {N - 4} ok, 3 error, 1 timeout; 3 not finished" in rep.text
    assert "errored: 4" in rep.text
    assert "3 x error: ValueError: state went non-finite at T+12 s (runs 3, 50, 77)" in rep.text
    assert "1 x timeout: (no message) (runs 120)" in rep.text


def test_clean_campaign_exits_zero(tmp_path):
    """No errored run: errored 0, exit status 0, no error lines."""
    directory, _ = synthetic(tmp_path / "clean", n=30, errors=(), timeouts=())
    rep = report(directory)
    assert rep.errored == 0 and rep.exit_status == 0 and "errored:" not in rep.text


def test_statistics_are_those_of_the_ok_runs(campaign):
    """Against the construction: the touchdown speed's mean and percentiles over the ok
    runs that touched down (numpy on the values written; the errored runs' 1e6 left out);
    its bootstrap interval holds the mean."""
    rep, truth, _ = campaign
    row = rep.tables["statistics"].loc["booster.touchdown.vertical_speed_m_s"]
    values = truth["vertical"][truth["ok"] & ~truth["impact"]]
    assert row["n"] == values.size
    assert row["mean"] == pytest.approx(values.mean(), rel=1e-12)
    assert row["p99"] == pytest.approx(np.percentile(values, 99), rel=1e-12)
    assert row["max"] == values.max() < 1e6
    assert row["mean_low"] < row["mean"] < row["mean_high"]
    assert "wall_time_s" not in rep.tables["statistics"].index
    assert "booster.touchdown.vertical_speed_m_s" in rep.text


def test_probabilities_are_clopper_pearson_of_the_outcomes(campaign):
    """The booster's touchdowns, impacts and the upper stage's orbits over the ok runs,
    errored runs over the finished ones, each with the beta quantiles
    ``B(0.025; k, n-k+1)``, ``B(0.975; k+1, n-k)`` (scipy.stats.beta) as its interval."""
    rep, truth, _ = campaign
    table = rep.tables["probabilities"].set_index("outcome")
    ok = truth["ok"]
    expected = {"booster touched down (first contact; tip-overs too)": ((ok & ~truth["impact"]).sum(), ok.sum()),
                "booster crashed (impact)": ((ok & truth["impact"]).sum(), ok.sum()),
                "stage2 reached orbit": ((ok & (truth["periapsis"] > 180e3)).sum(), ok.sum()),
                "fairing crashed (impact)": (ok.sum(), ok.sum()),
                "errored (status not ok)": (4, N),
                "outcome 'ok'": (ok.sum(), N)}
    for label, (k, n) in expected.items():
        row = table.loc[label]
        assert (row["k"], row["n"]) == (k, n)
        low = stats.beta.ppf(0.025, k, n - k + 1) if k else 0.0
        high = stats.beta.ppf(0.975, k + 1, n - k) if k < n else 1.0
        assert (row["low"], row["high"]) == pytest.approx((low, high), abs=1e-9)
    assert "booster touched down (first contact; tip-overs too)" in rep.text and "Clopper-Pearson" in rep.text


def test_landing_dispersion_per_body(campaign):
    """The booster and the fairing came down (the upper stage did not): their mean offset
    and R50 about the pad against the east/north that pymap3d.geodetic2enu gives for the
    points written (within 1 mm), the R-circles by counting; the text gives each body's
    ellipses and circles."""
    rep, truth, _ = campaign
    assert list(rep.dispersions) == ["booster", "fairing"]
    ok = truth["ok"]
    lat0, lon0 = TARGET["latitude_deg"], TARGET["longitude_deg"]
    east, north, _ = pymap3d.geodetic2enu(truth["lat"][ok], truth["lon"][ok], 0.0, lat0, lon0, 0.0)
    d = rep.dispersions["booster"]
    assert d.n == ok.sum() and d.kinds.count("impact") == (ok & truth["impact"]).sum()
    assert d.mean == pytest.approx([east.mean(), north.mean()], abs=1e-3)
    row = rep.tables["landing"].loc["booster"]
    distance = np.sort(np.hypot(east, north))
    assert row["r50_target_m"] == pytest.approx(distance[math.ceil(0.5 * d.n) - 1], abs=1e-3)
    assert row["mean_east_m"] == pytest.approx(east.mean(), abs=1e-3)
    assert row["ellipse90_semi_major_m"] > row["ellipse50_semi_major_m"] > row["ellipse50_semi_minor_m"]
    for body in ("booster", "fairing"):
        block = rep.text.split(f"  {body}: ")[1].split("\n\n")[0]
        for p in ("50 %", "90 %", "99 %"):
            assert f"{p}: semi-axes" in block
        assert "circles about the target: R50" in block and "circles about the mean: R50" in block
    assert "stage2:" not in rep.text.split("landing dispersion")[1].split("sensitivities")[0]


def test_sensitivities_rank_the_driving_input(campaign):
    """The booster's east offset is 60 m per m/s of wind plus 40 m of noise: SRC
    ``60 * 2 / sqrt(60^2 * 4 + 40^2) = 0.949`` (sampling error ~0.01 at 236 runs, tolerance
    0.03); the periapsis follows the thrust. Seeds and string choices are not ranked."""
    rep, truth, _ = campaign
    table = rep.tables["sensitivities"]
    east = table[table["output"] == "booster.landing.east_m"].set_index("input")
    assert east.loc["wind_speed", "src"] == pytest.approx(120.0 / math.sqrt(16000.0), abs=0.03)
    assert abs(east.loc["wind_speed", "spearman"]) > 5 * abs(east.loc["thrust_scale", "spearman"])
    periapsis = table[table["output"] == "stage2.orbit.periapsis_altitude"].set_index("input")
    assert periapsis["spearman"].abs().idxmax() == "thrust_scale"
    assert set(table["input"]) == {"wind_speed", "thrust_scale"}
    assert "not ranked: weather_seed (a seed), engine (not numeric)" in rep.text
    line = next(s for s in rep.text.splitlines() if s.startswith("  booster.landing.east_m (R^2"))
    assert line.split(": ", 1)[1].startswith("wind_speed rho +0.9")


def test_plots_and_geojson_are_written(campaign):
    """landing.png, histograms.png, sensitivities.png (PNG signature, not empty) and
    landing.geojson (JSON without NaN: the target and both bodies' ellipses)."""
    rep, _, plots = campaign
    names = sorted(p.name for p in rep.files)
    assert names == ["histograms.png", "landing.geojson", "landing.png", "sensitivities.png"]
    for path in rep.files:
        assert path.parent == plots and path.stat().st_size > 1000
        if path.suffix == ".png":
            assert path.read_bytes()[:8] == PNG
    collection = json.loads((plots / "landing.geojson").read_text(), parse_constant=lambda c: pytest.fail(c))
    ellipses = [f["properties"]["body"] for f in collection["features"] if f["properties"]["feature"] == "ellipse"]
    assert ellipses == ["booster"] * 3 + ["fairing"] * 3


def test_rows_not_yet_gathered_are_noted(tmp_path):
    """A campaign still flying (or stopped before it gathered its rows) has part files
    beside results.parquet: the report reads only results.parquet and says so."""
    directory, _ = synthetic(tmp_path / "flying", n=20, errors=(), timeouts=())
    (directory / "results").mkdir()
    for k in range(2):
        (directory / "results" / f"part-{k:06d}.parquet").write_bytes(b"")
    rep = report(directory)
    assert rep.counts["finished"] == 20
    assert "note: 2 part files" in rep.text and "--resume" in rep.text


def test_the_same_directory_gives_the_same_report(campaign, tmp_path):
    """Deterministic: the same files (copied elsewhere) give the same text and tables,
    bootstrap intervals included."""
    rep, _, _ = campaign
    directory, _ = synthetic(tmp_path / "again")
    again = report(directory)
    assert again.text == rep.text
    pd.testing.assert_frame_equal(again.tables["statistics"], rep.tables["statistics"])


def test_no_matplotlib_without_plots(campaign):
    """A report without plot_dir never imports matplotlib (a fresh interpreter)."""
    rep, _, _ = campaign
    code = ("import sys; from rocketsim.campaigns.report import report; "
            f"report({str(rep.directory)!r}); print('matplotlib' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "False"


def test_a_campaign_with_no_finished_run(tmp_path):
    """Nothing finished yet: every count is zero but the planned, nothing to describe."""
    directory, _ = synthetic(tmp_path / "full")
    results = pd.read_parquet(directory / "results.parquet").iloc[:0]
    results.to_parquet(directory / "results.parquet")
    rep = report(directory)
    assert rep.counts["finished"] == 0 and rep.counts["missing"] == N + 3 and rep.errored == 0
    assert "(no run flew to its end)" in rep.text and "(no body came down on Earth in an ok run)" in rep.text


def test_bad_directories_are_input_errors_naming_the_file(tmp_path):
    """A missing directory or file, JSON that is not, a target latitude that is not a number, a
    results table without status, a file that is not Parquet: InputError naming the file
    (and the line or the field)."""
    with pytest.raises(InputError, match="no such campaign directory"):
        report(tmp_path / "nowhere")
    directory, _ = synthetic(tmp_path / "bad", n=20, errors=(), timeouts=())
    meta = directory / "meta.json"
    good = meta.read_text()
    meta.write_text(good.replace('"seed": 7,', '"seed": 7,,'))
    with pytest.raises(InputError) as error:
        report(directory)
    assert error.value.file == str(meta) and error.value.line == 3
    meta.write_text(json.dumps({**json.loads(good), "target": {"latitude_deg": "28.5 N", "longitude_deg": -80.5}}))
    with pytest.raises(InputError) as error:
        report(directory)
    assert error.value.field == "target.latitude_deg" and error.value.file == str(meta)
    meta.write_text(good)
    results = directory / "results.parquet"
    pd.read_parquet(results).drop(columns="status").to_parquet(results)
    with pytest.raises(InputError) as error:
        report(directory)
    assert error.value.field == "status" and error.value.file == str(results)
    results.write_bytes(b"not parquet at all")
    with pytest.raises(InputError, match="not a readable Parquet file"):
        report(directory)
    results.unlink()
    with pytest.raises(InputError, match="no results.parquet .*--resume"):
        report(directory)
    meta.unlink()
    with pytest.raises(InputError, match="no meta.json"):
        report(directory)


def test_bodies_with_few_landings(tmp_path):
    """One landing has circles but no ellipses (three points are the fewest a covariance
    ellipse takes); two landings on one spot have circles of radius 0, left out of the
    GeoJSON (a polygon of no area). The figures against the construction (pymap3d)."""
    directory, truth = synthetic(tmp_path / "few", n=12, errors=(), timeouts=())
    results = pd.read_parquet(directory / "results.parquet")
    results.loc[1:, ["booster.landing.latitude_deg", "booster.landing.longitude_deg"]] = np.nan
    results.loc[2:, ["fairing.landing.latitude_deg", "fairing.landing.longitude_deg"]] = np.nan
    results.loc[1, ["fairing.landing.latitude_deg", "fairing.landing.longitude_deg"]] = \
        results.loc[0, ["fairing.landing.latitude_deg", "fairing.landing.longitude_deg"]].to_numpy()
    results.to_parquet(directory / "results.parquet")
    rep = report(directory)
    booster, fairing = rep.dispersions["booster"], rep.dispersions["fairing"]
    assert booster.n == 1 and not booster.ellipses and fairing.n == 2
    east, north, _ = pymap3d.geodetic2enu(truth["lat"][0], truth["lon"][0], 0.0,
                                          TARGET["latitude_deg"], TARGET["longitude_deg"], 0.0)
    assert booster.circles[0].radius_m == pytest.approx(math.hypot(east, north), abs=1e-3)
    assert all(c.radius_m == 0.0 for c in fairing.circles if c.about == "mean")
    assert rep.text.count("no ellipses: fewer than 3 points") == 2
    collection = geojson(TARGET, rep.dispersions.values())
    circles = [(f["properties"]["body"], f["properties"]["about"]) for f in collection["features"]
               if f["properties"]["feature"] == "circle"]
    assert circles == [("booster", "target")] * 3 + [("fairing", "target")] * 3


def test_many_outcome_strings_are_counted_and_the_text_lists_the_commonest(tmp_path):
    """Twelve distinct error outcomes (one run each) and the ok ones: the table counts each
    (k = 1 of 30), the text lists the 8 commonest (ok first) and says how many it left out."""
    directory, _ = synthetic(tmp_path / "outcomes", n=30, errors=tuple(range(12)), timeouts=())
    results = pd.read_parquet(directory / "results.parquet")
    results.loc[:11, "outcome"] = [f"RuntimeError: program failed at step {k}" for k in range(12)]
    results.to_parquet(directory / "results.parquet")
    rep = report(directory)
    table = rep.tables["probabilities"]
    outcomes = table[table["outcome"].str.startswith("outcome ")]
    assert len(outcomes) == 13 and outcomes.iloc[0]["outcome"] == "outcome 'ok'" and outcomes.iloc[0]["k"] == 18
    assert (outcomes.iloc[1:]["k"] == 1).all() and (outcomes["n"] == 30).all()
    assert sum(line.startswith("  outcome ") for line in rep.text.splitlines()) == 8
    assert "... and 5 rarer outcome strings" in rep.text


def test_an_insertion_campaign_leads_with_its_share_within_tolerance(tmp_path):
    """The insertion's share (of the 8 ok runs, 4 within: the exact Clopper-Pearson
    interval of 4 in 8 is [15.7 %, 84.3 %]) comes before the tables, where a reader looks
    first."""
    directory, _ = synthetic(tmp_path / "insertion", n=10, errors=(0,), timeouts=(1,))
    results = pd.read_parquet(directory / "results.parquet")
    within = np.array([0.0, 0.0, 1.0, 1.0, 0.0, 1.0, 1.0, 0.0, np.nan, np.nan])
    results["stage2.insertion.within_tolerance"] = within
    for error in ("periapsis_error_m", "apoapsis_error_m", "inclination_error_deg"):
        results[f"stage2.insertion.{error}"] = 0.5
    results.to_parquet(directory / "results.parquet")
    meta = json.loads((directory / "meta.json").read_text())
    meta["insertion"] = {"periapsis_m": 2e3, "apoapsis_m": 2e3, "inclination_deg": 0.02}
    (directory / "meta.json").write_text(json.dumps(meta))
    lines = report(directory).text.splitlines()
    share = lines.index("  stage2: 4 of 8 ok runs, 50 % [15.7 %, 84.3 %]")
    assert lines[share - 1].startswith("insertion within tolerance")
    assert share < next(i for i, line in enumerate(lines) if line.startswith("outputs over"))


def test_no_target_position_and_landings_elsewhere(tmp_path):
    """A scenario without a pad or a site has a target of NaN degrees (what the engine
    writes): no dispersion, no GeoJSON, the rest of the report as ever. A body whose final
    central body is the Moon came down on no WGS84 map: left out of the dispersion, counted."""
    directory, truth = synthetic(tmp_path / "nowhere", n=20, errors=(), timeouts=())
    meta = json.loads((directory / "meta.json").read_text())
    (directory / "meta.json").write_text(json.dumps(
        {**meta, "target": {"name": None, "latitude_deg": math.nan, "longitude_deg": math.nan, "kind": "site"}}))
    rep = report(directory, plot_dir=tmp_path / "plots")
    assert rep.dispersions == {} and "target has no position" in rep.text
    assert sorted(p.name for p in rep.files) == ["histograms.png", "sensitivities.png"]
    assert rep.tables["probabilities"].set_index("outcome").loc["booster crashed (impact)", "n"] == 20
    (directory / "meta.json").write_text(json.dumps(meta))
    results = pd.read_parquet(directory / "results.parquet")
    results["fairing.orbit.central_body"] = ["moon"] * 5 + ["earth"] * 15
    results.to_parquet(directory / "results.parquet")
    rep = report(directory)
    assert rep.dispersions["fairing"].n == 15 and rep.dispersions["booster"].n == 20
    assert "fairing: 5 landings about another central body are not in the dispersion" in rep.text
    assert rep.tables["statistics"].loc["fairing.landing.east_m", "n"] == 15
