"""``rocketsim ephemeris``: the csv and table outputs and the input errors."""

from __future__ import annotations

import datetime as dt

import numpy as np
from click.testing import CliRunner

from rocketsim.ephemeris import solar_system
from rocketsim.timescales import Epoch
from rocketsim_cli.main import main


def _run(*args):
    return CliRunner().invoke(main, ["ephemeris", *args])


def test_csv_columns_rows_and_values():
    result = _run("--body", "moon", "--from", "2026-03-01", "--to", "2026-03-02",
                  "--step", "6h", "--format", "csv")
    assert result.exit_code == 0, result.output
    lines = result.output.strip().splitlines()
    assert lines[0] == "utc,tt_jd,x_km,y_km,z_km,vx_km_s,vy_km_s,vz_km_s"
    assert len(lines) == 1 + 5                       # 00h, 06h, 12h, 18h, 24h
    fields = lines[3].split(",")
    assert fields[0] == "2026-03-01T12:00:00Z"
    # the Moon's default centre is the Earth; TT = UTC + Delta T (~75 s in 2026)
    jd_tt = Epoch.from_utc(dt.datetime(2026, 3, 1, 12, tzinfo=dt.timezone.utc)).jd_tt()
    assert abs(float(fields[1]) - jd_tt) < 1e-6
    assert 60.0 < (jd_tt - 2461101.0) * 86400.0 < 90.0
    r, v = solar_system.state("moon", jd_tt, center="earth")
    assert np.allclose([float(f) for f in fields[2:5]], r / 1e3, atol=1e-3)
    assert np.allclose([float(f) for f in fields[5:8]], v / 1e3, atol=1e-6)


def test_table_has_distances_and_elongation():
    # Mars was in conjunction with the Sun on 2026 January 9 (small
    # elongation) and at quadrature-like angles months later.
    result = _run("--body", "mars", "--from", "2026-01-01", "--to", "2026-02-01", "--step", "10d")
    assert result.exit_code == 0, result.output
    rows = [line.split() for line in result.output.splitlines()[2:]]
    assert len(rows) == 4
    elongations = [float(row[-1]) for row in rows]
    assert min(elongations) < 3.0
    assert all(1.38 < float(row[4]) < 1.67 for row in rows)        # au from the Sun


def test_bad_input_exits_2_with_one_line():
    for args, field in ((("--step", "6x"), "--step"), (("--step", "-1d"), "--step"),
                        (("--from", "2026-13-01"), "--from"),
                        (("--from", "2027-01-01"), "--to")):
        options = {"--from": "2026-01-01", "--to": "2026-02-01", "--step": "1d"}
        options.update(dict(zip(args[::2], args[1::2])))
        result = _run("--body", "moon", *[x for kv in options.items() for x in kv])
        assert result.exit_code == 2, result.output
        assert field in result.output and "Traceback" not in result.output
