"""Engine commands and readings by engine, group or stage name (the layer the flight
computer calls). Reference: the published figures of the Falcon 9-class
file (8 227 kN in vacuum for the nine booster engines, 7 607 kN at sea level) and the
engine timings of the file."""

from pathlib import Path

import numpy as np
import pytest

from rocketsim.constants import USSA_P0
from rocketsim.scenario.load import validate
from rocketsim.scenario.models import VehicleSpec
from rocketsim.scenario.yaml_source import read_yaml
from rocketsim.vehicle.build import build
from rocketsim.vehicle.control import Propulsion

F9 = Path(__file__).resolve().parents[3] / "vehicles" / "falcon9-block5.yaml"


def falcon():
    model = build(validate(read_yaml(F9), VehicleSpec))
    return model, Propulsion(model), model.state([0, 0, 0], [0, 0, 0])


def test_selection_by_stage_group_and_name():
    model, prop, _ = falcon()
    assert prop.select("booster") == list(range(9))
    assert prop.select("Merlin 1D ring") == list(range(1, 9))
    assert prop.select("booster/Merlin 1D centre") == [0]
    assert prop.select("second stage") == [9]
    assert prop.select(["Merlin Vacuum", 0]) == [0, 9]
    with pytest.raises(ValueError, match="no engine, group or stage named 'RD-180'"):
        prop.select("RD-180")


def test_ignite_spool_and_read_the_booster_thrust():
    model, prop, y = falcon()
    assert len(prop.ignite(y, "booster")) == 9
    assert prop.ignite(y, "booster") == []                  # already on
    y[model.clocks] = 0.3 + 1.5                              # dead time + spool-up: full
    states = prop.states(y, 0.0, USSA_P0)
    thrust = sum(s["thrust_N"] for s in states)
    assert thrust == pytest.approx(7_607e3, rel=0.01)
    assert sum(s["thrust_N"] for s in prop.states(y, 0.0, 0.0)) == pytest.approx(8_227e3, rel=0.01)
    assert states[9]["thrust_N"] == 0.0 and not states[9]["on"]
    assert states[0]["ignitions_left"] == 3 and states[1]["ignitions_left"] == 2
    assert states[9]["separated"] and not states[0]["separated"]
    # the vehicle file's ranges: Merlin 1D 40-100 %, Merlin Vacuum 39-100 %
    assert states[0]["throttle_range"] == (0.4, 1.0) and states[9]["throttle_range"] == (0.39, 1.0)


def test_throttle_gimbal_shutdown_and_propellant():
    model, prop, y = falcon()
    prop.ignite(y, "booster")
    y[model.clocks] = 10.0
    prop.throttle(0.0, 0.1, "booster")                       # held at the 40 % floor
    prop.gimbal(0.0, 0.2, 0.0, "Merlin 1D centre")           # clipped to the 5 deg cone
    states = prop.states(y, 5.0, 0.0)
    assert states[0]["throttle"] == pytest.approx(0.4) and states[5]["throttle"] == pytest.approx(0.4)
    assert np.hypot(*states[0]["gimbal_rad"]) == pytest.approx(np.radians(5.0), rel=1e-12)
    assert states[1]["gimbal_rad"] == (0.0, 0.0)
    assert prop.shutdown(y, "Merlin 1D centre") == ["booster/Merlin 1D centre"]
    assert prop.propellant(y)["booster/LOX"] == 288_607.0
