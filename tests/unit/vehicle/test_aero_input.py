"""The aero: section as input (located errors) and the wind held for a step."""

import math

import numpy as np
import pytest

from rocketsim.atmosphere.day import standard_table
from rocketsim.atmosphere.table import make_table
from rocketsim.dynamics.rk4 import step
from rocketsim.errors import InputError
from rocketsim.flight.readings import StateView
from rocketsim.frames.geodetic import geodetic_to_ecef
from rocketsim.scenario.load import validate
from rocketsim.scenario.models import VehicleSpec
from rocketsim.scenario.yaml_source import read_yaml
from rocketsim.vehicle.build import build
from tests.aero_vehicles import SOUNDING, corotating, earth_params, spec

VEHICLE = """\
name: finned
stages:
  - name: rocket
    length: 6 m
    diameter: 0.3 m
    structure_mass: 60 kg
aero:
  nose: {length: 1 m, shape: ogive}
  fins:
    - {stage: rockett, position: 0.5 m, root_chord: 0.4 m, tip_chord: 0.2 m, span: 0.3 m}
"""


def test_a_part_on_an_unknown_stage_is_an_error_at_its_line(write):
    path = write("vehicle.yaml", VEHICLE)
    with pytest.raises(InputError) as caught:
        validate(read_yaml(path), VehicleSpec)
    error = caught.value
    assert error.line == 10 and "rockett" in str(error) and "aero.fins" in str(error.field).replace("[", ".")


def test_a_thruster_on_a_missing_tank_is_an_error(write):
    text = VEHICLE.replace("rockett", "rocket") + """\
  rcs:
    - {stage: rocket, tank: N2, position: 5 m, direction: [0, 1, 0], thrust: 100 N, isp: 60 s}
"""
    with pytest.raises(InputError) as caught:
        validate(read_yaml(write("vehicle.yaml", text)), VehicleSpec)
    assert caught.value.line == 12 and "N2" in str(caught.value)


def test_aero_belongs_to_staged_vehicles(write):
    text = "name: r\nrigid_body: {mass: 10 kg, inertia: [1, 1, 1]}\naero: {segments: 12}\n"
    with pytest.raises(InputError):
        validate(read_yaml(write("vehicle.yaml", text)), VehicleSpec)


def test_the_wind_is_sampled_once_per_step_where_the_vehicle_is():
    # Reference: the flight computer's readings (rocketsim.flight.readings.StateView.air),
    # which turn the day's east/north wind into ECI through the numpy frame functions.
    base = standard_table()
    east = 12.0 + base.heights * 1e-3          # a wind that grows with height
    north = np.full_like(east, -4.0)
    table = make_table(base.h0, base.dh, base.density, base.pressure, base.temperature, base.speed_of_sound,
                       base.viscosity, east, north)
    model = build(spec(SOUNDING), air=table)
    a = model.arrays
    assert a.aero.ref[7] == 1.0
    r = np.array(geodetic_to_ecef(math.radians(40.0), math.radians(15.0), 3000.0))
    y = model.state(r, corotating(r) + 100.0 * r / np.linalg.norm(r))
    t = 37.0
    step(y, t, 0.02, earth_params(), a)
    view = StateView(t, y[0:3].copy(), y[3:6].copy(), y[6:10].copy(), y[10:13].copy(), lambda: table)
    assert a.aero.wind == pytest.approx(view.air[4], abs=1e-9)
    assert np.linalg.norm(a.aero.wind) > 10.0
