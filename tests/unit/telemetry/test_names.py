"""Every name rocketsim writes has one meaning and, in a column, its unit.

Walked here: the state message's schema, the tables of flown runs (in memory and read
from their files), the CSV and Parquet exports and events.csv, the events' figures and
the summaries, of flights that between them reach every kind of body and ending: the
hobby rocket (a staged vehicle off a rail, parachutes, a touchdown; its whole flight),
the sounding payload's ballistic arc (a rigid body, an impact), the ISS coast (a rigid
body in orbit, a minute) and the first 170 s of the Falcon 9 mission (engines, tanks,
a separation, the booster's return begun) at 0.1 s steps.

What is checked:

* each column is one the glossary (:mod:`rocketsim.telemetry.names`) defines, named
  with its unit or one of the glossary's unitless ones (ratios, counts, text);
* each figure of a summary is one the glossary defines; each of an event too, or (a
  shipped program's own) named with its unit; none is a name that says no reference
  (``speed_m_s``, ``height_m``: :data:`~rocketsim.telemetry.names.AMBIGUOUS`);
* a name an event, the summary and a table share means the same there: where a table
  has a sample at an event's instant, or the summary's final state, the two agree
  (to the centimetre and the mm/s a step moves them), which a height above the ground
  against the ellipsoid's (1 380 m apart at Spaceport America) or an inertial speed
  against a speed over the ground (390 m/s apart there) would not.
"""

from __future__ import annotations

import csv
import math

import numpy as np
import pytest

import rocketsim
from rocketsim import api
from rocketsim.telemetry import names
from rocketsim.telemetry.schemas import BODY_STATE
from tests.conftest import ROOT

SCENARIOS = ROOT / "scenarios"
FLIGHTS = {"hobby-rocket": {}, "spaceport-ballistic": {}, "iss-coast": {"duration": 60.0},
           "falcon9-leo": {"duration": 170.0, "step": 0.1}}
# figures that are text, lists or counts the events carry (what, by whom, which)
TEXT = {"motor", "parachute", "trigger", "by", "stage", "cause", "engines", "motors", "from", "to",
        "separated_body", "from_body", "payload_body", "reason", "central_body", "landing_kind"}


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    folder = tmp_path_factory.mktemp("names")
    return {name: rocketsim.fly(SCENARIOS / f"{name}.yaml", folder / f"{name}.mcap", **options)
            for name, options in FLIGHTS.items()}


def _known(column: str) -> bool:
    if column in names.COLUMNS:
        return True
    return any(column.startswith(group.split("*")[0]) and column.endswith(group.split("*")[1])
               for group in names.COLUMNS if "*" in group)


def test_every_field_of_the_state_is_in_the_glossary():
    fields = set(BODY_STATE["properties"]) - {"orbit", "group_throttle", "group_thrust", "propellant_tanks"}
    vectors = {"position", "velocity", "body_rates", "attitude"}
    for field in fields - vectors:
        assert names.column_name(field) in names.COLUMNS, field
    for key in BODY_STATE["properties"]["orbit"]["properties"]:
        assert names.column_name(f"orbit_{key}") in names.COLUMNS, key


def test_every_column_has_its_unit_and_one_meaning(runs, tmp_path):
    for name, run in runs.items():
        for body, part in run.bodies.items():
            for table in (part.table(), rocketsim.open_run(run.path).bodies[body].table()):
                assert table.index.name == "t_s"
                for column in table.columns:
                    assert _known(column), (name, body, column)
                    assert names.has_unit(column) or column in names.UNITLESS or \
                        column.startswith("group_throttle_"), (name, column)
        written = api.export_tables(run.path, tmp_path / name, "csv")
        for path in written:
            with open(path, newline="") as stream:
                header = next(csv.reader(stream))
            if path.name == "events.csv":
                assert header[:3] == ["t_s", "body", "name"]
                for figure in header[3:]:
                    base = figure.split("[")[0]
                    assert base not in names.AMBIGUOUS, (name, figure)
            else:
                table = run.bodies[path.stem].table()
                assert header == ["t_s", *table.columns], (name, path.name)
    pyarrow_parquet = pytest.importorskip("pyarrow.parquet")
    run = runs["hobby-rocket"]
    written = api.export_tables(run.path, tmp_path / "pq", "parquet")
    columns = pyarrow_parquet.read_table(written[0]).column_names
    assert columns == ["t_s", *run.bodies["hobby-rocket"].table().columns]


def _flat(prefix: str, value, out: dict) -> None:
    if isinstance(value, dict):
        for key, item in value.items():
            _flat(key, item, out)
    elif isinstance(value, list) and value and isinstance(value[0], dict):
        for item in value:
            _flat(prefix, item, out)
    else:
        out.setdefault(prefix, value)


def test_every_figure_of_the_events_and_summaries_is_in_the_glossary(runs):
    for name, run in runs.items():
        figures = {}
        for body in run.summary["bodies"].values():
            for part in ("final", "orbit", "flight", "touchdown"):
                _flat(part, body.get(part, {}), figures)
        for key in figures:
            assert key not in names.AMBIGUOUS, (name, key)
            assert key in names.FIGURES or key in TEXT or key in ("position_m", "velocity_m_s"), (name, key)
        for event in run.file.events:
            for key in event["figures"]:
                assert key not in names.AMBIGUOUS, (name, event["name"], key)
                assert key in names.FIGURES or key in TEXT or names.has_unit(key), (name, event["name"], key)


def test_a_name_shared_by_events_summary_and_tables_means_the_same(runs):
    checked = set()
    tolerance = {"_deg": 1e-6, "_m": 0.05, "_m_s": 0.05, "_Pa": 1.0, "": 1e-9}
    for name, run in runs.items():
        for event in run.file.events:
            if "at_s" in event["figures"]:
                continue                    # the figures of another instant than the event's
            table = run.bodies[event["body"]].table()
            t = round(event["t"], 6)
            if t not in table.index:
                continue
            row = table.loc[t]
            if isinstance(row, type(table)):
                row = row.iloc[-1]          # a handover's or a landing's second sample
            for key, value in event["figures"].items():
                if key in row.index and isinstance(value, float) and math.isfinite(row[key]):
                    limit = next(v for s, v in sorted(tolerance.items(), key=lambda x: -len(x[0]))
                                 if key.endswith(s))
                    assert abs(value - row[key]) <= limit, (name, event["name"], key, value, row[key])
                    checked.add(key)
        for body, part in run.summary["bodies"].items():
            final, table = part["final"], run.bodies[body].table()
            last = table.iloc[-1]
            for key in ("altitude_m", "inertial_speed_m_s", "surface_speed_m_s", "latitude_deg"):
                assert final[key] == pytest.approx(last[key], abs=1e-6), (name, body, key)
                checked.add(key)
    print(f"\n[names] compared: {sorted(checked)}")
    assert {"height_agl_m", "surface_speed_m_s", "altitude_m", "inertial_speed_m_s"} <= checked
    hobby = runs["hobby-rocket"].bodies["hobby-rocket"].table()
    apart = hobby["altitude_m"] - hobby["height_agl_m"]
    assert np.all(apart == 1380.0)
    assert (hobby["inertial_speed_m_s"] - hobby["surface_speed_m_s"]).abs().max() > 300.0
