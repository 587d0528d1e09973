"""The state message's figures of where the nose points and how fast over the ground,
against their definitions worked out here from the message's own state.

References, for a state about Earth at mission time ``t`` (the ECI of the mission epoch
has x through Greenwich at ``t = 0``, z the spin axis: the ground turns by
``omega t``, omega the simulator's Earth rate, ``rocketsim.constants.EARTH_OMEGA``):

* ``surface_speed`` = ``|v - omega z x r|`` (the velocity over the turning ground);
* the local east, north and up axes at geodetic latitude ``phi`` and inertial longitude
  ``lambda = longitude + omega t``: up ``(cos phi cos lambda, cos phi sin lambda, sin phi)``,
  east ``(-sin lambda, cos lambda, 0)``, north ``(-sin phi cos lambda, -sin phi sin lambda,
  cos phi)`` (Vallado, *Fundamentals of Astrodynamics and Applications*, the SEZ axes);
* the nose is the body's x axis, ``q (1, 0, 0) q*`` for the attitude quaternion ``q``
  (w, x, y, z; body to ECI), written out here as the rotation matrix's first column;
* ``pitch_deg`` = ``asin(nose . up)``, ``heading_deg`` = ``atan2(nose . east, nose . north)``
  in 0-360; ``angle_of_attack_deg`` = the angle between the nose and the air-relative
  velocity, in calm air (the standard atmosphere of scenarios/hobby-rocket.yaml) the
  velocity over the ground;
* ``height_agl`` = ``altitude`` less the site's ``ground_height`` (1 380 m).

The hobby rocket's first 30 s: on its rail, the boost, the coast to apogee.
"""

import math

import numpy as np
import pytest

import rocketsim
from rocketsim.constants import EARTH_OMEGA
from tests.conftest import ROOT

OMEGA = EARTH_OMEGA


@pytest.fixture(scope="module")
def table():
    run = rocketsim.fly(ROOT / "scenarios" / "hobby-rocket.yaml", duration=30.0)
    return run.bodies["hobby-rocket"].table()


def test_the_speed_over_the_ground_is_the_velocity_less_the_ground_turning(table):
    r = table[["position_x_m", "position_y_m", "position_z_m"]].to_numpy()
    v = table[["velocity_x_m_s", "velocity_y_m_s", "velocity_z_m_s"]].to_numpy()
    ground = OMEGA * np.stack([-r[:, 1], r[:, 0], np.zeros(len(r))], axis=1)
    expected = np.linalg.norm(v - ground, axis=1)
    assert np.allclose(table["surface_speed_m_s"], expected, rtol=1e-9, atol=1e-9)
    assert table["surface_speed_m_s"].iloc[0] < 1e-6 and 390.0 < table["inertial_speed_m_s"].iloc[0]


def test_pitch_heading_and_angle_of_attack_are_the_noses(table):
    t = table.index.to_numpy()
    phi = np.radians(table["latitude_deg"].to_numpy())
    lam = np.radians(table["longitude_deg"].to_numpy()) + OMEGA * t
    up = np.stack([np.cos(phi) * np.cos(lam), np.cos(phi) * np.sin(lam), np.sin(phi)], axis=1)
    east = np.stack([-np.sin(lam), np.cos(lam), np.zeros(len(t))], axis=1)
    north = np.stack([-np.sin(phi) * np.cos(lam), -np.sin(phi) * np.sin(lam), np.cos(phi)], axis=1)
    w, x, y, z = (table[f"attitude_{c}"].to_numpy() for c in "wxyz")
    nose = np.stack([1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y)], axis=1)
    pitch = np.degrees(np.arcsin(np.sum(nose * up, axis=1)))
    heading = np.degrees(np.arctan2(np.sum(nose * east, axis=1), np.sum(nose * north, axis=1))) % 360.0
    assert np.allclose(table["pitch_deg"], pitch, atol=1e-7)
    turn = (table["heading_deg"].to_numpy() - heading + 180.0) % 360.0 - 180.0
    assert np.abs(turn).max() < 1e-6
    assert table["pitch_deg"].iloc[0] == pytest.approx(85.0, abs=0.01)      # the rail: 85 deg, north
    assert table["heading_deg"].iloc[0] == pytest.approx(0.0, abs=0.01) or table["heading_deg"].iloc[0] > 359.99
    r = table[["position_x_m", "position_y_m", "position_z_m"]].to_numpy()
    v = table[["velocity_x_m_s", "velocity_y_m_s", "velocity_z_m_s"]].to_numpy()
    air = v - OMEGA * np.stack([-r[:, 1], r[:, 0], np.zeros(len(r))], axis=1)
    speed = np.linalg.norm(air, axis=1)
    moving = speed > 1.0
    alpha = np.degrees(np.arccos(np.clip(np.sum(nose * air, axis=1)[moving] / speed[moving], -1, 1)))
    assert np.allclose(table["angle_of_attack_deg"].to_numpy()[moving], alpha, atol=1e-6)
    assert np.isnan(table["angle_of_attack_deg"].iloc[0])          # at rest on the rail: none
    assert table.loc[10.0, "angle_of_attack_deg"] < 5.0              # stable in the climb


def test_the_height_above_the_ground_is_the_altitude_less_the_sites_ground(table):
    assert np.array_equal(table["height_agl_m"], table["altitude_m"] - 1380.0)
