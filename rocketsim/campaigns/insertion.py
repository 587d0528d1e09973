"""How close each run of a campaign put its vehicle to the mission's target orbit.

A campaign with an ``insertion:`` block (its tolerances) measures the ascent's
insertion: for the scenario's vehicle (the run's first body), the state of its
first sample at or after its ``orbit`` event (the truth, the first coasting
step of an orbit whose periapsis clears 100 km: the engine's cut-off and
tail-off done) gives the insertion orbit, in the elements the target is stated
in: Kozai mean elements unless the mission's target says ``elements:
osculating`` (:mod:`rocketsim.frames.mean_elements`: for a circular target the
osculating radius ripples by some 6 km at 200 km and the inclination by
0.04 deg with the argument of latitude, which the mean elements leave out).

Columns of a run's row (``<body>`` the vehicle's name; NaN when it never reached orbit):

* ``<body>.insertion.time_s``: the sample's mission time, s;
* ``<body>.insertion.periapsis_altitude_m``, ``.apoapsis_altitude_m`` (above the
  equatorial radius) and ``.inclination_deg`` of the insertion orbit;
* ``.periapsis_error_m``, ``.apoapsis_error_m``, ``.inclination_error_deg``: those
  less the target's (a circular orbit: its altitude for both apsides);
* ``.within_tolerance``: 1.0 when all three errors are within the tolerances, else 0.0
  (also when the vehicle never reached orbit).

The report gives the share of the ok runs within tolerance with its exact
Clopper-Pearson interval (:func:`report_lines`).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from rocketsim.campaigns import statistics
from rocketsim.constants import EARTH_MU, EARTH_RADIUS_EQ
from rocketsim.frames.elements import state_to_elements
from rocketsim.frames.mean_elements import mean_elements_of_state
from rocketsim.scenario.units import STRICT, Angle, Length

from pydantic import BaseModel, Field, field_serializer

ERRORS = ("periapsis_error_m", "apoapsis_error_m", "inclination_error_deg")


class InsertionTolerance(BaseModel):
    """The ``insertion:`` block of a campaign file: how far from the target orbit an
    insertion may be and still count (each a quantity with its unit)."""

    model_config = STRICT

    periapsis: Length = Field(description="largest periapsis altitude error")
    apoapsis: Length = Field(description="largest apoapsis altitude error")
    inclination: Angle = Field(description="largest inclination error")

    @field_serializer("inclination")
    def _with_unit(self, value: float) -> str:
        """As a file holds it (an angle needs its unit): the resolved campaign reads back."""
        return f"{value!r} rad"


def insertion_columns(run, target, tolerance: InsertionTolerance) -> dict[str, Any]:
    """The columns (see the module) of a :class:`~rocketsim.api.run.Run` whose mission
    aims at ``target`` (the scenario's ``mission.target.orbit``: ``altitude``,
    ``inclination`` SI, ``elements``)."""
    body = next(iter(run.bodies.values()))
    prefix = f"{body.name}.insertion"
    row = {f"{prefix}.{key}": math.nan for key in ("time_s", "periapsis_altitude_m", "apoapsis_altitude_m",
                                                    "inclination_deg", *ERRORS)}
    row[f"{prefix}.within_tolerance"] = 0.0
    events = body.events
    orbit = events[events["name"] == "orbit"] if len(events) else events
    if not len(orbit):
        return row
    table = body.table()
    after = table[table.index >= float(orbit["t_s"].iloc[0])]
    if not len(after):
        return row
    sample = after.iloc[0]
    r = np.array([sample[f"position_{c}_m"] for c in "xyz"])
    v = np.array([sample[f"velocity_{c}_m_s"] for c in "xyz"])
    elements = mean_elements_of_state(r, v) if target.elements == "mean" else state_to_elements(r, v, EARTH_MU)
    figures = {"time_s": float(after.index[0]),
               "periapsis_altitude_m": elements.periapsis - EARTH_RADIUS_EQ,
               "apoapsis_altitude_m": elements.apoapsis - EARTH_RADIUS_EQ,
               "inclination_deg": math.degrees(elements.i)}
    figures["periapsis_error_m"] = figures["periapsis_altitude_m"] - target.altitude
    figures["apoapsis_error_m"] = figures["apoapsis_altitude_m"] - target.altitude
    figures["inclination_error_deg"] = figures["inclination_deg"] - math.degrees(target.inclination)
    within = (abs(figures["periapsis_error_m"]) <= tolerance.periapsis
              and abs(figures["apoapsis_error_m"]) <= tolerance.apoapsis
              and abs(figures["inclination_error_deg"]) <= math.degrees(tolerance.inclination))
    row.update({f"{prefix}.{key}": value for key, value in figures.items()})
    row[f"{prefix}.within_tolerance"] = 1.0 if within else 0.0
    return row


def report_lines(tolerance: dict | None, results, ok) -> list[str]:
    """The report's lines on the insertion (none without ``tolerance``, meta.json's
    ``insertion``: ``periapsis_m``, ``apoapsis_m``, ``inclination_deg``): per body with
    a ``within_tolerance`` column, the share of the ``ok`` runs (a boolean mask of
    ``results``' rows) within tolerance with its Clopper-Pearson interval, and the
    spread of each error (its 1st, 50th and 99th percentiles and the largest)."""
    if not tolerance:
        return []
    confidence = f"{100 * statistics.CONFIDENCE:g} %"
    lines = [f"insertion within tolerance (periapsis and apoapsis within {tolerance['periapsis_m'] / 1e3:g} km "
             f"and {tolerance['apoapsis_m'] / 1e3:g} km, inclination within {tolerance['inclination_deg']:g} deg "
             f"of the target; {confidence} exact Clopper-Pearson interval)"]
    for column in [c for c in results.columns if c.endswith(".insertion.within_tolerance")]:
        within = results[column].to_numpy(float)[ok]
        k, n = int(np.sum(within == 1.0)), int(within.size)
        p, low, high = statistics.proportion(k, n)
        body = column.split(".")[0]
        lines.append(f"  {body}: {k} of {n} ok runs, {_percent(p)} [{_percent(low)}, {_percent(high)}]")
        for error in ERRORS:
            values = results[f"{body}.insertion.{error}"].to_numpy(float)[ok]
            values = values[np.isfinite(values)]
            if values.size:
                p1, p50, p99 = np.percentile(values, (1.0, 50.0, 99.0))
                lines.append(f"    {error}: p1 {p1:.4g}, median {p50:.4g}, p99 {p99:.4g}, "
                             f"largest |error| {np.max(np.abs(values)):.4g}")
    return lines + [""]


def _percent(x) -> str:
    return "-" if not np.isfinite(x) else f"{100 * x:.3g} %"
