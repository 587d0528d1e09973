"""What a body's samples say it senses, and the air figures of bodies the air acts on.

References:

* a body in free fall senses nothing: ``|dv/dt - g| = 0`` (an accelerometer's reading);
* a body falling at its terminal speed senses its weight: drag equals ``m g``, so the
  sensed acceleration is the local gravity ``g = mu / r^2 (1 - 3 J2 (a / r)^2)`` over the
  pole (Vallado, *Fundamentals of Astrodynamics*, 4th ed., eq. 8-20 with ``P2(1) = 1``);
  the drum of tests/unit/dynamics/test_tumbling_drag.py falls within 0.3 % of that speed from 6 km
  down (so its drag is within 0.6 % of its weight);
* the sensed acceleration of a sample is the motion's: the velocity's central
  difference over the samples either side, less the model's gravity there
  (:func:`rocketsim.bodies.gravity.point_mass_j2`), to the difference's error
  (``h^2/6`` of the third derivative: micrometres per second squared at 0.1 s);
* a body the flight model flies without air (the sounding payload: a rigid body, no
  drag area) has no dynamic pressure, and its summary no max q or Mach.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import rocketsim
from rocketsim.atmosphere.day import standard_table
from rocketsim.bodies.gravity import point_mass_j2
from rocketsim.constants import EARTH_J2, EARTH_MU, EARTH_RADIUS_EQ, EARTH_RADIUS_POLAR
from rocketsim.dynamics.free_body import advance_free
from rocketsim.dynamics.nbody import make_field
from rocketsim.layout import make_params, make_state
from rocketsim.stepping.sample_figures import (SAMPLE_AIRSPEED, SAMPLE_DYNAMIC_PRESSURE, SAMPLE_MACH, SAMPLE_SENSED,
                                               figures)
from rocketsim.vehicle.tumbling import cylinder_area
from tests.conftest import ROOT

MASS, RADIUS, LENGTH = 100.0, 1.0, 2.0          # the drum of tests/unit/dynamics/test_tumbling_drag.py
AREA = cylinder_area(RADIUS, LENGTH)
H = 0.02
_NO_GROUPS = np.zeros(0, dtype=np.int64)


def _figures(t, y, p, table, area_mass):
    """The sample figures of a rigid body (``area_mass``: its drag area over mass, 0: none)."""
    return figures(t, y, p, EARTH_MU, 0.0, True, *table.arrays(), None, _NO_GROUPS, 0, 0.0, 0.0, area_mass,
                   LENGTH, None, math.nan)


def _gravity(r: float) -> float:
    return EARTH_MU / r ** 2 * (1.0 - 3.0 * EARTH_J2 * (EARTH_RADIUS_EQ / r) ** 2)


def test_a_drum_senses_nothing_at_rest_in_the_air_and_its_weight_at_its_terminal_speed():
    """Dropped from rest over the North Pole (where the air turning with the Earth is at
    rest): 0 g at the drop, then its sensed acceleration climbs to 1 g: at 6, 4 and 2 km
    within 1 % of the local gravity, above it (falling into denser air, the drum is a
    little faster than its terminal speed there: its drag a little above its weight)."""
    table = standard_table()
    air = table.arrays()
    p = make_params(MASS, (1.0, 2.0, 2.0), EARTH_MU, EARTH_RADIUS_EQ, EARTH_J2, EARTH_RADIUS_POLAR)
    fp = make_field("earth", 0.0, bodies=())
    y = make_state([0.0, 0.0, EARTH_RADIUS_POLAR + 10e3], [0.0, 0.0, 0.0], [1.0, 0.0, 0.0, 0.0], (0.1, 0.2, -0.05))
    assert _figures(0.0, y, p, table, AREA / MASS)[SAMPLE_SENSED] == 0.0
    per_second = round(1.0 / H)
    found = {}
    for k in range(400):
        y, taken = advance_free(y, k * per_second, H, per_second, p, fp, air, AREA / MASS, LENGTH)
        height = y[2] - EARTH_RADIUS_POLAR
        for target in (6e3, 4e3, 2e3):
            if target not in found and height < target:
                found[target] = (_figures((k + 1) * 1.0, y, p, table, AREA / MASS)[SAMPLE_SENSED], _gravity(y[2]))
        if taken < per_second:
            break
    assert sorted(found) == [2e3, 4e3, 6e3]
    for target, (sensed, g) in found.items():
        print(f"\n[drum] {target / 1e3:.0f} km: senses {sensed:.4f} m/s^2, local gravity {g:.4f} m/s^2")
        assert g < sensed < 1.01 * g


def test_a_rigid_body_without_drag_senses_nothing_and_has_no_air_figures():
    """The same fall, the body without a drag area: the flight model flies it in vacuum,
    so it senses nothing and meets no dynamic pressure (its motion through the air, airspeed
    and Mach, is the dragged body's)."""
    table = standard_table()
    p = make_params(MASS, (1.0, 2.0, 2.0), EARTH_MU, EARTH_RADIUS_EQ, EARTH_J2, EARTH_RADIUS_POLAR)
    y = make_state([0.0, 0.0, EARTH_RADIUS_POLAR + 4e3], [0.0, 0.0, -300.0], [1.0, 0.0, 0.0, 0.0], (0.0, 0.0, 0.0))
    out = _figures(0.0, y, p, table, 0.0)
    assert out[SAMPLE_SENSED] == 0.0
    dragged = _figures(0.0, y, p, table, AREA / MASS)
    assert np.isnan(out[SAMPLE_DYNAMIC_PRESSURE])
    assert out[SAMPLE_AIRSPEED] == dragged[SAMPLE_AIRSPEED] == 300.0 and out[SAMPLE_MACH] == dragged[SAMPLE_MACH]
    assert dragged[SAMPLE_DYNAMIC_PRESSURE] > 30e3 and dragged[SAMPLE_SENSED] > 9.8     # 300 m/s at 4 km


@pytest.fixture(scope="module")
def fairing_in_thin_air(tmp_path_factory):
    """An Electron in a 110 km orbit drops its fairing at T+1 s; 3 s of flight: its halves
    tumble through air of about a pascal."""
    folder = tmp_path_factory.mktemp("fairing")
    (folder / "drop.py").write_text("def main(fc):\n    fc.sleep(1.0)\n    fc.jettison_fairing()\n")
    (folder / "scenario.yaml").write_text(f"""\
name: fairing-drop
vehicle: {ROOT / 'vehicles' / 'electron.yaml'}
payload: {{name: a smallsat, mass: 100 kg, length: 0.8 m, diameter: 0.6 m}}
program: drop.py
mission:
  epoch: 2026-11-26T12:00:00Z
  start: {{orbit: {{altitude: 110 km, inclination: 97.4 deg}}}}
  duration: 3 s
""")
    return rocketsim.fly(folder / "scenario.yaml")


def test_a_fairing_half_senses_its_drag_as_its_motion_says(fairing_in_thin_air):
    """Each sample of a fairing half between its first and last: the sensed acceleration
    is the velocity's central difference less gravity, to 1e-4 m/s^2 and 0.1 %; it is
    not nought (the drag of about a pascal on a light shell)."""
    table = fairing_in_thin_air.bodies["fairing_1"].table()
    t = table.index.to_numpy()
    r = table[["position_x_m", "position_y_m", "position_z_m"]].to_numpy()
    v = table[["velocity_x_m_s", "velocity_y_m_s", "velocity_z_m_s"]].to_numpy()
    sensed = table["sensed_acceleration_m_s2"].to_numpy()
    assert len(t) >= 10 and np.allclose(np.diff(t), 0.1)
    for k in range(1, len(t) - 1):
        g = np.array(point_mass_j2(*r[k], EARTH_MU, EARTH_RADIUS_EQ, EARTH_J2))
        motion = np.linalg.norm((v[k + 1] - v[k - 1]) / (t[k + 1] - t[k - 1]) - g)
        assert sensed[k] == pytest.approx(motion, rel=1e-3, abs=1e-4)
    assert table["dynamic_pressure_Pa"].min() > 0.5 and sensed.min() > 0.05
    print(f"\n[fairing] q {table['dynamic_pressure_Pa'].mean():.1f} Pa, senses {sensed.mean():.4f} m/s^2")


def test_a_body_in_vacuum_has_no_max_q_or_mach_in_its_summary(tmp_path):
    """The sounding payload's arc (a rigid body, vacuum) for 20 s: 0 g, no dynamic pressure in
    its table, no max q or Mach in its flight summary or its printed summary."""
    from cli.summary import format_summary
    run = rocketsim.fly(ROOT / "scenarios" / "spaceport-ballistic.yaml", tmp_path / "arc.mcap", duration=20.0)
    body = run.bodies["sounding-payload"]
    table = body.table()
    assert (table["sensed_acceleration_m_s2"] == 0.0).all()
    assert "dynamic_pressure_Pa" not in table or table["dynamic_pressure_Pa"].isna().all()
    for figure in ("max_dynamic_pressure_Pa", "max_mach"):
        assert body.flight[figure] is None or math.isnan(body.flight[figure])
    text = format_summary(run.summary)
    assert "max q" not in text and "Mach" not in text and "max 0.0 g" in text
