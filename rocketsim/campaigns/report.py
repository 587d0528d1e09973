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
  1st percentile, with bootstrap intervals);
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
intervals included. The bootstraps cost most: about 0.3 s per output per 10 000 runs
(measured: 23 outputs of 10 000 runs in 8.8 s on a loaded 2-core machine).
"""

from __future__ import annotations

import json
import re
import zlib
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from rocketsim.campaigns import insertion, landing, statistics
from rocketsim.campaigns.outputs import BODY_SECTIONS
from rocketsim.errors import InputError
from rocketsim.extras import needs

META, INPUTS, RESULTS = "meta.json", "inputs.parquet", "results.parquet"
MAIN_OUTPUTS = 16                     # histograms and sensitivities drawn and printed at most
OUTCOMES_PRINTED = 8                  # the most frequent outcome strings the text lists
TOP_INPUTS = 3                        # inputs the text names per output
_NOT_OUTPUTS = ("run", "wall_time_s")
_EVENT_LABELS = {"touchdown": "touched down (first contact; tip-overs too)", "impact": "crashed (impact)",
                 "orbit": "reached orbit", "breakup": "broke up", "tip-over": "tipped over after landing",
                 "landing": "came down (touchdown or impact)"}
# the summary figures worth a histogram, by section, in this order (after the campaign's own outputs)
_MAIN = (("landing", ("offset_m", "east_m", "north_m")),
         ("touchdown", ("vertical_speed_m_s", "horizontal_speed_m_s", "tilt_deg", "distance_to_target_m")),
         ("orbit", ("periapsis_altitude_m", "apoapsis_altitude_m", "inclination_deg", "eccentricity")),
         ("flight", ("apogee_height_agl_m", "max_surface_speed_m_s", "max_sensed_acceleration_g")),
         ("final", ("altitude_m", "surface_speed_m_s")))


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


def _bodies(columns, extra) -> list[str]:
    """The bodies named by ``<body>.<section>.<key>`` columns, in the order they come."""
    found = {}
    for column in columns:
        if column in extra:
            continue
        parts = column.split(".")
        if len(parts) >= 3 and parts[1] in BODY_SECTIONS:
            found.setdefault(parts[0], None)
    return list(found)


def _seed(meta: dict, name: str) -> list[int]:
    """The bootstrap stream of the output ``name``: from the campaign's seed and the name
    alone (not from the column's place in the file)."""
    seed = meta.get("seed")
    return [int(seed) if isinstance(seed, int) and seed >= 0 else 0, zlib.crc32(name.encode())]


def _fmt(x, digits: int = 4) -> str:
    if x is None or (isinstance(x, float) and not np.isfinite(x)):
        return "-"
    return f"{x:.{digits}g}"


def _interval(low, high, digits: int = 4) -> str:
    if not (np.isfinite(low) and np.isfinite(high)):
        return "-"
    return f"[{_fmt(low, digits)}, {_fmt(high, digits)}]"


def _percent(x) -> str:
    return "-" if not np.isfinite(x) else f"{100 * x:.3g} %"


def report(directory, plot_dir=None) -> Report:
    """The :class:`Report` of the campaign in ``directory`` (see the module); with ``plot_dir``
    (created if need be) the plots and ``landing.geojson`` are written there."""
    import pandas as pd
    directory = Path(directory)
    meta, inputs, results = load(directory)
    target = _target(meta)
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
    bodies = _bodies(results.columns, extra)
    dispersions, elsewhere = _landings(outputs, ok, bodies, target)
    numeric = [c for c in outputs.columns if c not in _NOT_OUTPUTS
               and pd.api.types.is_numeric_dtype(outputs[c]) and not pd.api.types.is_bool_dtype(outputs[c])]
    flown = outputs[ok]

    rows = {c: statistics.describe(flown[c].to_numpy(float), _seed(meta, c)) for c in numeric}
    stats_table = pd.DataFrame.from_dict(rows, orient="index")
    stats_table.index.name = "output"
    stats_table = stats_table[stats_table["n"] > 0] if len(stats_table) else stats_table

    probabilities = _probabilities(results, status, ok, bodies, extra)
    outcomes = _outcomes(results, ok, bodies)
    headline = _headline(meta, outputs, ok, outcomes)
    landing_table = _landing_table(dispersions)
    sensitivities, ranked, unranked = _sensitivities(meta, inputs, flown, list(stats_table.index))
    main = _main_outputs(stats_table, bodies, meta.get("outputs") or [])

    tables = {"statistics": stats_table, "probabilities": probabilities, "outcomes": outcomes,
              "landing": landing_table, "sensitivities": sensitivities}
    text = _text(meta, counts, results, status, stats_table, probabilities, dispersions, elsewhere,
                 target, sensitivities, main, ranked, unranked, headline)
    text += "\n".join(["", *insertion.report_lines(meta.get("insertion"), results, ok)])
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


def _target(meta: dict) -> dict | None:
    """meta.json's target, or None when it has no position (a scenario without a site)."""
    target = meta.get("target") or {}
    position = [target.get("latitude_deg"), target.get("longitude_deg")]
    if any(v is None or not np.isfinite(v) for v in position):
        return None
    return target


def _landings(outputs, ok, bodies, target) -> tuple[dict, dict]:
    """``(dispersions, elsewhere)``: each body's :class:`~rocketsim.campaigns.landing.Dispersion`
    over the ok runs where it came down on Earth, and per body the number of ok runs where it
    came down about another central body (the final orbit's ``central_body``: a lunar
    landing has no east/north on WGS84). Adds each body's ``<body>.landing.east_m``,
    ``.north_m`` and ``.offset_m`` (m, about the target) to ``outputs``."""
    import pandas as pd
    dispersions, elsewhere = {}, {}
    if target is None:
        return dispersions, elsewhere
    for body in bodies:
        lat, lon = f"{body}.landing.latitude_deg", f"{body}.landing.longitude_deg"
        if lat not in outputs or lon not in outputs:
            continue
        central = outputs.get(f"{body}.orbit.central_body")
        on_earth = np.ones(len(outputs), dtype=bool) if central is None else \
            np.array([pd.isna(c) or c == "earth" for c in central])
        east, north = landing.east_north(outputs[lat].to_numpy(float), outputs[lon].to_numpy(float),
                                         target["latitude_deg"], target["longitude_deg"])
        east[~on_earth] = np.nan
        north[~on_earth] = np.nan
        outputs[f"{body}.landing.east_m"] = east
        outputs[f"{body}.landing.north_m"] = north
        outputs[f"{body}.landing.offset_m"] = np.hypot(east, north)
        away = int((ok & ~on_earth & np.isfinite(outputs[lat].to_numpy(float))).sum())
        if away:
            elsewhere[body] = away
        down = ok & np.isfinite(east) & np.isfinite(north)
        kinds = outputs.get(f"{body}.landing.kind")
        kinds = np.array(["" if pd.isna(k) else str(k) for k in kinds] if kinds is not None else [""] * len(down))
        outcome = _outcome_column(outputs, body)
        groups = [(body, down)]
        if outcome is not None and np.isin(outcome[down], (*landing.UPRIGHT, "tipped over")).any():
            upright = np.isin(outcome, landing.UPRIGHT)
            groups = [(f"{body} upright", down & upright), (f"{body} crashed", down & ~upright)]
        for name, chosen in groups:
            if chosen.any():
                dispersions[name] = landing.dispersion(name, east[chosen], north[chosen], list(kinds[chosen]))
    return dispersions, elsewhere


def _outcome_column(outputs, body):
    """The body's landing outcomes (strings, '' for none) or None without the column."""
    import pandas as pd
    column = outputs.get(f"{body}.landing.outcome")
    if column is None:
        return None
    return np.array(["" if pd.isna(v) else str(v) for v in column], dtype=object)


def _outcomes(results, ok, bodies):
    """Per body with landing outcomes, the share of the ok runs of each (and ``not down``)."""
    import pandas as pd
    rows = []
    n_ok = int(ok.sum())
    for body in bodies:
        outcome = _outcome_column(results, body)
        if outcome is None:
            continue
        flown = outcome[ok]
        for name in (*landing.OUTCOMES, "not down"):
            k = int(np.sum(flown == ("" if name == "not down" else name)))
            if k == 0 and name in ("under a parachute", "not down"):
                continue
            p, low, high = statistics.proportion(k, n_ok)
            rows.append({"body": body, "outcome": name, "k": k, "n": n_ok, "p": p, "low": low, "high": high})
    return pd.DataFrame(rows, columns=["body", "outcome", "k", "n", "p", "low", "high"])


def _headline(meta, outputs, ok, outcomes) -> dict | None:
    """The landing body's headline figures (see the module), or None without one: the body
    with landing outcomes that lit an engine (an ``ignition`` column) and came down upright
    most often, then the one with the most outcomes."""
    if not len(outcomes):
        return None

    def rank(body):
        rows = outcomes[outcomes["body"] == body]
        upright = int(rows[rows["outcome"].isin(landing.UPRIGHT)]["k"].sum())
        powered = f"{body}.ignition.t_s" in outputs and bool(np.isfinite(outputs[f"{body}.ignition.t_s"]).any())
        return (powered, upright, int(rows[rows["outcome"] != "not down"]["k"].sum()))

    body = max(dict.fromkeys(outcomes["body"]), key=rank)
    if rank(body)[2] == 0:
        return None
    outcome = _outcome_column(outputs, body)
    upright = ok & np.isin(outcome, landing.UPRIGHT)
    figures = {}
    for key, column in (("miss", f"{body}.touchdown.distance_to_target_m"),
                        ("down", f"{body}.touchdown.vertical_speed_m_s"),
                        ("sideways", f"{body}.touchdown.horizontal_speed_m_s"),
                        ("tilt", f"{body}.touchdown.tilt_deg")):
        if column in outputs:
            figures[key] = np.abs(outputs[column].to_numpy(float)[upright])
    propellant = None
    if f"{body}.final.usable_propellant_kg" in outputs:
        name = f"{body}.final.usable_propellant_kg (upright landings)"
        propellant = statistics.describe(outputs[f"{body}.final.usable_propellant_kg"].to_numpy(float)[upright],
                                         _seed(meta, name))
    return {"body": body, "outcomes": outcomes[outcomes["body"] == body], "figures": figures,
            "propellant": propellant}


def _probabilities(results, status, ok, bodies, extra):
    """The table of named outcomes (see the module)."""
    import pandas as pd
    rows = []
    finished = len(results)

    def add(label, k, n, of):
        p, low, high = statistics.proportion(int(k), int(n))
        rows.append({"outcome": label, "k": int(k), "n": int(n), "of": of, "p": p, "low": low, "high": high})

    add("errored (status not ok)", (status != "ok").sum(), finished, "finished runs")
    for name in ("error", "timeout"):
        add(f"status {name}", (status == name).sum(), finished, "finished runs")
    if "outcome" in results:
        outcome = results["outcome"].dropna().astype(str)
        for value, k in sorted(outcome.value_counts().items(), key=lambda vk: (-vk[1], vk[0])):
            add(f"outcome {value!r}", k, finished, "finished runs")
    n_ok = int(ok.sum())
    pattern = re.compile(r"^(?P<body>[^.]+)\.(?P<event>[^.]+)\.t_s$")
    for body in bodies:
        events = [m.group("event") for c in results.columns if c not in extra
                  for m in [pattern.match(c)] if m and m.group("body") == body and m.group("event") != "final"]
        order = {e: i for i, e in enumerate(_EVENT_LABELS)}
        for event in sorted(events, key=lambda e: (order.get(e, len(order)), events.index(e))):
            happened = np.isfinite(results[f"{body}.{event}.t_s"].to_numpy(float)) & ok
            add(f"{body} {_EVENT_LABELS.get(event, f'event {event!r}')}", happened.sum(), n_ok, "ok runs")
    return pd.DataFrame(rows, columns=["outcome", "k", "n", "of", "p", "low", "high"])


def _landing_table(dispersions):
    """One row per body: the scatter's figures (see the module)."""
    import pandas as pd
    rows = {}
    for body, d in dispersions.items():
        row = {"n": d.n, "touchdowns": d.kinds.count("touchdown"), "impacts": d.kinds.count("impact"),
               "mean_east_m": d.mean[0], "mean_north_m": d.mean[1],
               "mean_offset_m": float(np.hypot(*d.mean)),
               "std_east_m": float(np.sqrt(d.covariance[0, 0])), "std_north_m": float(np.sqrt(d.covariance[1, 1])),
               "correlation": float(d.covariance[0, 1] / np.sqrt(d.covariance[0, 0] * d.covariance[1, 1]))
               if d.n > 1 and d.covariance[0, 0] > 0 and d.covariance[1, 1] > 0 else np.nan}
        for e in d.ellipses:
            tag = f"ellipse{100 * e.probability:g}"
            row |= {f"{tag}_semi_major_m": e.semi_major_m, f"{tag}_semi_minor_m": e.semi_minor_m,
                    f"{tag}_azimuth_deg": e.azimuth_deg, f"{tag}_share": e.share}
        for c in d.circles:
            row[f"r{100 * c.probability:g}_{c.about}_m"] = c.radius_m
        rows[body] = row
    table = pd.DataFrame.from_dict(rows, orient="index")
    table.index.name = "body"
    return table


def _sensitivities(meta, inputs, flown, outputs):
    """``(table, ranked inputs, unranked inputs with why)``: Spearman and SRC of every
    output against the numeric, varying, non-seed inputs, over the ok runs."""
    import pandas as pd
    kinds = {d.get("name"): d.get("kind") for d in meta.get("dispersions") or [] if isinstance(d, dict)}
    joined = flown[["run"]].merge(inputs, on="run", how="left")
    ranked, unranked = [], {}
    for column in inputs.columns:
        if column == "run":
            continue
        if kinds.get(column) == "seed":
            unranked[column] = "a seed"
        elif not pd.api.types.is_numeric_dtype(inputs[column]) or pd.api.types.is_bool_dtype(inputs[column]):
            unranked[column] = "not numeric"
        elif joined[column].nunique(dropna=True) < 2:
            unranked[column] = "constant over the ok runs"
        else:
            ranked.append(column)
    rows = []
    if ranked:
        x = joined[ranked].to_numpy(float)
        for output in outputs:
            result = statistics.sensitivity(x, flown[output].to_numpy(float))
            if not np.isfinite(result["spearman"]).any():
                continue
            for j, name in enumerate(ranked):
                rows.append({"output": output, "input": name, "n": result["n"],
                             "spearman": result["spearman"][j], "spearman_p": result["spearman_p"][j],
                             "src": result["src"][j], "r2": result["r2"]})
    table = pd.DataFrame(rows, columns=["output", "input", "n", "spearman", "spearman_p", "src", "r2"])
    return table, ranked, unranked


def _main_outputs(stats_table, bodies, asked) -> list[str]:
    """The outputs drawn and printed with their sensitivities: the campaign's own outputs,
    then per body its landing offsets, touchdown, orbit and final figures, those that vary."""
    varied = set(stats_table.index[stats_table["std"] > 0]) if len(stats_table) else set()
    names = [c for c in asked if c in varied]
    for section, keys in _MAIN:
        for body in bodies:
            names += [f"{body}.{section}.{k}" for k in keys if f"{body}.{section}.{k}" in varied]
    return list(dict.fromkeys(names))[:MAIN_OUTPUTS]


def _headline_text(headline, target) -> list[str]:
    """The landing body's lines of the text (see :func:`_headline`)."""
    body, rows = headline["body"], headline["outcomes"].set_index("outcome")
    where = "the target" if target is None else f"the {target.get('kind') or 'target'} {target.get('name') or ''}".strip()
    confidence = f"{100 * statistics.CONFIDENCE:g} %"
    n = int(rows["n"].iloc[0])
    on = rows.loc["upright on target"]
    lines = [f"landing of {body} at {where}, over the {n} ok runs ({confidence} Clopper-Pearson intervals):",
             f"  upright within {landing.ON_TARGET_RADIUS:g} m: {on.k} of {n}, {_percent(on.p)} "
             f"[{_percent(on.low)}, {_percent(on.high)}]"]
    others = [f"{name} {int(row.k)} ({_percent(row.p)} [{_percent(row.low)}, {_percent(row.high)}])"
              for name, row in rows.iterrows() if name != "upright on target"]
    lines.append("  then: " + "; ".join(others))
    figures = headline["figures"]
    labels = {"miss": ("miss", "m"), "down": ("touchdown down", "m/s"), "sideways": ("touchdown sideways", "m/s"),
              "tilt": ("tilt at touchdown", "deg")}
    for key, values in figures.items():
        if values.size:
            label, unit = labels[key]
            lines.append(f"  {label} (upright landings, {values.size}): median {_fmt(float(np.median(values)))}, "
                         f"p90 {_fmt(float(np.percentile(values, 90)))}, p99 {_fmt(float(np.percentile(values, 99)))}, "
                         f"max {_fmt(float(values.max()))} {unit}")
    left = headline["propellant"]
    if left is not None and left["n"]:
        lines.append(f"  usable propellant left at touchdown (upright landings, {left['n']}): mean "
                     f"{_fmt(left['mean'])} kg {_interval(left['mean_low'], left['mean_high'])}, 1st percentile "
                     f"{_fmt(left['p1'])} kg {_interval(left['p1_low'], left['p1_high'])}, least {_fmt(left['min'])} kg")
    lines.append("")
    return lines


def _text(meta, counts, results, status, stats_table, probabilities, dispersions, elsewhere,
          target, sensitivities, main, ranked, unranked, headline=None) -> str:
    """The plain-text report (see :class:`Report`)."""
    import pandas as pd
    lines = [f"campaign {meta.get('name') or '?'}: seed {meta.get('seed')}, "
             f"scenario {meta.get('scenario') or '?'}",
             f"runs: {counts['planned']} planned, {counts['finished']} finished: {counts['ok']} ok, "
             f"{counts['error']} error, {counts['timeout']} timeout"
             + (f", {counts['other']} other" if counts["other"] else "")
             + (f"; {counts['missing']} not finished" if counts["missing"] else "")]
    failed = results[status != "ok"]
    if len(failed):
        lines.append(f"errored: {len(failed)}")
        messages = failed["error"] if "error" in failed else [None] * len(failed)
        groups: dict = {}
        for run, st, message in zip(failed["run"], failed["status"], messages):
            first = "" if pd.isna(message) else (str(message).strip().splitlines() or [""])[0]
            groups.setdefault((str(st), first[:100]), []).append(int(run))
        for (st, message), runs in groups.items():
            shown = ", ".join(map(str, runs[:8])) + (", ..." if len(runs) > 8 else "")
            lines.append(f"  {len(runs)} x {st}: {message or '(no message)'} (runs {shown})")
    lines.append("")
    if headline is not None:
        lines += _headline_text(headline, target)

    confidence = f"{100 * statistics.CONFIDENCE:g} %"
    lines.append(f"outputs over the {counts['ok']} ok runs (mean and std with {confidence} bootstrap "
                 f"intervals: {statistics.BOOTSTRAP_METHOD} method, {statistics.N_RESAMPLES} resamples; "
                 "percentiles linear; intervals of every percentile in the statistics table)")
    if len(stats_table):
        width = max(len("output"), *(len(c) for c in stats_table.index))
        head = (f"  {'output':<{width}} {'n':>5} {'mean':>11} {'[' + confidence + ' interval]':<25}"
                f" {'std':>11} {'[' + confidence + ' interval]':<25}"
                + "".join(f" {'p' + format(p, 'g'):>11}" for p in statistics.PERCENTILES)
                + f" {'min':>11} {'max':>11}")
        lines.append(head)
        for name, row in stats_table.iterrows():
            digits = 9 if name.endswith(("latitude_deg", "longitude_deg")) else 4   # 9: 0.1 m
            lines.append(f"  {name:<{width}} {int(row['n']):>5} {_fmt(row['mean'], digits):>11} "
                         f"{_interval(row['mean_low'], row['mean_high'], digits):<25}"
                         f" {_fmt(row['std']):>11} {_interval(row['std_low'], row['std_high']):<25}"
                         + "".join(f" {_fmt(row[f'p{p:g}'], digits):>11}" for p in statistics.PERCENTILES)
                         + f" {_fmt(row['min'], digits):>11} {_fmt(row['max'], digits):>11}")
    else:
        lines.append("  (no run flew to its end)")
    lines.append("")

    lines.append(f"probabilities ({confidence} exact Clopper-Pearson intervals)")
    outcomes = probabilities["outcome"].str.startswith("outcome ")
    hidden = probabilities[outcomes].index[OUTCOMES_PRINTED:]
    shown = probabilities.drop(index=hidden)
    if len(shown):
        width = min(60, max(len(s) for s in shown["outcome"]))
        for row in shown.itertuples():
            label = row.outcome if len(row.outcome) <= width else row.outcome[:width - 4] + " ...'"
            lines.append(f"  {label:<{width}} {row.k:>5} of {row.n:<5} {row.of:<13} {_percent(row.p):>8}"
                         f"  [{_percent(row.low)}, {_percent(row.high)}]")
    if len(hidden):
        lines.append(f"  ... and {len(hidden)} rarer outcome strings (the probabilities table has them all)")
    lines.append("")

    if target is None:
        lines.append("landing dispersion: none (meta.json's target has no position: no pad, no site)")
    else:
        where = f"{target.get('kind') or 'target'} {target.get('name') or ''}".strip()
        lines.append(f"landing dispersion about the {where} ({target['latitude_deg']:.6f} N, "
                     f"{target['longitude_deg']:.6f} E), east/north on WGS84, m")
        if not dispersions:
            lines.append("  (no body came down on Earth in an ok run)")
    for body, count in elsewhere.items():
        lines.append(f"  {body}: {count} landings about another central body are not in the dispersion")
    for body, d in dispersions.items():
        kinds = {k: d.kinds.count(k) for k in dict.fromkeys(d.kinds) if k}
        how = ", ".join(f"{n} {k}" for k, n in kinds.items())
        lines.append(f"  {body}: {d.n} points" + (f" ({how})" if how else ""))
        lines.append(f"    mean offset: east {_fmt(d.mean[0])} m, north {_fmt(d.mean[1])} m "
                     f"({_fmt(float(np.hypot(*d.mean)))} m from the target)")
        if d.n > 1:
            lines.append(f"    std: east {_fmt(float(np.sqrt(d.covariance[0, 0])))} m, "
                         f"north {_fmt(float(np.sqrt(d.covariance[1, 1])))} m; covariance "
                         f"[[{_fmt(d.covariance[0, 0])}, {_fmt(d.covariance[0, 1])}], "
                         f"[{_fmt(d.covariance[1, 0])}, {_fmt(d.covariance[1, 1])}]] m^2")
        if d.ellipses:
            lines.append("    ellipses of the fitted normal (2-D probability P: k = sqrt(-2 ln(1 - P)), "
                         "not 1-D sigmas), about the mean:")
            for e in d.ellipses:
                lines.append(f"      {_percent(e.probability):>6}: semi-axes {_fmt(e.semi_major_m)} x "
                             f"{_fmt(e.semi_minor_m)} m, major axis azimuth {e.azimuth_deg:.1f} deg; "
                             f"holds {_percent(e.share)} of the points")
        else:
            lines.append("    no ellipses: fewer than 3 points")
        for about in ("target", "mean"):
            circles = [c for c in d.circles if c.about == about]
            lines.append(f"    circles about the {about}: "
                         + ", ".join(f"R{100 * c.probability:g} {_fmt(c.radius_m)} m" for c in circles))
    lines.append("")

    lines.append("sensitivities (Spearman rank correlation rho; standardized regression coefficient SRC "
                 "with the linear fit's R^2)")
    if ranked:
        lines.append("  inputs ranked: " + ", ".join(ranked))
    if unranked:
        lines.append("  not ranked: " + ", ".join(f"{k} ({why})" for k, why in unranked.items()))
    shown = 0
    for output in main:
        rows = sensitivities[sensitivities["output"] == output]
        if not len(rows):
            continue
        rows = rows.assign(order=-rows["spearman"].abs().fillna(-1.0)).sort_values("order", kind="stable")
        top = "; ".join(f"{r.input} rho {r.spearman:+.2f} SRC {_fmt(r.src, 2) if np.isfinite(r.src) else '-'}"
                        for r in rows.head(TOP_INPUTS).itertuples())
        lines.append(f"  {output} (R^2 {_fmt(rows['r2'].iloc[0], 2)}, n {rows['n'].iloc[0]}): {top}")
        shown += 1
    if not shown:
        lines.append("  (none: no varying output against a varying input)")
    return "\n".join(lines) + "\n"
