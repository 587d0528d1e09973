"""campaigns/ndrt-landing.yaml, flown small: 4 runs in this process at a 50 ms step.

Reference: each run's descent and drift, estimated independently of the simulator
from the day's ERA5 file itself (read with xarray, a peer used only in tests: the
site's column interpolated to the run's launch time, heights from the geopotential
over g0, the density ``p / (R_d T)`` of dry air on each pressure level, as the days are
flown dry) and the run's own dispersed inputs (inputs.parquet): falling at the
terminal speed ``sqrt(2 m g / (rho C_D S))`` of the canopies open at each height
(the drogue from apogee, the main from where it has filled: its trigger height less
the drogue's speed times its lag and half its inflation, the centroid of the linear
growth) and drifting with the wind, the descent takes ``T = int dh / v(h)`` and the
drift from the apogee's point to the landing point is ``D = int w(h) / v(h) dh``.

Bounds: the descent time within 5 % (the estimate leaves out the 1 s free fall before
the drogue pulls and the approach to each terminal speed: about 3 %); the drift within
20 % of ``|D|`` as a vector (the rocket leaves apogee moving upwind, weathercocked,
and takes a few seconds under the drogue to drift with the air: about 100 m of
700 m). And the rows hold together: each landing is a touchdown under the main, and
its distance from the pad is the landing point's (pymap3d, 1e-3). The flights are
the campaign's at a 50 ms step instead of 20 ms (the landing point moves under a
metre), about a second each.
"""

import math
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import rocketsim
from rocketsim.scenario.yaml_source import read_yaml

xr = pytest.importorskip("xarray")
pymap3d = pytest.importorskip("pymap3d")

ROOT = Path(__file__).resolve().parents[2]
CAMPAIGN = ROOT / "campaigns" / "ndrt-landing.yaml"
WEATHER = ROOT / "scenarios" / "measured" / "weather" / "ndrt_2020_weather_data_ERA5.nc"
LAT, LON, PAD = 41.775447, -86.572467, 206.0        # the site (scenarios/measured/ndrt-2020.yaml)
EPOCH = np.datetime64("2020-02-23T16:00:00")
CASE = 4.323 - 2.475                  # kg, the 4895L1395's case (its .eng header)
SECTION = math.pi / 4 * 0.203 ** 2    # m^2, the body's, falling tail first at C_A 0.85
MAIN_HEIGHT, LAG, INFLATION = 167.64, 1.0, 1.0      # the vehicle file's main parachute
G = 9.803                             # m/s^2, normal gravity at 42 deg N near the ground
R_DRY = 287.05                        # J/(kg K)


def estimate(row) -> tuple[float, float, float]:
    """``(descent time s, drift east m, drift north m)`` from apogee of one run's inputs."""
    when = EPOCH + np.timedelta64(int(round(row["launch_time"])), "s")
    day = xr.open_dataset(WEATHER)
    column = day.interp(latitude=LAT, longitude=LON, time=when).load()
    order = np.argsort(column["z"].values)
    height = column["z"].values[order] / 9.80665 - PAD
    density = column["level"].values[order] * 100.0 / (R_DRY * column["t"].values[order])
    east, north = column["u"].values[order], column["v"].values[order]
    mass = row["dry_mass"] + CASE
    drogue = row["drogue"] + 0.85 * SECTION

    def speed(h, area):
        return np.sqrt(2 * mass * G / (np.interp(h, height, density) * area))

    filled = MAIN_HEIGHT - speed(MAIN_HEIGHT, drogue) * (LAG + 0.5 * INFLATION)
    h = np.linspace(0.0, row["apogee"], 20001)
    slowness = 1.0 / speed(h, np.where(h < filled, drogue + row["main"], drogue))
    return (float(np.trapezoid(slowness, h)), float(np.trapezoid(slowness * np.interp(h, height, east), h)),
            float(np.trapezoid(slowness * np.interp(h, height, north), h)))


def test_the_landing_rows_match_the_days_drift(tmp_path):
    data = read_yaml(CAMPAIGN).data
    data["runs"] = 4
    data["overrides"]["step"] = "50 ms"
    results = rocketsim.campaign(data, tmp_path / "ndrt", workers=1, base_dir=CAMPAIGN.parent)
    inputs = pd.read_parquet(tmp_path / "ndrt" / "inputs.parquet")
    assert len(results) == 4 and set(results["status"]) == {"ok"}
    assert set(results["ndrt-2020.landing.kind"]) == {"touchdown"}
    for (_, row), (_, given) in zip(results.sort_values("run").iterrows(), inputs.sort_values("run").iterrows()):
        top = (row["ndrt-2020.apogee.latitude_deg"], row["ndrt-2020.apogee.longitude_deg"])
        down = (row["ndrt-2020.landing.latitude_deg"], row["ndrt-2020.landing.longitude_deg"])
        e, n, _ = pymap3d.geodetic2enu(*down, 0.0, *top, 0.0)
        time, de, dn = estimate({**given.to_dict(), "apogee": row["ndrt-2020.apogee.height_agl_m"]})
        print(f"\n[ndrt-landing] run {int(row['run'])}: descent {row['ndrt-2020.touchdown.descent_time_s']:.1f} s "
              f"(estimate {time:.1f}), drift {e:.0f} m east {n:.0f} m north (estimate {de:.0f}, {dn:.0f})")
        assert row["ndrt-2020.touchdown.descent_time_s"] == pytest.approx(time, rel=0.05)
        assert math.hypot(e - de, n - dn) < 0.2 * math.hypot(de, dn)
        pe, pn, _ = pymap3d.geodetic2enu(*down, 0.0, LAT, LON, 0.0)
        assert row["ndrt-2020.touchdown.distance_to_target_m"] == pytest.approx(math.hypot(pe, pn), rel=1e-3)
