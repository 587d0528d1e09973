"""Small staged vehicles for the vehicle tests (plain dicts, validated by the tests)."""

from __future__ import annotations

import copy
import math

from rocketsim.scenario.models import VehicleSpec

# One engine, 100 kN vacuum, Isp 300 s: mdot = 100e3 / (300 g0) = 33.99 kg/s.
ENGINE = {"name": "E1", "thrust_vacuum": "100 kN", "isp_vacuum": "300 s", "exit_area": "0.5 m2",
          "throttle": [0.5, 1.0], "throttle_rate": 0.5, "gimbal_range": "5 deg",
          "gimbal_rate": "10 deg/s", "ignition_delay": "0.3 s", "spool_up": "1 s", "mass": "100 kg"}

# tank radius 1 m, density 1000/pi: 1000 kg per metre of column
TANK = {"name": "T", "propellant": "X", "density": 1000.0 / math.pi, "radius": "1 m", "length": "6 m",
        "position": "1 m", "wall_mass": "200 kg"}

STAGE = {"name": "S1", "length": "10 m", "diameter": "2 m", "structure_mass": "1000 kg",
         "tanks": [TANK], "engines": [ENGINE]}


def single_stage(**stage_changes) -> dict:
    stage = copy.deepcopy(STAGE)
    stage.update(stage_changes)
    return {"name": "test", "stages": [stage]}


def spec(data: dict) -> VehicleSpec:
    return VehicleSpec.model_validate(data)
