"""Events nobody commands (burn-out, orbit achieved) and commanded ones (ignition, shutdown)."""

import pytest

from rocketsim.constants import G0, UNUSABLE_PROPELLANT
from rocketsim.scenario.load import load
from rocketsim.api.telemetry_flight import fly_to_file as fly
from tests.unit.flight.test_autopilot import VEHICLE

BURN_OUT = """
def main(fc):
    fc.ignite()
    fc.throttle(1.0)
    fc.hold("prograde")
"""

TO_ORBIT = """
def main(fc):
    fc.ignite()
    fc.throttle(1.0)
    fc.hold("prograde")
    fc.wait_until(lambda: fc.periapsis > 150e3)
    fc.shutdown()
"""


def flight(write, tmp_path, program, start):
    write("vehicle.yaml", VEHICLE)
    write("program.py", program)
    path = write("scenario.yaml", f"""\
        name: kick
        vehicle: vehicle.yaml
        program: program.py
        mission:
          epoch: 2026-11-26T12:00:00Z
          start: {start}
          duration: 240 s
        """)
    return fly(load(path), tmp_path / "run.mcap")["bodies"]["kick_stage"]["events"]


def test_a_burn_to_depletion_reports_meco_at_the_analytic_burnout(write, tmp_path):
    """The kick stage (20 kN, Isp 320 s, 1 300 kg loaded, 1 % unusable) burns out
    at dead time + half the spool-up + usable / mass flow (the engine model's
    linear spool-up, then the constant flow T / (g0 Isp)). Starting in orbit,
    no "orbit achieved" is reported."""
    events = flight(write, tmp_path, BURN_OUT, "{orbit: {altitude: 300 km, inclination: 28.5 deg}}")
    assert [e["name"] for e in events] == ["ignition", "MECO"]
    flow = 20e3 / (G0 * 320.0)
    expected = 0.2 + 0.5 / 2 + (1 - UNUSABLE_PROPELLANT) * 1300.0 / flow
    assert events[1]["burnout_s"] == pytest.approx(expected, rel=1e-6)


def test_orbit_is_reported_once_the_engine_is_off_with_a_periapsis_above_100_km(write, tmp_path):
    """From 300 km at 6.9 km/s horizontal (an ellipse dipping to 4 400 km from
    the centre: suborbital) the stage burns prograde until its periapsis passes
    150 km, shuts down, and once the 0.25 s tail-off is over the orbit is
    reported with its elements."""
    start = ("{state: {position: [6678.137 km, 0 km, 0 km], "
             "velocity: [0 km/s, 6.0623 km/s, 3.2903 km/s]}}")
    events = flight(write, tmp_path, TO_ORBIT, start)
    assert [e["name"] for e in events] == ["ignition", "shutdown", "orbit"]
    shutdown, orbit = events[1], events[2]
    assert orbit["time_s"] >= shutdown["time_s"] + 0.25
    assert 150e3 < orbit["periapsis_altitude_m"] < 400e3
    assert orbit["inclination_deg"] == pytest.approx(28.5, abs=0.05)


def test_the_cheap_periapsis_bound_is_never_below_the_periapsis():
    """The orbit test computes the elements only once ``|r x v|^2 / mu`` (the semi-latus
    rectum p) passes the bound: p = r_p (1 + e) >= r_p (Vallado, eq. 2-57), so no
    orbit can be missed. Checked on random states, bound or not, and on the circular
    orbit where the two are equal."""
    import numpy as np
    from rocketsim.constants import EARTH_MU
    from rocketsim.frames.elements import state_to_elements
    from rocketsim.sim.flight_events import periapsis_bound
    rng = np.random.default_rng(6)
    for _ in range(2000):
        r = rng.normal(size=3) * rng.uniform(6.4e6, 5e7)
        v = rng.normal(size=3) * rng.uniform(100.0, 9000.0)
        periapsis = state_to_elements(r, v, EARTH_MU).periapsis
        assert periapsis_bound(np.concatenate((r, v)), EARTH_MU) >= periapsis * (1 - 1e-12)
    r, v = np.array([7e6, 0.0, 0.0]), np.array([0.0, (EARTH_MU / 7e6) ** 0.5, 0.0])
    assert periapsis_bound(np.concatenate((r, v)), EARTH_MU) == pytest.approx(7e6, rel=1e-12)
