"""Foxglove-ready MCAP: every Foxglove message validates against Foxglove's
published JSON schemas (tests/fixtures/foxglove, from foxglove-sdk), and says
what the state message says, in Foxglove's conventions."""

import json
import math
from pathlib import Path

import jsonschema
import numpy as np
import pytest
from mcap.reader import make_reader
from scipy.spatial.transform import Rotation

from rocketsim.frames.earth_fixed import eci_to_ecef
from rocketsim.scenario.load import load
from rocketsim.api.telemetry_flight import fly_to_file as fly
from tests.run_files import write_scenario

PUBLISHED = Path(__file__).parents[2] / "fixtures" / "foxglove"

PROGRAM = """
def main(fc):
    fc.log("hello")
    fc.sleep(0.5)
    fc.event("marker", altitude_m=fc.altitude)
    fc.sleep(0.5)
    raise RuntimeError("boom")
"""


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    """A two-second coast whose program logs, marks an event and then fails."""
    folder = tmp_path_factory.mktemp("fox")
    scenario = write_scenario(folder, PROGRAM, "2 s")
    out = folder / "run.mcap"
    with pytest.raises(Exception, match="boom"):
        fly(load(scenario), out)
    with open(out, "rb") as stream:
        reader = make_reader(stream)
        messages = [(schema.name, channel.topic, message.log_time, json.loads(message.data))
                    for schema, channel, message in reader.iter_messages()]
    return messages


def _published(name):
    return json.loads((PUBLISHED / f"{name}.json").read_text())


def _of(messages, topic):
    return [(stamp, m) for _, t, stamp, m in messages if t == topic]


@pytest.mark.parametrize("name", ["FrameTransform", "LocationFix", "Log"])
def test_messages_validate_against_the_published_schemas(run, name):
    schema = _published(name)
    jsonschema.Draft202012Validator.check_schema(schema)
    mine = [m for schema_name, _, _, m in run if schema_name == f"foxglove.{name}"]
    assert len(mine) >= 2
    for message in mine:
        jsonschema.validate(message, schema)
        # Foxglove's timestamp is the message's log time
        stamp = message["timestamp"]
        assert any(stamp["sec"] * 10**9 + stamp["nsec"] == s for _, _, s, m in run if m is message)


def test_poses_in_frame_schema_is_the_published_one():
    """PosesInFrame is not written (a FrameTransform per body is what the 3-D
    panel follows); the published schema is kept to check it stays loadable."""
    jsonschema.Draft202012Validator.check_schema(_published("PosesInFrame"))


def test_transform_places_and_turns_the_body_as_its_state_says(run):
    states = dict(_of(run, "/probe/state"))
    transforms = _of(run, "/probe/transform")
    assert len(transforms) == len(states) == 11          # 10 Hz until the program fails at 1 s
    for stamp, tf in transforms:
        state = states[stamp]
        assert (tf["parent_frame_id"], tf["child_frame_id"]) == ("eci", "probe")
        assert [tf["translation"][k] for k in "xyz"] == state["position"]
        w, x, y, z = state["attitude"]
        assert tf["rotation"] == {"x": x, "y": y, "z": z, "w": w}


def test_earth_transform_turns_eci_into_the_earth_fixed_frame(run):
    """A point's coordinates in the child frame 'ecef' (Foxglove: the child's
    pose in the parent) must be the project's ECI -> ECEF conversion; scipy's
    Rotation is the independent quaternion algebra."""
    states = dict(_of(run, "/probe/state"))
    earth = _of(run, "/earth/transform")
    assert [s for s, _ in earth] == sorted(s for s in states if (s - min(states)) % 10**9 == 0)
    for stamp, tf in earth:
        r = tf["rotation"]
        child_in_parent = Rotation.from_quat([r["x"], r["y"], r["z"], r["w"]])
        state = states[stamp]
        in_ecef = child_in_parent.inv().apply(state["position"])
        assert in_ecef == pytest.approx(eci_to_ecef(np.array(state["position"]), state["t"]), abs=1e-6)


def test_location_fix_is_the_geodetic_position(run):
    states = dict(_of(run, "/probe/state"))
    for stamp, fix in _of(run, "/probe/location"):
        state = states[stamp]
        assert (fix["latitude"], fix["longitude"], fix["altitude"]) == (
            state["latitude_deg"], state["longitude_deg"], state["altitude"])
        assert fix["frame_id"] == "probe"


def test_program_output_events_and_the_error_are_foxglove_logs(run):
    logs = [m for _, m in _of(run, "/log")]
    assert [(m["message"], m["name"], m["file"], m["level"]) for m in logs] == [("hello", "probe", "program.py", 2)]
    lines = [m for _, m in _of(run, "/events/log")]
    marker = [m for m in lines if m["message"].startswith("marker ")]
    assert len(marker) == 1 and marker[0]["message"].startswith("marker altitude_m=") and marker[0]["level"] == 2
    assert lines[-1]["level"] == 4 and "boom" in lines[-1]["message"]      # ERROR
    assert math.isclose(lines[-1]["t"], 1.0)


def test_registered_schemas_use_foxgloves_names(run):
    names = {schema for schema, *_ in run}
    assert {"foxglove.FrameTransform", "foxglove.LocationFix", "foxglove.Log", "rocketsim.BodyState",
            "rocketsim.Event"} == names


def test_messages_also_validate_against_the_schemas_registered_in_the_file(tmp_path, scenario):
    out = tmp_path / "run.mcap"
    fly(load(scenario(PROGRAM.replace('raise RuntimeError("boom")', 'fc.log("done")'), duration="2 s")), out)
    with open(out, "rb") as stream:
        reader = make_reader(stream)
        checked = set()
        for schema, channel, message in reader.iter_messages():
            jsonschema.validate(json.loads(message.data), json.loads(schema.data))
            checked.add(schema.name)
    assert checked == {"foxglove.FrameTransform", "foxglove.LocationFix", "foxglove.Log",
                       "rocketsim.BodyState", "rocketsim.Event"}
