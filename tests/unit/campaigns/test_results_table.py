"""The results table a campaign writes and reads (rocketsim.campaigns.store.frame): one row
per run, the later row of a run winning, sorted by run, the leading columns first and the
others by name; ``run`` int64, a column holding any string a string column (None where
missing: pandas may hold it as NaN, a number in it written as text), every other float64 (NaN
where missing)."""

import math

import numpy as np
import pandas as pd

from rocketsim.campaigns.store import LEADING, frame


def texts(column) -> list:
    """A string column's values, None where missing."""
    assert column.dtype == object or pd.api.types.is_string_dtype(column.dtype)
    return [None if pd.isna(value) else value for value in column]


def test_rows_and_tables_make_one_table_of_the_documented_types(tmp_path):
    first = [{"run": 2, "status": "ok", "error": None, "wall_time_s": 1.5, "outcome": "landed",
              "b.miss_m": 3.0, "a.count": 4, "a.flag": True, "c.note": None, "d.label": "x"},
             {"run": 0, "status": "error", "error": "boom", "wall_time_s": 0.5, "outcome": "boom",
              "b.miss_m": None, "a.count": 5, "a.flag": False, "c.note": None, "d.label": 2.5}]
    path = tmp_path / "part.parquet"
    frame([first]).to_parquet(path, index=False)
    again = [{"run": 2, "status": "ok", "error": None, "wall_time_s": 9.0, "outcome": "tipped",
              "b.miss_m": 7.0, "a.count": 6, "a.flag": True, "c.note": None, "d.label": "y"},
             {"run": 1, "status": "timeout", "error": "late", "wall_time_s": 20.0, "outcome": "timeout",
              "a.flag": False}]
    table = frame([pd.read_parquet(path), again])
    assert list(table.columns) == LEADING + ["a.count", "a.flag", "b.miss_m", "c.note", "d.label"]
    assert table["run"].dtype == np.int64 and table["run"].tolist() == [0, 1, 2]
    assert table["status"].tolist() == ["error", "timeout", "ok"]
    assert texts(table["error"]) == ["boom", "late", None]
    assert table["outcome"].tolist() == ["boom", "timeout", "tipped"]        # run 2's later row
    assert table["wall_time_s"].tolist() == [0.5, 20.0, 9.0]
    for name, expected in (("a.count", [5.0, math.nan, 6.0]), ("a.flag", [0.0, 0.0, 1.0]),
                           ("b.miss_m", [math.nan, math.nan, 7.0])):
        assert table[name].dtype == np.float64
        np.testing.assert_array_equal(table[name].to_numpy(), expected)
    assert texts(table["c.note"]) == [None, None, None]      # never set: a column of no string
    assert texts(table["d.label"]) == ["2.5", None, "y"]     # a string column: the number as text


def test_no_rows_make_the_leading_columns_alone():
    table = frame([[], pd.DataFrame()])
    assert list(table.columns) == LEADING and len(table) == 0
    assert table["run"].dtype == np.int64 and table["wall_time_s"].dtype == np.float64


def test_a_store_consolidates_the_parts_it_wrote_as_they_read_back(tmp_path, monkeypatch):
    from rocketsim.campaigns import store as store_module
    rows = [{"run": 2, "status": "ok", "error": None, "wall_time_s": 1.25, "outcome": "landed",
             "b.miss_m": 0.1 + 0.2, "c.note": None, "d.label": "x"},
            {"run": 1, "status": "error", "error": "boom", "wall_time_s": 0.5, "outcome": "boom"},
            {"run": 0, "status": "ok", "error": None, "wall_time_s": 2.0, "outcome": "tipped",
             "b.miss_m": -0.0, "c.note": None, "d.label": 7.5, "e.extra": math.inf},
            {"run": 1, "status": "ok", "error": None, "wall_time_s": 3.0, "outcome": "landed again",
             "b.miss_m": 1e-300, "c.note": None, "d.label": "z"}]
    monkeypatch.setattr(store_module, "FLUSH_S", 0.0)          # a part file per row
    store = store_module.Store(tmp_path / "campaign")
    store.parts.mkdir(parents=True)
    (tmp_path / "campaign" / "results").mkdir(exist_ok=True)
    store.add(rows[0])
    store.consolidate()                                       # results.parquet, then parts on top of it
    for row in rows[1:]:
        store.add(row)
    parts = sorted(store.parts.glob("part-*.parquet"))
    assert len(parts) == 3
    expected = frame([pd.read_parquet(tmp_path / "campaign" / "results.parquet")]
                     + [pd.read_parquet(part) for part in parts])
    store.consolidate()
    assert not list(store.parts.glob("part-*.parquet"))
    found = pd.read_parquet(tmp_path / "campaign" / "results.parquet")
    assert list(found.columns) == list(expected.columns) and found["run"].tolist() == [0, 1, 2]
    assert found["outcome"].tolist() == ["tipped", "landed again", "landed"]
    for name in found.columns:
        a, b = found[name].to_numpy(), expected[name].to_numpy()
        if a.dtype.kind == "f":
            assert a.dtype == b.dtype and a.tobytes() == b.tobytes(), name
        else:
            assert [None if pd.isna(v) else v for v in a] == [None if pd.isna(v) else v for v in b], name
