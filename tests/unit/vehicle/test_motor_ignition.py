"""Solid motors lit by the flight program (``ignition: program``, ``fc.ignite``).

References:

* an air start: a body without aerodynamics hanging at 1 000 m, its motor lit by the
  program at T+1 s, is pushed vertically by the curve's impulse while the propellant
  burns in proportion to it, ``m = m0 - m_p I(t)/I_total``; the thrust's velocity gain
  is then exactly ``(I_total/m_p) ln(m0/(m0 - m_p))`` (the integral of ``dI/m``), less
  gravity: WGS84 normal gravity (Somigliana, NIMA TR8350.2 eq. 4-1) less the free-air
  gradient at the body's heights, over the whole 3.5 s. The K1000T's figures are its
  file's (motors/AeroTech_K1000T.eng: 1.182 kg of propellant, the curve's trapezoid),
  and with ``thrust_scale: 1.03`` the impulse is 3 % more for the same propellant;
* the motor lights once and cannot be shut down: a second ``fc.ignite`` lights nothing,
  ``fc.shutdown`` naming it is refused with a ``ValueError`` the program can catch;
* a program-lit motor on the stack stays lit across a separation (its ignition
  instant carried to the new body). tests/flights/test_solid_staging.py flies a sustainer
  lit by the program after the separation.

The flight takes 3.6 s at 20 ms.
"""

import math
from pathlib import Path

import numpy as np
import pytest

from rocketsim.scenario.load import load
from rocketsim.scenario.motor_file import read_thrust_curve
from rocketsim.sim.build import build_world

ROOT = Path(__file__).resolve().parents[3]
K1000T = ROOT / "motors" / "AeroTech_K1000T.eng"
LATITUDE = 32.99

AIR_START = """
def main(fc):
    fc.sleep(1.0)
    lit = fc.ignite()
    again = fc.ignite("K1000T")
    try:
        fc.shutdown("K1000T")
        refused = ""
    except ValueError as error:
        refused = str(error)
    fc.event("checked", lit=",".join(lit), again=len(again), refused=refused)
"""


def somigliana(latitude_deg: float) -> float:
    s2 = math.sin(math.radians(latitude_deg)) ** 2
    return 9.7803253359 * (1 + 0.00193185265241 * s2) / math.sqrt(1 - 0.00669437999013 * s2)


@pytest.mark.parametrize("scale", [1.0, 1.03])
def test_an_air_start_lit_by_the_program_delivers_the_curves_impulse(tmp_path, scale):
    (tmp_path / "program.py").write_text(AIR_START)
    data = {"name": "air start", "program": "program.py", "telemetry": {"rate": 50},   # every step
            "vehicle": {"name": "dart", "stages": [{
                "name": "dart", "length": "1 m", "diameter": "0.1 m", "structure_mass": "5 kg",
                "motors": [{"name": "K1000T", "file": str(K1000T), "ignition": "program",
                            "thrust_scale": scale}]}]},
            "site": {"name": "range", "latitude": f"{LATITUDE} deg", "longitude": "-106.975 deg",
                     "height": "1000 m", "ground_height": "0 m"},     # hanging in the air
            "mission": {"epoch": "2026-06-13T15:00:00Z", "duration": "3.6 s", "start": {"site": {}}}}
    world = build_world(load(data, base_dir=tmp_path))
    body = world.bodies[0]
    trace = []

    def watch(t):
        view = body.view()
        trace.append((t, float(view.vertical_speed), view.geodetic[2], float(body.y[body.vehicle.motors][0])))
    world.on_progress = watch
    world.run()
    events = {e["name"]: e for e in body.events}
    checked, ignition, burnout = events["checked"], events["ignition"], events["burnout"]
    assert checked["lit"] == "dart/K1000T" and checked["again"] == 0
    assert checked["refused"].startswith("dart/K1000T: a solid motor cannot be shut down")
    assert ignition["time_s"] == pytest.approx(1.0, abs=1e-12) and ignition["motors"] == ["dart/K1000T"]
    curve = read_thrust_curve(K1000T)
    assert burnout["burnout_s"] == pytest.approx(1.0 + curve.points[-1][0], abs=1e-12)

    t, up, height, left = (np.array(c) for c in zip(*trace))
    assert np.all(left[t <= 1.0] == curve.propellant_mass)             # dark until the program lights it
    points = np.array(curve.points)
    impulse = scale * float(np.sum(0.5 * (points[1:, 1] + points[:-1, 1]) * np.diff(points[:, 0])))
    m0 = 5.0 + curve.total_mass
    gain = impulse / curve.propellant_mass * math.log(m0 / (m0 - curve.propellant_mass))
    end = int(np.searchsorted(t, burnout["burnout_s"] + 0.05))
    g = somigliana(LATITUDE) - 3.086e-6 * height[:end + 1]
    lost = float(np.sum(0.5 * (g[1:] + g[:-1]) * np.diff(t[:end + 1]))) + g[0] * t[0]
    expected = gain - lost
    print(f"\n[ignition] lit at T+1 s: {up[end]:.4f} m/s up at T+{t[end]:.2f} s, the impulse law "
          f"{expected:.4f} m/s (thrust {gain:.2f} less gravity {lost:.2f})")
    assert up[end] == pytest.approx(expected, rel=1e-5)


