"""Measured flights as acceptance tests: Notre Dame 2020 and EPFL Bella Lui.

References: the flight computers' altitude logs (RocketPy's repository, MIT;
scenarios/measured/README.md), and RocketPy (a peer library used only in
tests) flying the same rockets as its own acceptance tests do, with its
default settings. The bounds are RocketPy's acceptance bounds: apogee within
1.5 % of the log, apogee time within 2 %, peak vertical speed within 6 %; and
rocketsim's apogee error against the log no larger than RocketPy's. The
descent rate under the last parachute is printed beside the log's (not
bounded).

The rockets are flown from the stations RocketPy's acceptance tests give
(vehicles/ndrt-2020.yaml and bella-lui.yaml cite them): each stage reaching to
its nose's tip (the nose the top of the stage it caps) with the boattail at its
base. So built, Notre Dame's static margin is 0.32 calibres at liftoff (RocketPy's
own Barrowman sum for the same rocket gives the same, tests/unit/vehicle/test_design_review.py)
and it meets every bound: apogee -0.5 % (RocketPy -0.8 %). (Ended at the nose's
base, the nose inside the stage and no boattail, it is 0.61 m short, 2.04
calibres stable, and in the day's wind turns upwind and peaks 3.6 % under the
log: that gap is the geometry's, not RocketPy's acceptance figures'.) (The
team's own report, as RocketPy's test quotes it, gives a
measured stability margin of 2.875 calibres, which the published stations do
not: the datum missing is the rocket as built, its fins' and centre of mass's
stations.)

Bella Lui misses its apogee (-2.8 %) and peak vertical speed for one figure of
RocketPy's acceptance set-up, marked xfail, strict: RocketPy's motor burns the
0.824 kg its grain geometry holds (782.4 kg/m^3), not the 1.45 kg of the
AeroTech K828FJ's .eng header (an Isp of 267 s against 152 s for the same
2 157 N s); rocketsim flies the .eng file's motor, so its rocket is 0.63 kg
heavier during the burn. With RocketPy's masses the two simulators agree within
0.14 % (test_with_rocketpys_masses_...). The datum missing is the rocket's
liftoff mass as flown.

RocketPy flying Notre Dame as our file builds it (motor in the tail, our
inertia) in the day's wind weathercocks more than rocketsim's: its fins' lift
rises with Mach (Prandtl-Glauert, 0.52 calibres at Mach 0.5 against our fixed
0.32; our crossflow moves the centre of pressure forward as the angle grows),
which on a 0.3-calibre rocket matters: 1 297.7 m and 204 m upwind against
1 313.9 m and 75 m (marked xfail, strict). In calm air the two agree within
0.06 % and meet the log within 0.1 % (test_in_calm_air_...).

rocketsim flies each scenario at its 10 ms step (the apogee moves 0.01 % from
5 ms to 20 ms: the motors' curve points cut the steps anyway) and samples at
50 Hz, so the apogee time is read to 0.02 s; the two flights take about 2 s,
RocketPy's about 1 s each.
"""

from functools import lru_cache

import pytest

from tests.measured_flights import (MOTORS, SCENARIOS, figures_of_run, measured,
                                    rocketpy_figures, rocketpy_flight)
from tests.plot_checks import assert_the_plot_reads

rocketpy = pytest.importorskip("rocketpy")

PEER_FINS = ("RocketPy's fins' lift rises with Mach (Prandtl-Glauert): on this 0.3-calibre rocket "
             "it weathercocks more in the day's wind: see the module's docstring")
BELLA_MASS = ("rocketsim flies the K828FJ's .eng propellant (1.45 kg), RocketPy's acceptance "
              "rocket 0.824 kg: see the module's docstring")


@lru_cache(maxsize=None)
def run_of(name: str):
    """rocketsim's run of scenarios/measured/<name>.yaml (in memory), flown once per session."""
    import rocketsim
    return rocketsim.fly(SCENARIOS / f"{name}.yaml")


