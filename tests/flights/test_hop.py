"""A first-stage hop: the Falcon 9 booster alone, light, lifts off, hovers
and lands back where it started; and the scenario fields that make it
(``stages:``, ``propellant:``, rocketsim/scenario/stage_selection.py).

Flown at a 0.05 s headless step (about 4 s of CPU for 75 s of flight).
"""

import pytest

from rocketsim.scenario.load import load
from rocketsim.scenario.stage_selection import keep_stages, reload_tanks
from rocketsim.api.telemetry_flight import fly_to_file as fly
from rocketsim.sim.build import build_world
from tests.conftest import ROOT
from tests.plot_checks import assert_the_plot_reads

HOP = ROOT / "scenarios" / "falcon9-hop.yaml"


@pytest.fixture(scope="module")
def flight(tmp_path_factory):
    out = tmp_path_factory.mktemp("hop") / "run.mcap"
    return {**fly(load(HOP), out, step=0.05), "file": out}


def test_the_hop_vehicle_is_the_booster_alone_with_its_reload():
    """Reference: the vehicle file's published first-stage dry mass, 22 200 kg
    (Falcon 9 Block 5), plus the scenario's 7 440 + 17 560 kg: 47 200 kg on the
    pad; one stage, no payload, no fairing, the booster's legs and grid fins."""
    vehicle = load(HOP).scenario.vehicle
    assert [s.name for s in vehicle.stages] == ["booster"]
    assert vehicle.payload is None and vehicle.fairing is None
    assert len(vehicle.aero.legs) == 1 and len(vehicle.aero.grid_fins) == 1
    world = build_world(load(HOP))
    assert world.bodies[0].mass == pytest.approx(22_200 + 25_000, abs=1e-6)


def test_the_hop_lifts_off_hovers_and_lands_where_it_started(flight):
    """Liftoff, the hover at 100 m, touchdown within the booster-return limits (tilt
    < 5 deg, vertical speed < 2 m/s) and within 1 m of the launch point."""
    body = flight["bodies"]["falcon9-block5"]
    names = [e["name"] for e in body["events"]]
    remaining = iter(names)
    assert all(n in remaining for n in ["ignition", "liftoff", "hover", "legs deployed", "touchdown"]), names
    hover = {e["name"]: e for e in body["events"]}["hover"]
    assert hover["clearance_m"] == pytest.approx(100.0, abs=1.0)
    touchdown = body["touchdown"]
    print(f"\nhop touchdown: {touchdown}")
    assert touchdown["tilt_deg"] < 5.0
    assert abs(touchdown["vertical_speed_m_s"]) < 2.0
    assert touchdown["distance_to_target_m"] < 1.0
    assert "breakup" not in names and "impact" not in names


def test_stage_selection_refuses_what_the_vehicle_does_not_have():
    vehicle = load(ROOT / "scenarios" / "falcon9-leo.yaml").scenario.vehicle
    with pytest.raises(ValueError, match="lowest stages"):
        keep_stages(vehicle, ["second stage"])
    with pytest.raises(ValueError, match="no tank booster/LH2"):
        reload_tanks(vehicle, {"booster/LH2": 1000.0})
    with pytest.raises(ValueError, match="does not fit"):
        reload_tanks(vehicle, {"booster/RP-1": 1e7})
    reloaded = reload_tanks(vehicle, {"booster/LOX": 1000.0})
    assert reloaded.stages[0].tanks[1].propellant_mass == 1000.0
    assert reloaded.stages[0].tanks[0].propellant_mass == vehicle.stages[0].tanks[0].propellant_mass


def test_its_plot_reads(flight):
    """The replay plot of the whole hop (tests/plot_checks.py)."""
    assert_the_plot_reads(flight["file"], "falcon9-hop")