def test_a_motor_lit_on_the_stack_burns_on_after_the_separation():
    """The ignition instant travels with the motor's stage at a separation
    (rocketsim.vehicle.staging): the new body's arrays are rebuilt from the file, where
    a program motor is dark."""
    from rocketsim.scenario.models import VehicleSpec
    from rocketsim.vehicle.build import build
    from rocketsim.vehicle.motors import M_IGNITION
    from rocketsim.vehicle.staging import separate
    spec = VehicleSpec.model_validate({"name": "two", "stages": [
        {"name": "lower", "length": "1 m", "diameter": "0.1 m", "structure_mass": "2 kg"},
        {"name": "upper", "length": "1 m", "diameter": "0.1 m", "structure_mass": "2 kg",
         "motors": [{"name": "K1000T", "file": str(K1000T), "ignition": "program"}]}]})
    whole = build(spec)
    assert math.isnan(whole.arrays.motor[0, M_IGNITION])
    whole.arrays.motor[0, M_IGNITION] = 4.25
    (_, _), (upper, _) = separate(spec, whole, whole.state([7e6, 0, 0], [0, 7e3, 0]), 1)
    assert upper.arrays.motor[0, M_IGNITION] == 4.25


def test_a_misspelt_ignition_word_is_named_with_its_line_and_the_word_meant(tmp_path):
    """``ignition`` is a time or the word ``program``: a misspelt word gets both choices
    and the nearest word, at its file's line, as one problem (not the time's complaint
    plus a hidden one about the word)."""
    from rocketsim.errors import InputError
    (tmp_path / "dart.yaml").write_text(
        "name: dart\nstages:\n  - name: dart\n    length: 1 m\n    diameter: 0.1 m\n"
        f"    structure_mass: 5 kg\n    motors:\n      - name: K1000T\n        file: {K1000T}\n"
        "        ignition: progam\n")
    (tmp_path / "scenario.yaml").write_text(
        "name: dart\nvehicle: dart.yaml\nsite: {name: range, latitude: 33 deg, longitude: -106.975 deg}\n"
        "mission: {epoch: 2026-06-13T15:00:00Z, duration: 3 s, start: {site: {}}}\n")
    with pytest.raises(InputError) as caught:
        load(tmp_path / "scenario.yaml")
    error = caught.value
    assert error.file == str(tmp_path / "dart.yaml") and error.line == 10
    assert error.message == ("expected '<number> <unit>' for a time, got 'progam'; or 'program' "
                             "(did you mean 'program'?)")
