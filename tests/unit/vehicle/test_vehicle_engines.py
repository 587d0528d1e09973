"""Engines (docs/physics.md#propulsion): thrust against ambient pressure vs the
published figures of the shipped engines, dead time, spool-up, tail-off, throttle and
gimbal slew, the gimbal cone, restarts and the Summerfield flow-separation floor. Each
timing is checked against the engine's own figures at chosen instants (the analytic
profile of the model)."""

import math
from pathlib import Path

import numpy as np
import pytest

from rocketsim.atmosphere.day import standard_table
from rocketsim.constants import EARTH_RADIUS_EQ, EARTH_RADIUS_POLAR, G0, USSA_P0
from rocketsim.dynamics.rk4 import advance
from rocketsim.layout import V, make_params
from rocketsim.scenario.load import validate
from rocketsim.scenario.models import VehicleSpec
from rocketsim.scenario.yaml_source import read_yaml
from rocketsim.vehicle.engines import (C_IGNITED, C_LEVEL, C_ON, C_TAU, S_DRY, command_gimbal,
                                       command_throttle, engine_forces, ignite, separated,
                                       shutdown, throttle_at)
from rocketsim.vehicle.build import build
from tests.vehicle_specs import single_stage, spec

VEHICLES = Path(__file__).resolve().parents[3] / "vehicles"

# Published figures (sources quoted in each vehicle file): (file, engine, vacuum N, sea level N)
PUBLISHED = [
    # SpaceX: 8 227 kN vacuum / 7 607 kN sea level for nine Merlin 1D
    ("falcon9-block5.yaml", "booster/Merlin 1D centre", 8_227e3 / 9, 7_607e3 / 9),
    # SpaceX: Merlin Vacuum 934 kN (no sea-level figure: it does not fire there)
    ("falcon9-block5.yaml", "second stage/Merlin Vacuum", 934e3, None),
    # Rocket Lab: Rutherford 24.9 kN at sea level (no vacuum figure for the sea-level engine)
    ("electron.yaml", "first stage/Rutherford centre", None, 24.9e3),
    ("electron.yaml", "second stage/Rutherford Vacuum", 25.8e3, None),
    # SpaceX: Raptor 2 2 256 kN at sea level, Isp 327 s there and 347 s in vacuum (same flow)
    ("starship-superheavy.yaml", "Super Heavy/Raptor centre/1", 2256e3 * 347 / 327, 2256e3),
    ("starship-superheavy.yaml", "Starship/Raptor Vacuum/1", 2530e3, None),
    # NASA/Grumman: LM descent engine 45.04 kN (10 125 lbf) in vacuum
    ("lander.yaml", "descent stage/descent engine", 45.04e3, None),
]


def forces(model, t, clock=None, p_a=0.0, y=None):
    """Body force and torque of all engines at ``t`` (with every clock at ``clock``)."""
    a = model.arrays
    y = model.state([0, 0, 0], [0, 0, 0]) if y is None else y
    if clock is not None:
        y[model.clocks] = clock
    dy = np.zeros_like(y)
    x_cm = model.mass_properties(y)[1]
    return np.array(engine_forces(t, y, dy, a.first_tank, a.first_clock, a.eng, a.cmd, a.stage,
                                    a.tank_share, p_a, x_cm)), dy


def lit_model(**changes):
    m = build(spec(single_stage(**changes)))
    y = m.state([0, 0, 0], [0, 0, 0])
    assert ignite(y, m.arrays.eng, m.arrays.cmd, m.arrays.stage, 0, m.arrays.first_clock)
    return m, y


@pytest.mark.parametrize("file, engine, vacuum, sea_level", PUBLISHED)
def test_thrust_in_vacuum_and_at_sea_level_matches_the_published_figures(file, engine, vacuum, sea_level):
    model = build(validate(read_yaml(VEHICLES / file), VehicleSpec))
    e = model.engine_names.index(engine)
    a = model.arrays
    y = model.state([0, 0, 0], [0, 0, 0])
    ignite(y, a.eng, a.cmd, a.stage, e, a.first_clock)
    y[model.clocks] = 10.0                                   # spooled up
    p_sea = standard_table().at(0.0)[1][0]                   # US 1976 at sea level: 101 325 Pa
    assert p_sea == pytest.approx(USSA_P0, rel=1e-9)
    t_vac = np.linalg.norm(forces(model, 0.0, y=y.copy())[0][:3])
    if vacuum is not None:
        assert t_vac == pytest.approx(vacuum, rel=0.01)
    if sea_level is not None:
        t_sea = np.linalg.norm(forces(model, 0.0, y=y.copy(), p_a=p_sea)[0][:3])
        assert t_sea == pytest.approx(sea_level, rel=0.01)
        # the mass flow is the same: specific impulse rises as the air thins
        assert forces(model, 0.0, y=y.copy(), p_a=p_sea)[1][model.tanks].sum() == pytest.approx(
            forces(model, 0.0, y=y.copy())[1][model.tanks].sum(), rel=1e-15)


