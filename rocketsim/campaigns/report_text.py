"""The plain text of a campaign's report (:mod:`rocketsim.campaigns.report`): what ``rocketsim
campaign report`` prints, from the tables of :mod:`rocketsim.campaigns.report_tables`."""

from __future__ import annotations

import numpy as np

from rocketsim.campaigns import landing, statistics

OUTCOMES_PRINTED = 8                  # the most frequent outcome strings the text lists
TOP_INPUTS = 3                        # inputs the text names per output


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


def _headline_text(headline, target) -> list[str]:
    """The landing body's lines of the text (see :func:`headline`)."""
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


def plain_text(meta, counts, results, status, stats_table, probabilities, dispersions, elsewhere,
               target, sensitivities, main, ranked, unranked, headline=None, insertion=()) -> str:
    """The plain-text report (see :class:`Report`): its lines on the landing body
    (``headline``) and on the insertion (``insertion``), the campaign's answers, lead;
    the tables follow."""
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
    lines += insertion

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
