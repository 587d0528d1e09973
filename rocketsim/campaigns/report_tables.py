"""The tables of a campaign's report (:mod:`rocketsim.campaigns.report`), each from the
campaign's files alone: its bodies, its landing scatters about the target, the outcomes and
probabilities with exact Clopper-Pearson intervals, the landing body's headline figures, the
sensitivities of each output to the dispersed inputs, and the main outputs drawn and printed.
Bootstrap streams come from the campaign's seed and each output's name."""

from __future__ import annotations

import re
import zlib

import numpy as np

from rocketsim.campaigns import landing, statistics
from rocketsim.campaigns.outputs import BODY_SECTIONS

MAIN_OUTPUTS = 16                     # histograms and sensitivities drawn and printed at most
NOT_OUTPUTS = ("run", "wall_time_s")
_EVENT_LABELS = {"touchdown": "touched down (first contact; tip-overs too)", "impact": "crashed (impact)",
                 "orbit": "reached orbit", "breakup": "broke up", "tip-over": "tipped over after landing",
                 "landing": "came down (touchdown or impact)"}
# the summary figures worth a histogram, by section, in this order (after the campaign's own outputs)
_MAIN = (("landing", ("offset_m", "east_m", "north_m")),
         ("touchdown", ("vertical_speed_m_s", "horizontal_speed_m_s", "tilt_deg", "distance_to_target_m")),
         ("orbit", ("periapsis_altitude_m", "apoapsis_altitude_m", "inclination_deg", "eccentricity")),
         ("flight", ("apogee_height_agl_m", "max_surface_speed_m_s", "max_sensed_acceleration_g")),
         ("final", ("altitude_m", "surface_speed_m_s")))


def bodies_of(columns, extra) -> list[str]:
    """The bodies named by ``<body>.<section>.<key>`` columns, in the order they come."""
    found = {}
    for column in columns:
        if column in extra:
            continue
        parts = column.split(".")
        if len(parts) >= 3 and parts[1] in BODY_SECTIONS:
            found.setdefault(parts[0], None)
    return list(found)


def bootstrap_seed(meta: dict, name: str) -> list[int]:
    """The bootstrap stream of the output ``name``: from the campaign's seed and the name
    alone (not from the column's place in the file)."""
    seed = meta.get("seed")
    return [int(seed) if isinstance(seed, int) and seed >= 0 else 0, zlib.crc32(name.encode())]


def target_of(meta: dict) -> dict | None:
    """meta.json's target, or None when it has no position (a scenario without a site)."""
    target = meta.get("target") or {}
    position = [target.get("latitude_deg"), target.get("longitude_deg")]
    if any(v is None or not np.isfinite(v) for v in position):
        return None
    return target


def landings(outputs, ok, bodies, target) -> tuple[dict, dict]:
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


def outcomes_table(results, ok, bodies):
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


def headline(meta, outputs, ok, outcomes) -> dict | None:
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
                                         bootstrap_seed(meta, name))
    return {"body": body, "outcomes": outcomes[outcomes["body"] == body], "figures": figures,
            "propellant": propellant}


def probabilities_table(results, status, ok, bodies, extra):
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


def landing_table(dispersions):
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


def sensitivities(meta, inputs, flown, outputs):
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


def main_outputs(stats_table, bodies, asked) -> list[str]:
    """The outputs drawn and printed with their sensitivities: the campaign's own outputs,
    then per body its landing offsets, touchdown, orbit and final figures, those that vary."""
    varied = set(stats_table.index[stats_table["std"] > 0]) if len(stats_table) else set()
    names = [c for c in asked if c in varied]
    for section, keys in _MAIN:
        for body in bodies:
            names += [f"{body}.{section}.{k}" for k in keys if f"{body}.{section}.{k}" in varied]
    return list(dict.fromkeys(names))[:MAIN_OUTPUTS]
