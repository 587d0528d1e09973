"""Mars: the Glenn engineering model below 40 km, and the smoothness of the profile above.

Reference below 40 km: the NASA Glenn Research Center formulas ("Mars Atmosphere
Model - Metric Units", www.grc.nasa.gov/www/k-12/airplane/atmosmrm.html),
written out here (h in metres, T in °C, p in kPa):
T = -31 - 0.000998 h (h <= 7000), -23.4 - 0.00222 h (h > 7000);
p = 0.699 exp(-0.00009 h); rho = p / (0.1921 (T + 273.1)).
The speed of sound is sqrt(gamma R T) with the published model's 188.92
J/(kg K) and gamma = 1.33 (ideal-gas CO2 at 220 K, NIST-JANAF).
Above 40 km: continuity of temperature and density and of their first
derivatives at every joint (one-sided finite differences), hydrostatic
balance above the 40-60 km hand-over band, and the named temperatures.
"""

import math

import numpy as np
import pytest

from rocketsim.atmosphere.mars import (EXOBASE_HEIGHT, GLENN_TOP, HANDOVER_DEPTH,
                                       MESOPAUSE_HEIGHT, gravity, mars_atmosphere, mars_table)


def glenn_by_hand(h):
    t_c = -31.0 - 0.000998 * h if h <= 7000.0 else -23.4 - 0.00222 * h
    p_kpa = 0.699 * math.exp(-0.00009 * h)
    return t_c + 273.1, p_kpa * 1000.0, p_kpa / (0.1921 * (t_c + 273.1))


@pytest.mark.parametrize("h", [0.0, 1000.0, 6999.0, 7000.0, 7001.0, 15_000.0, 30_000.0, 40_000.0])
def test_glenn_formulas_to_rounding(h):
    t, p, rho = glenn_by_hand(h)
    air = mars_atmosphere(h)
    assert air.temperature == pytest.approx(t, rel=1e-14)
    assert air.pressure == pytest.approx(p, rel=1e-14)
    assert air.density == pytest.approx(rho, rel=1e-14)
    assert air.speed_of_sound == pytest.approx(math.sqrt(1.33 * 188.92 * t), rel=1e-14)


def test_glenn_temperature_step_at_7_km_is_the_published_one():
    # The two published lines do not meet: -37.986 °C and -38.940 °C at 7 km. The model is
    # kept exactly as specified, so the step is the formulas' own 0.954 K, and the density
    # (the pressure formula is one line) steps up by 235.114 / 234.160 - 1 = 0.41 %.
    below, above = mars_atmosphere(7000.0), mars_atmosphere(7000.0 + 1e-6)
    assert below.temperature - above.temperature == pytest.approx(0.954, abs=1e-3)
    assert above.density / below.density - 1.0 == pytest.approx(0.00407, abs=2e-5)


def _one_sided(h, eps=1.0):
    a = mars_atmosphere(np.array([h - 2 * eps, h - eps, h, h + eps, h + 2 * eps]))
    out = {}
    for name in ("temperature", "density"):
        v = getattr(a, name)
        left = (3 * v[2] - 4 * v[1] + v[0]) / (2 * eps)
        right = (-3 * v[2] + 4 * v[3] - v[4]) / (2 * eps)
        edge = getattr(mars_atmosphere(np.array([h - 1e-3, h + 1e-3])), name)
        out[name] = (edge[0], edge[1], left, right, v[2])
    return out


@pytest.mark.parametrize("joint", [GLENN_TOP, GLENN_TOP + HANDOVER_DEPTH, MESOPAUSE_HEIGHT,
                                   EXOBASE_HEIGHT])
def test_value_and_slope_continuous_at_joints(joint):
    for name, (left_v, right_v, left_d, right_d, v) in _one_sided(joint).items():
        assert right_v == pytest.approx(left_v, rel=1e-6), name
        scale = max(abs(left_d), abs(right_d), 1e-6 * abs(v) / 1000.0)
        assert abs(right_d - left_d) <= 1e-3 * scale, name


def test_named_temperatures_and_hydrostatic_balance_above_the_handover():
    assert mars_atmosphere(MESOPAUSE_HEIGHT).temperature == pytest.approx(110.0)
    assert mars_atmosphere(200_000.0).temperature == pytest.approx(230.0)
    # dp/dh = -rho g above 60 km (central difference over 2 m).
    for h in (70_000.0, 120_000.0, 300_000.0):
        a = mars_atmosphere(np.array([h - 1.0, h, h + 1.0]))
        dp = (a.pressure[2] - a.pressure[0]) / 2.0
        assert dp == pytest.approx(-a.density[1] * gravity(h), rel=1e-5)


def test_mars_table_reaches_600_km_with_no_wind():
    table = mars_table()
    assert table.h0 <= -8000.0 and table.heights[-1] == pytest.approx(600_000.0)
    assert not table.has_wind
    rho, *_ = table.at([20_000.0])
    assert rho[0] == pytest.approx(glenn_by_hand(20_000.0)[2], rel=1e-4)
