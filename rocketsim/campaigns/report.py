"""The report of a Monte Carlo campaign: what its runs did, how often, where they came down,
and which dispersed input drove each output.

:func:`report` reads only the three files of the campaign directory (``meta.json``,
``inputs.parquet``, ``results.parquet``: the layout of the campaign engine) and gives a
:class:`Report`:

- ``statistics``: per output column (every numeric column of the results but ``run`` and
  ``wall_time_s``, plus each landing body's ``<body>.landing.east_m``, ``.north_m`` and
  ``.offset_m``, its east, north and distance about the target), over the runs that flew to
  their end (status ``ok``): :func:`rocketsim.campaigns.statistics.describe`;
- ``probabilities``: errored runs and each outcome string over the finished runs, and each
  body's events (landed: a touchdown, crashed: an impact, reached orbit, broke up, came
  down, and every other event that has a column) over the ``ok`` runs, with exact
  Clopper-Pearson intervals;
- ``outcomes``: per body with landing outcomes (``<body>.landing.outcome``: upright on
  target, upright off target, hard landing, tipped over, impact, ran dry, broke up, under
  a parachute; :func:`rocketsim.campaigns.landing.landing_outcome`), the share of the
  ``ok`` runs of each, ``not down`` for the rest, with exact Clopper-Pearson intervals.
  The text leads with the *landing body* (the one that lit an engine and came down
  softly most often): its upright-on-target share, the miss and touchdown speeds of its
  upright landings and the propellant they kept (``final.usable_propellant_kg``: mean and
  1st percentile, with bootstrap intervals), then, for a campaign with insertion
  tolerances, the share of runs inserted within them (:mod:`rocketsim.campaigns.insertion`);
- ``landing``: per body that came down on Earth: the mean offset, standard deviations and
  correlation of the east/north scatter, the 50/90/99 % covariance ellipses (chi-square
  with 2 degrees of freedom) and the R50/R90/R99 circles about the target and about the
  mean (:mod:`rocketsim.campaigns.landing`); a body with landing outcomes has two
  scatters, ``<body> upright`` (its upright landings) and ``<body> crashed`` (tipped
  over, impacts, ran dry), so an ellipse never mixes a pad's landings with wrecks;
- ``sensitivities``: per output and numeric dispersed input (a seed is not ranked: its
  value has no order that means anything, nor is a choice among strings), Spearman's rho
  and the standardized regression coefficients with the fit's R².

The *main outputs* (at most 16, those that vary) are the campaign's own ``outputs:``, then
each body's landing offsets, touchdown speeds and tilt, orbit and final altitude and speed:
the text names their three strongest inputs, and they are the histograms and tornadoes.
With ``plot_dir`` the report also writes ``landing.png`` (the scatter on a local map with
the coastline), ``histograms.png``, ``sensitivities.png`` (:func:`rocketsim.plots.campaign`,
which draws them from a :class:`Report` in a notebook too) and ``landing.geojson`` there.
Everything the report says follows from the files and the campaign's seed: the same directory gives the same report, bootstrap
intervals included. The tables are computed by :mod:`rocketsim.campaigns.report_tables`, the
text written by :mod:`rocketsim.campaigns.report_text`.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from pathlib import Path

from rocketsim.campaigns import insertion, landing, report_tables, report_text, statistics
from rocketsim.errors import InputError
from rocketsim.extras import needs

META, INPUTS, RESULTS = "meta.json", "inputs.parquet", "results.parquet"


@dataclass
class Report:
    """A campaign's report: ``text`` (what ``rocketsim campaign report`` prints), ``errored``
    (finished runs whose status is not ``ok``), ``counts`` (planned, finished, by status,
    missing), ``tables`` (pandas DataFrames ``statistics``, ``probabilities``, ``landing``,
    ``sensitivities``), ``dispersions`` (by body, :class:`~rocketsim.campaigns.landing.Dispersion`),
    what the plots draw (``flown``: the ok runs' outputs with each landing body's offsets
    about the target, a DataFrame; ``main``: the main outputs; ``target``: meta.json's, or
    None without a position; ``name``: the campaign's) and ``files`` (the plots and the
    GeoJSON written)."""

    directory: Path
    text: str
    errored: int
    counts: dict
    tables: dict
    dispersions: dict
    flown: object
    main: list
    target: dict | None
    name: str
    files: list = field(default_factory=list)

    @property
    def exit_status(self) -> int:
        """What the command line exits with: 1 when a run errored or timed out, else 0."""
        return 1 if self.errored else 0


def load(directory) -> tuple:
    """``(meta, inputs, results)`` of the campaign ``directory``, or an InputError naming the
    file (and the line and field) that is missing or wrong. ``results`` keeps the last row
    of a run written twice and is sorted by ``run``."""
    needs("campaign", "a campaign's report", "pyarrow")
    import pandas as pd
    directory = Path(directory)
    if not directory.is_dir():
        raise InputError("no such campaign directory", file=directory)
    path = directory / META
    try:
        meta = json.loads(path.read_text())
    except FileNotFoundError:
        raise InputError("the campaign directory has no meta.json (is it a campaign's?)", file=path) from None
    except json.JSONDecodeError as exc:
        raise InputError(f"not JSON: {exc.msg}", file=path, line=exc.lineno, column=exc.colno) from None
    if not isinstance(meta, dict):
        raise InputError("expected a JSON object", file=path, line=1)
    target = meta.get("target")
    if target is not None and not isinstance(target, dict):
        raise InputError("expected a mapping (name, latitude_deg, longitude_deg, kind) or null",
                         file=path, field="target")
    for key in ("latitude_deg", "longitude_deg"):
        value = (target or {}).get(key)
        if value is not None and (not isinstance(value, (int, float)) or isinstance(value, bool)):
            raise InputError("expected a number (degrees) or null", file=path, field=f"target.{key}")
    tables = []
    for name, needed in ((INPUTS, ("run",)), (RESULTS, ("run", "status"))):
        path = directory / name
        if not path.exists():
            hint = (" (no run has finished yet, or its rows are still in results/part-*.parquet: "
                    "`rocketsim campaign run CAMPAIGN -o DIR --resume` gathers them)") if name == RESULTS else ""
            raise InputError(f"the campaign directory has no {name}{hint}", file=path)
        try:
            frame = pd.read_parquet(path)
        except Exception as exc:          # pyarrow's errors have no common base but Exception
            raise InputError(f"not a readable Parquet file: {exc}", file=path) from None
        for column in needed:
            if column not in frame.columns:
                raise InputError("missing column", file=path, field=column)
        tables.append(frame)
    inputs, results = tables
    results = results.drop_duplicates("run", keep="last").sort_values("run", kind="stable").reset_index(drop=True)
    return meta, inputs, results


def report(directory, plot_dir=None) -> Report:
    """The :class:`Report` of the campaign in ``directory`` (see the module); with ``plot_dir``
    (created if need be) the plots and ``landing.geojson`` are written there."""
    import pandas as pd
    directory = Path(directory)
    meta, inputs, results = load(directory)
    target = report_tables.target_of(meta)
    extra = set(meta.get("outputs") or [])
    status = results["status"].astype(str)
    ok = (status == "ok").to_numpy()
    planned = int(meta["runs"]) if isinstance(meta.get("runs"), int) else len(inputs)
    counts = {"planned": planned, "finished": len(results), "ok": int(ok.sum()),
              "error": int((status == "error").sum()), "timeout": int((status == "timeout").sum())}
    counts["other"] = counts["finished"] - counts["ok"] - counts["error"] - counts["timeout"]
    counts["missing"] = max(0, planned - counts["finished"])
    errored = counts["finished"] - counts["ok"]

    outputs = results.copy()
    bodies = report_tables.bodies_of(results.columns, extra)
    dispersions, elsewhere = report_tables.landings(outputs, ok, bodies, target)
    numeric = [c for c in outputs.columns if c not in report_tables.NOT_OUTPUTS
               and pd.api.types.is_numeric_dtype(outputs[c]) and not pd.api.types.is_bool_dtype(outputs[c])]
    flown = outputs[ok]

    rows = {c: statistics.describe(flown[c].to_numpy(float), report_tables.bootstrap_seed(meta, c)) for c in numeric}
    stats_table = pd.DataFrame.from_dict(rows, orient="index")
    stats_table.index.name = "output"
    stats_table = stats_table[stats_table["n"] > 0] if len(stats_table) else stats_table

    probabilities = report_tables.probabilities_table(results, status, ok, bodies, extra)
    outcomes = report_tables.outcomes_table(results, ok, bodies)
    headline = report_tables.headline(meta, outputs, ok, outcomes)
    landing_table = report_tables.landing_table(dispersions)
    sensitivities, ranked, unranked = report_tables.sensitivities(meta, inputs, flown, list(stats_table.index))
    main = report_tables.main_outputs(stats_table, bodies, meta.get("outputs") or [])

    tables = {"statistics": stats_table, "probabilities": probabilities, "outcomes": outcomes,
              "landing": landing_table, "sensitivities": sensitivities}
    text = report_text.plain_text(meta, counts, results, status, stats_table, probabilities, dispersions,
                                  elsewhere, target, sensitivities, main, ranked, unranked, headline,
                                  insertion.report_lines(meta.get("insertion"), results, ok))
    parts = len(list((directory / "results").glob("part-*.parquet")))
    if parts:       # rows the engine has not yet gathered into results.parquet
        text += (f"\nnote: {parts} part files in {directory / 'results'} are not yet in results.parquet; "
                 "their runs are not in this report (`rocketsim campaign run CAMPAIGN -o DIR --resume` "
                 "gathers them)\n")
    out = Report(directory, text, errored, counts, tables, dispersions, flown, main, target,
                 meta.get("name") or directory.name)
    if plot_dir is not None:
        from rocketsim.plots import campaign as plot_campaign
        plot_dir = Path(plot_dir)
        out.files = plot_campaign(out, plot_dir)
        if target is not None:
            path = plot_dir / "landing.geojson"
            path.write_text(json.dumps(landing.geojson(target, dispersions.values()), indent=1, allow_nan=False))
            out.files.append(path)
    return out