@lru_cache(maxsize=None)
def flights(name: str):
    """(log, rocketsim, RocketPy) figures of ``name``, flown once per session."""
    log, ours, peer = measured(name), figures_of_run(name, run_of(name)), rocketpy_figures(name, MOTORS)
    rows = [("apogee (m AGL)", "apogee"), ("apogee time (s)", "apogee_time"),
            ("peak vertical speed (m/s)", "peak_vertical_speed"),
            ("descent rate (m/s)", "descent_rate")]
    print(f"\n[{name}] {'':26}{'measured':>10}{'rocketsim':>11}{'RocketPy':>10}")
    for label, key in rows:
        m, a, b = getattr(log, key), getattr(ours, key), getattr(peer, key)
        print(f"[{name}] {label:26}{m:10.2f}{a:11.2f}{b:10.2f}   "
              f"({100 * (a / m - 1):+.2f} %, {100 * (b / m - 1):+.2f} %)")
    return log, ours, peer


def _error(simulated, log, key):
    return abs(getattr(simulated, key) / getattr(log, key) - 1)


@pytest.mark.parametrize("name", [
    "ndrt-2020", pytest.param("bella-lui", marks=pytest.mark.xfail(strict=True, reason=BELLA_MASS))])
def test_apogee_within_1_5_percent_of_the_log(name):
    log, ours, _ = flights(name)
    assert _error(ours, log, "apogee") < 0.015


@pytest.mark.parametrize("name", [
    "ndrt-2020", pytest.param("bella-lui", marks=pytest.mark.xfail(strict=True, reason=BELLA_MASS))])
def test_apogee_error_no_larger_than_rocketpys(name):
    log, ours, peer = flights(name)
    assert _error(ours, log, "apogee") <= _error(peer, log, "apogee")


@pytest.mark.parametrize("name", ["ndrt-2020", "bella-lui"])
def test_apogee_time_within_2_percent_of_the_log(name):
    log, ours, _ = flights(name)
    assert _error(ours, log, "apogee_time") < 0.02


@pytest.mark.parametrize("name", [
    "ndrt-2020",
    pytest.param("bella-lui", marks=pytest.mark.xfail(strict=True, reason=BELLA_MASS))])
def test_peak_vertical_speed_within_6_percent_of_the_log(name):
    log, ours, _ = flights(name)
    assert _error(ours, log, "peak_vertical_speed") < 0.06


def test_in_calm_air_rocketsim_and_rocketpy_fly_notre_dame_alike(tmp_path):
    """The day's ERA5 file with its wind set to zero (temperature and heights kept), the rocket
    as vehicles/ndrt-2020.yaml builds it flown by both: apogee within 0.5 %, its time within
    1 % (measured 1 321.4 against 1 320.6 m, 16.78 against 16.77 s). Both then meet the
    log's apogee (1 320.4 m) within 0.1 %."""
    import xarray as xr
    import rocketsim
    day = xr.open_dataset(SCENARIOS / "weather" / "ndrt_2020_weather_data_ERA5.nc").load()
    day = day.drop_encoding()
    day["u"][:] = 0.0
    day["v"][:] = 0.0
    day.to_netcdf(tmp_path / "calm.nc", engine="netcdf4")
    run = rocketsim.fly(rocketsim.load(SCENARIOS / "ndrt-2020.yaml",
                                       overrides={"weather.file": str(tmp_path / "calm.nc")}))
    ours = figures_of_run("ndrt-2020", run)
    peer, env = rocketpy_flight("ndrt-2020", MOTORS, weather=tmp_path / "calm.nc",
                                to_apogee=True, physical=True)
    log = measured("ndrt-2020")
    print(f"\n[calm] apogee rocketsim {ours.apogee:.1f} m at {ours.apogee_time:.2f} s, RocketPy "
          f"{peer.apogee - env.elevation:.1f} m at {peer.apogee_time:.2f} s, log {log.apogee:.1f} m")
    assert ours.apogee == pytest.approx(peer.apogee - env.elevation, rel=0.005)
    assert ours.apogee_time == pytest.approx(peer.apogee_time, rel=0.01)
    assert _error(ours, log, "apogee") < 0.015


