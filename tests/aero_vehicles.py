"""Vehicles and helpers for the aerodynamics tests (plain dicts, validated here)."""

from __future__ import annotations

import copy
import math
from pathlib import Path

import numpy as np

from rocketsim.constants import EARTH_J2, EARTH_MU, EARTH_OMEGA, EARTH_RADIUS_EQ, EARTH_RADIUS_POLAR
from rocketsim.layout import make_params
from rocketsim.scenario.load import validate
from rocketsim.scenario.models import VehicleSpec
from rocketsim.scenario.yaml_source import read_yaml

ROOT = Path(__file__).resolve().parents[1]

# A slender body: one 10 m x 0.5 m stage (an inert tank for the mass), a 2 m cone nose.
SLENDER = {
    "name": "slender",
    "stages": [{"name": "body", "length": "10 m", "diameter": "0.5 m", "structure_mass": "200 kg",
                "tanks": [{"name": "T", "propellant": "X", "density": 1000.0, "radius": "0.2 m",
                           "length": "4 m", "position": "1 m", "propellant_mass": "0 kg"}]}],
    "aero": {"nose": {"length": "2 m", "shape": "cone"}, "segments": 40},
}

# A finned sounding rocket: 6 m x 0.3 m, ogive nose, four fins at the base, a burnt-out motor.
SOUNDING = {
    "name": "finned sounding rocket",
    "stages": [{"name": "rocket", "length": "6 m", "diameter": "0.3 m", "structure_mass": "60 kg",
                "structure_centre": "3.4 m",
                "tanks": [{"name": "T", "propellant": "X", "density": 1000.0, "radius": "0.14 m",
                           "length": "3 m", "position": "0.5 m", "propellant_mass": "0 kg"}],
                "point_masses": [{"name": "payload", "mass": "40 kg", "position": "5.2 m"}]}],
    "aero": {"nose": {"length": "1 m", "shape": "ogive"},
             "fins": [{"stage": "rocket", "count": 4, "position": "0.5 m", "root_chord": "0.4 m",
                       "tip_chord": "0.2 m", "span": "0.3 m", "sweep": "0.2 m"}]},
}


def spec(data: dict) -> VehicleSpec:
    return VehicleSpec.model_validate(copy.deepcopy(data))


def shipped(name: str) -> VehicleSpec:
    return validate(read_yaml(ROOT / "vehicles" / name), VehicleSpec)


def earth_params():
    """Parameters of a staged vehicle on Earth (mass and inertia come from its arrays)."""
    return make_params(1.0, (1.0, 1.0, 1.0), EARTH_MU, EARTH_RADIUS_EQ, EARTH_J2, EARTH_RADIUS_POLAR)


def corotating(r) -> np.ndarray:
    """The ground's (and still air's) inertial velocity at ECI position ``r`` (m/s)."""
    return np.array([-EARTH_OMEGA * r[1], EARTH_OMEGA * r[0], 0.0])


def pitch_quaternion(angle: float) -> tuple:
    """Body -> ECI for a rotation of ``angle`` (rad) about the ECI y axis."""
    return (math.cos(angle / 2), 0.0, math.sin(angle / 2), 0.0)
