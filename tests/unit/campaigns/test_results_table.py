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