@pytest.mark.xfail(strict=True, reason=PEER_FINS)
def test_in_the_wind_rocketsim_and_rocketpy_fly_the_physical_notre_dame_alike():
    """RocketPy flying Notre Dame as vehicles/ndrt-2020.yaml builds it (tests/rocketpy_rockets.py:
    the motor in the tail, our inertia and boattail) in the day's ERA5 wind: apogee within
    0.5 %, its time within 1 %, the drift upwind by apogee within 10 %. Measured: RocketPy
    1 297.7 m at 16.70 s, 204 m upwind; rocketsim 1 313.9 m at 16.84 s, 75 m."""
    import math
    _, ours, _ = flights("ndrt-2020")
    peer, env = rocketpy_flight("ndrt-2020", MOTORS, to_apogee=True, physical=True)
    drift = math.hypot(peer.x(peer.apogee_time), peer.y(peer.apogee_time))
    print(f"\n[physical] apogee rocketsim {ours.apogee:.1f} m at {ours.apogee_time:.2f} s, "
          f"RocketPy {peer.apogee - env.elevation:.1f} m at {peer.apogee_time:.2f} s, "
          f"drift {ours.apogee_drift:.0f} and {drift:.0f} m")
    assert ours.apogee == pytest.approx(peer.apogee - env.elevation, rel=0.005)
    assert ours.apogee_time == pytest.approx(peer.apogee_time, rel=0.01)
    assert drift == pytest.approx(ours.apogee_drift, rel=0.1)


def test_with_rocketpys_masses_rocketsim_and_rocketpy_fly_bella_lui_alike():
    """Bella Lui with RocketPy's masses (the K828FJ's curve with 0.824 kg of propellant in a
    1 kg case: 3 grains of 782.4 kg/m^3; a 17.227 kg rocket), in the day's ERA5 weather: apogee within 0.5 %, its time
    within 1 %, peak vertical speed within 1 % (measured 461.5 against 460.9 m, 10.62
    against 10.61 s)."""
    import rocketsim
    from rocketsim.scenario.motor_file import read_thrust_curve
    curve = read_thrust_curve(MOTORS / "AeroTech_K828FJ.eng")
    motor = {"name": "K828FJ", "thrust": [list(p) for p in curve.points], "position": "0 m",
             "diameter": f"{curve.diameter} m", "length": f"{curve.length} m",
             "propellant_mass": "0.8238 kg", "total_mass": "1.8238 kg"}
    run = rocketsim.fly(rocketsim.load(SCENARIOS / "bella-lui.yaml", overrides={
        "vehicle.stages[rocket].motors": [motor],
        "vehicle.stages[rocket].structure_mass": "17.227 kg"}))
    ours, peer = figures_of_run("bella-lui", run), flights("bella-lui")[2]
    print(f"\n[RocketPy's masses] apogee rocketsim {ours.apogee:.1f} m at {ours.apogee_time:.2f} s,"
          f" RocketPy {peer.apogee:.1f} m at {peer.apogee_time:.2f} s")
    assert ours.apogee == pytest.approx(peer.apogee, rel=0.005)
    assert ours.apogee_time == pytest.approx(peer.apogee_time, rel=0.01)
    assert ours.peak_vertical_speed == pytest.approx(peer.peak_vertical_speed, rel=0.01)


@pytest.mark.parametrize("name", ["ndrt-2020", "bella-lui"])
def test_its_plot_reads(name):
    """The replay plot of the whole flight (tests/plot_checks.py)."""
    assert_the_plot_reads(run_of(name), name)