def test_thrust_rises_monotonically_with_altitude_through_the_standard_atmosphere():
    m, y = lit_model()
    pressures = standard_table().at(np.linspace(0, 80e3, 17))[1]
    thrust = [forces(m, 0.0, clock=10.0, p_a=p, y=y.copy())[0][0] for p in pressures]
    assert np.all(np.diff(thrust) > 0)
    # T = T_vac - p_a A_e exactly (docs/physics.md#propulsion), A_e = 0.5 m2
    assert thrust[0] == pytest.approx(100e3 - pressures[0] * 0.5, rel=1e-14)


def test_dead_time_then_linear_spool_up():
    """Ignition dead time 0.3 s, spool-up 1 s: no thrust before 0.3 s, half at 0.8 s, full
    from 1.3 s; the mass flow follows the same fraction."""
    m, y = lit_model()
    for clock, fraction in [(0.0, 0.0), (0.299, 0.0), (0.3, 0.0), (0.55, 0.25), (0.8, 0.5),
                            (1.3, 1.0), (5.0, 1.0)]:
        f, dy = forces(m, 0.0, clock=clock, y=y.copy())
        assert f[0] == pytest.approx(100e3 * fraction, rel=1e-12, abs=1e-9)
        assert -dy[m.tanks].sum() == pytest.approx(100e3 / (G0 * 300) * fraction, rel=1e-12, abs=1e-12)


def test_dead_time_in_flight_no_velocity_before_first_thrust():
    """Integrated: in vacuum without gravity the vehicle does not move during the 0.3 s
    dead time, and the steps are split exactly there."""
    m, y = lit_model()
    p = make_params(1.0, (1, 1, 1), 0.0, EARTH_RADIUS_EQ, 0.0, EARTH_RADIUS_POLAR)
    y[:3] = (EARTH_RADIUS_EQ + 1e6, 0.0, 0.0)
    y1, _ = advance(y, 0, 0.1, 3, p, m.arrays)
    assert np.all(np.abs(y1[V:V + 3]) < 1e-15)               # rounding of the clock only
    y2, _ = advance(y1, 3, 0.1, 1, p, m.arrays)
    assert y2[V] > 0.0
    # after the dead time, the ramp: dv = integral of f T / m ~ (T/m) * 0.1^2 / 2 / spool-up
    mass = m.mass_properties(y1)[0]
    assert y2[V] == pytest.approx(100e3 / mass * 0.5 * 0.1 ** 2 / 1.0, rel=2e-3)


def test_tail_off_falls_to_nothing_in_a_quarter_second():
    m, y = lit_model()
    a = m.arrays
    y[m.clocks] = 10.0
    assert shutdown(y, a.eng, a.cmd, 0, a.first_clock)
    assert a.cmd[0, C_LEVEL] == 1.0 and y[a.first_clock] == 0.0
    for clock, fraction in [(0.0, 1.0), (0.125, 0.5), (0.2, 0.2), (0.25, 0.0), (1.0, 0.0)]:
        assert forces(m, 0.0, clock=clock, y=y.copy())[0][0] == pytest.approx(100e3 * fraction, rel=1e-12, abs=1e-9)


def test_shutdown_during_spool_up_tails_off_from_the_level_reached():
    m, y = lit_model()
    y[m.clocks] = 0.8                                       # half spooled
    shutdown(y, m.arrays.eng, m.arrays.cmd, 0, m.arrays.first_clock)
    assert forces(m, 0.0, clock=0.125, y=y.copy())[0][0] == pytest.approx(25e3, rel=1e-12)


def test_throttle_slews_at_its_rate_and_stays_in_its_range():
    """Range [0.5, 1], 0.5 per second: from 1 to 0.5 takes exactly 1 s; a command of 0.2
    is held at 0.5; back up to 1 takes 1 s again."""
    m, y = lit_model()
    a = m.arrays
    command_throttle(a.eng, a.cmd, 0, 10.0, 0.2)
    assert a.cmd[0, C_TAU] == 0.5
    for t, tau in [(10.0, 1.0), (10.5, 0.75), (11.0, 0.5), (12.0, 0.5)]:
        assert forces(m, t, clock=10.0, y=y.copy())[0][0] == pytest.approx(100e3 * tau, rel=1e-12)
    command_throttle(a.eng, a.cmd, 0, 10.4, 1.0)          # reversed half-way: from 0.8
    assert throttle_at(a.eng, a.cmd, 0, 10.4) == pytest.approx(0.8, rel=1e-12)
    assert throttle_at(a.eng, a.cmd, 0, 10.6) == pytest.approx(0.9, rel=1e-12)
    assert throttle_at(a.eng, a.cmd, 0, 10.8) == 1.0


def test_gimbal_slews_at_its_rate_inside_its_cone():
    """Cone 5 deg, 10 deg/s: a 10 deg command is clipped to 5 deg, reached after 0.5 s; the
    thrust turns by exactly that angle; a diagonal command is clipped to the cone's edge."""
    m, y = lit_model()
    a = m.arrays
    command_gimbal(a.eng, a.cmd, 0, 2.0, math.radians(10.0), 0.0)
    for t, angle in [(2.0, 0.0), (2.25, 2.5), (2.5, 5.0), (3.0, 5.0)]:
        f = forces(m, t, clock=10.0, y=y.copy())[0]
        assert np.linalg.norm(f[:3]) == pytest.approx(100e3, rel=1e-12)
        assert math.degrees(math.atan2(f[1], f[0])) == pytest.approx(angle, abs=1e-9)
        # the torque about the centre of mass: arm (x_e - x_cm) times the side force
        x_cm = m.mass_properties(y)[1]
        assert f[5] == pytest.approx((0.0 - x_cm) * f[1], rel=1e-12, abs=1e-9)
    command_gimbal(a.eng, a.cmd, 0, 3.0, math.radians(4.0), math.radians(4.0))
    f = forces(m, 10.0, clock=10.0, y=y.copy())[0]
    assert math.degrees(math.acos(f[0] / np.linalg.norm(f[:3]))) == pytest.approx(5.0, abs=1e-9)
    assert f[1] == pytest.approx(f[2], rel=1e-12)


def test_restarts_are_counted():
    m, y = lit_model(engines=[dict(single_stage()["stages"][0]["engines"][0], restarts=1)])
    a = m.arrays
    assert shutdown(y, a.eng, a.cmd, 0, a.first_clock)
    assert ignite(y, a.eng, a.cmd, a.stage, 0, a.first_clock)       # the one restart
    assert a.cmd[0, C_IGNITED] == 2
    shutdown(y, a.eng, a.cmd, 0, a.first_clock)
    assert not ignite(y, a.eng, a.cmd, a.stage, 0, a.first_clock)   # none left
    assert a.cmd[0, C_ON] == 0.0


def test_a_dry_stage_does_not_relight():
    m, y = lit_model(engines=[dict(single_stage()["stages"][0]["engines"][0], restarts=3)])
    a = m.arrays
    shutdown(y, a.eng, a.cmd, 0, a.first_clock)
    a.stage[0, S_DRY] = 1.0
    assert not ignite(y, a.eng, a.cmd, a.stage, 0, a.first_clock)


def test_summerfield_floor_at_deep_throttle_in_thick_air():
    """Summerfield: separation when p_e < 0.4 p_a. Exit pressure 50 kPa at full throttle,
    commanded 0.5 at sea level: p_e would be 25 kPa < 40.5 kPa, so the engine holds
    tau = 0.4 * 101 325 / 50 000 = 0.8106; in vacuum it throttles to 0.5."""
    m, y = lit_model(engines=[dict(single_stage()["stages"][0]["engines"][0], exit_pressure="50 kPa")])
    a = m.arrays
    command_throttle(a.eng, a.cmd, 0, 0.0, 0.5)
    tau_sep = 0.4 * USSA_P0 / 50e3
    sea = forces(m, 5.0, clock=10.0, p_a=USSA_P0, y=y.copy())[0][0]
    assert sea == pytest.approx(tau_sep * 100e3 - USSA_P0 * 0.5, rel=1e-12)
    assert forces(m, 5.0, clock=10.0, y=y.copy())[0][0] == pytest.approx(50e3, rel=1e-12)
    assert not separated(a.eng, a.cmd, 5.0, USSA_P0)[0]


def test_vacuum_nozzle_runs_separated_at_sea_level():
    model = build(validate(read_yaml(VEHICLES / "falcon9-block5.yaml"), VehicleSpec))
    a = model.arrays
    flags = separated(a.eng, a.cmd, 0.0, USSA_P0)
    assert list(flags) == [False] * 9 + [True]               # Merlin Vacuum only
    assert not separated(a.eng, a.cmd, 0.0, 0.0).any()


def test_mass_flow_instead_of_isp_gives_the_same_engine():
    """mdot = T_vac / (g0 Isp): 100 kN at 300 s is 33.9908 kg/s (docs/physics.md#propulsion)."""
    engine = dict(single_stage()["stages"][0]["engines"][0])
    del engine["isp_vacuum"]
    by_flow = build(spec(single_stage(engines=[dict(engine, mass_flow=100e3 / (G0 * 300))])))
    by_isp = build(spec(single_stage()))
    assert np.allclose(by_flow.arrays.eng, by_isp.arrays.eng, rtol=1e-15, atol=0)
    with pytest.raises(ValueError, match="exactly one of 'isp_vacuum' or 'mass_flow'"):
        spec(single_stage(engines=[dict(engine, mass_flow=1.0, isp_vacuum="300 s")]))
