"""Runs the Foxglove app shows whole: schemas its parser takes, messages true to them,
strict-JSON metadata, one frame tree whose frames are named for the body they are
about, maps only about Earth (the rules of :mod:`tests.foxglove_rules`).

Flights: the shipped hop (75 s at a 0.05 s step, engines off at times: the
throttle has no value), the shipped Mars entry's first 20 s (its first state
had its accelerations undefined), and a probe handed over from Earth to the
Moon 600 km outside the Moon's sphere of influence (of tests/unit/sim/test_world_soi.py,
900 s: the handover comes some 600 s in).
"""

import json
import math
import os
import shutil
import subprocess
from pathlib import Path

import numpy as np
import orjson
import pytest
from mcap.reader import make_reader
from scipy.spatial.transform import Rotation

from rocketsim.scenario.load import load
from rocketsim.api.telemetry_flight import fly_to_file as fly
from rocketsim.sim.build import build_world
from rocketsim.telemetry.schemas import BODY_STATE, EVENT
from rocketsim.telemetry import foxglove
from rocketsim.telemetry.writer import TelemetryWriter
from tests import foxglove_rules as rules
from tests.conftest import ROOT
from tests.unit.sim.test_world_soi import EPOCH, approach_state

HOP = ROOT / "scenarios" / "falcon9-hop.yaml"
MARS_ENTRY = ROOT / "scenarios" / "mars-entry.yaml"


@pytest.fixture(scope="module")
def hop(tmp_path_factory):
    """The hop's file and each sample the flight handed the writer (body, values, fields)."""
    out = tmp_path_factory.mktemp("hop") / "hop.mcap"
    kept = []

    class Keeping(TelemetryWriter):
        def sample(self, body, values, fields, leaving=False):
            kept.append((body, values, fields))
            super().sample(body, values, fields, leaving)

        def sample_rows(self, body, rows, fields):
            kept.extend((body, values, fields) for values in rows)
            super().sample_rows(body, rows, fields)

    world = build_world(load(HOP), step=0.05)
    with Keeping(out, 0) as telemetry:
        world.run(telemetry)
    return out, kept


@pytest.fixture(scope="module")
def mars_entry(tmp_path_factory):
    out = tmp_path_factory.mktemp("mars") / "mars-entry.mcap"
    fly(load(MARS_ENTRY), out, duration=20.0)
    return out


@pytest.fixture(scope="module")
def to_the_moon(tmp_path_factory):
    folder = tmp_path_factory.mktemp("moon")
    r, v = approach_state()
    (folder / "vehicle.yaml").write_text("name: probe\nrigid_body:\n  mass: 10 kg\n"
                                         "  inertia: [0.15, 0.12, 0.05]\n")
    (folder / "mission.yaml").write_text(
        f"epoch: {EPOCH}\nstart:\n  state:\n    position: {r.tolist()}\n    velocity: {v.tolist()}\n"
        "duration: 900 s\ngravity: n-body\n")
    (folder / "scenario.yaml").write_text("name: approach\nvehicle: vehicle.yaml\nmission: mission.yaml\n"
                                          "telemetry:\n  rate: 1 Hz\n")
    out = folder / "approach.mcap"
    summary = fly(load(folder / "scenario.yaml"), out)
    assert [e["name"] for e in summary["bodies"]["probe"]["events"]] == ["soi_handover"]
    return out


FLIGHTS = ["hop", "mars_entry", "to_the_moon"]


def _path(request, name):
    flight = request.getfixturevalue(name)
    return flight[0] if isinstance(flight, tuple) else flight


# --- the rules themselves can fail -----------------------------------------------

def test_the_parser_rules_reject_what_the_app_rejects():
    """The two constructs the app's parser threw on ('Unsupported type undefined for
    orbit', 'Unsupported type ["number","null"] for throttle'), and what it takes."""
    assert rules.parser_problems({"type": "object", "properties": {"orbit": {"$ref": "#/$defs/orbit"}},
                                  "$defs": {"orbit": {"type": "object"}}})
    assert rules.parser_problems({"type": "object", "properties": {"throttle": {"type": ["number", "null"]}}})
    assert rules.parser_problems({"type": "object", "additionalProperties": {"type": ["number", "null"]}})
    assert not rules.parser_problems(foxglove.LOG)          # oneOf of numeric consts: an enum


def test_the_tree_and_map_rules_find_two_roots_and_a_fix_off_earth():
    contents = rules.Contents(topics={"/a/transform": "foxglove.FrameTransform",
                                      "/a/state": "rocketsim.BodyState", "/a/location": "foxglove.LocationFix"})
    contents.messages = [("/a/transform", 1, {"parent_frame_id": "eci", "child_frame_id": "a"}),
                         ("/a/transform", 1, {"parent_frame_id": "mars_inertial", "child_frame_id": "b"}),
                         ("/a/state", 1, {"central_body": "mars"}),
                         ("/a/location", 1, {"frame_id": "a"})]
    assert any("roots" in p for p in rules.tree_problems(contents))
    found = rules.location_problems(contents)
    assert len(found) == 2 and "LocationFix" in found[1] and "a under eci" in found[0]


# --- the schemas -----------------------------------------------------------------------

@pytest.mark.parametrize("schema", [BODY_STATE, EVENT, foxglove.FRAME_TRANSFORM, foxglove.LOCATION_FIX,
                                    foxglove.LOG], ids=lambda s: s["title"])
def test_every_schema_written_is_one_the_app_parses(schema):
    assert rules.parser_problems(schema) == []


@pytest.mark.parametrize("name", FLIGHTS)
def test_the_files_break_none_of_the_apps_rules(request, name):
    """Schemas parsed, every message valid against its embedded schema, strict-JSON
    metadata, one frame tree, LocationFix only about Earth."""
    contents = rules.read(_path(request, name))
    assert set(contents.schemas) >= {"rocketsim.BodyState", "foxglove.FrameTransform"}
    assert rules.problems(contents) == []


def test_a_value_that_does_not_exist_is_left_out_not_null(hop):
    """The hop's ring engines never run (no throttle for them), the centre engine is off
    before ignition and after touchdown: those fields are absent, never null."""
    states = [m for _, m in rules.read(hop[0]).of("/falcon9-block5/state")]
    assert not any("booster_Merlin_1D_ring" in m["group_throttle"] for m in states)
    assert 0 < sum("throttle" not in m for m in states) < len(states)
    assert all(value is not None for m in states for value in m.values())


def test_hop_states_are_the_previous_encoding_less_its_nulls(hop):
    """The state fields of every sample are those of the previous encoding, the message
    dictionary written by orjson (nulls where a value is missing: the bytes the writer
    wrote before): equal field by field, a null there being an absent field here, and
    the bytes written those orjson writes for that dictionary without its nulls."""
    path, kept = hop
    with open(path, "rb") as stream:
        written = [bytes(m.data) for _, _, m in make_reader(stream).iter_messages(topics=["/falcon9-block5/state"])]
    assert len(written) == len(kept) > 700
    nulls = 0
    for data, (_, values, fields) in zip(written, kept):
        old = json.loads(orjson.dumps(fields(values.tolist(), int)))
        assert json.loads(data) == _without_nulls(old)
        assert data == orjson.dumps(_without_nulls(old))
        nulls += _without_nulls(old) != old
    assert nulls == len(kept)           # the ring engines never run: their throttle is never there


def _without_nulls(message: dict) -> dict:
    return {k: _without_nulls(v) if isinstance(v, dict) else v for k, v in message.items() if v is not None}


def test_the_summary_metadata_is_strict_json(mars_entry):
    text = rules.read(mars_entry).metadata["summary"]["json"]
    assert "NaN" not in text and json.loads(text)["bodies"]


def test_the_first_mars_state_has_its_accelerations(mars_entry):
    """They were nan (the other bodies' held positions were not set before the first
    step): the entry capsule, 400 km up (no air), falls at Mars's pull, GM / r^2
    (GM = 4.282837e13 m^3/s^2, JPL), give or take Mars's J2 (1.96e-3: up to
    3/2 J2 (R/r)^2, 0.25 %); nothing but gravity acts, so the sensed acceleration is nil."""
    first = rules.read(mars_entry).of("/mars-entry-capsule/state")[0][1]
    r = np.linalg.norm(first["position"])
    assert first["acceleration"] == pytest.approx(4.282837e13 / r**2, rel=3e-3)
    assert first["sensed_acceleration"] < 1e-3 * first["acceleration"]


# --- frames ---------------------------------------------------------------------------

def test_about_mars_the_body_hangs_in_mars_frames_and_no_map(mars_entry):
    contents = rules.read(mars_entry)
    pairs = {(tf["parent_frame_id"], tf["child_frame_id"]) for _, _, tf in contents.transforms()}
    assert pairs == {("mars_inertial", "mars-entry-capsule"), ("mars_inertial", "mars_fixed"),
                     ("mars_inertial", "mission")}
    assert not any(name == "foxglove.LocationFix" for name in contents.topics.values())
    assert not any(topic.startswith("/earth/") for topic in contents.topics)


def test_mars_fixed_frame_turns_so_that_the_state_longitude_is_read_in_it(mars_entry):
    """The state's planetocentric longitude is the longitude of the body's position seen
    in ``mars_fixed`` (scipy's Rotation as the independent quaternion algebra), and the
    frame turns at Mars's IAU rate, 350.891982443297 deg/day (IAU WGCCRE 2015, Archinal
    et al. 2018, Table 2; its periodic terms move the rate by parts in 10^8)."""
    contents = rules.read(mars_entry)
    states = dict(contents.of("/mars-entry-capsule/state"))
    turns = contents.of("/mars/transform")
    assert len(turns) >= 3
    for stamp, tf in turns:
        q = tf["rotation"]
        x, y, _ = Rotation.from_quat([q["x"], q["y"], q["z"], q["w"]]).inv().apply(states[stamp]["position"])
        assert math.degrees(math.atan2(y, x)) == pytest.approx(states[stamp]["longitude_deg"], abs=1e-9)
    angles = np.unwrap([2.0 * math.atan2(tf["rotation"]["z"], tf["rotation"]["w"]) for _, tf in turns])
    rate = (angles[-1] - angles[0]) / ((turns[-1][0] - turns[0][0]) * 1e-9)
    # the angle is read at TT Julian dates of 2.46e6 days held in 64-bit floats: 40 us steps
    assert math.degrees(rate) * 86400.0 == pytest.approx(350.891982443297, rel=1e-5)


def test_at_the_handover_the_probe_goes_on_in_the_moons_frames(to_the_moon):
    """Before the handover the probe hangs under ``eci`` with a location; after it under
    ``moon_inertial`` (as ``probe/moon_inertial``), which hangs under ``eci`` where the
    Moon is: the two samples at the handover instant, one in each frame, are the same
    point once the Moon's frame is composed in (scipy's Rotation for the quaternion)."""
    contents = rules.read(to_the_moon)
    states = contents.of("/probe/state")
    handover = next(t for (t, a), (_, b) in zip(states, states[1:]) if a["central_body"] != b["central_body"])
    body = [(t, tf) for t, tf in contents.of("/probe/transform")]
    before = {tf["parent_frame_id"] + ">" + tf["child_frame_id"] for t, tf in body if t < handover}
    after = {tf["parent_frame_id"] + ">" + tf["child_frame_id"] for t, tf in body if t >= handover}
    assert before == {"eci>probe"} and after == {"moon_inertial>probe/moon_inertial"}
    fixes = [t for t, _ in contents.of("/probe/location")]
    assert fixes and max(fixes) < handover
    moon = [tf for t, tf in contents.of("/moon/transform") if tf["child_frame_id"] == "moon_inertial"
            and t == handover]
    assert moon and moon[0]["parent_frame_id"] == "eci"
    pair = [m for t, m in states if t == handover][:2]        # (the sample of the rate may follow)
    assert [m["central_body"] for m in pair] == ["earth", "moon"]
    q, place = moon[0]["rotation"], moon[0]["translation"]
    in_eci = Rotation.from_quat([q["x"], q["y"], q["z"], q["w"]]).apply(pair[1]["position"]) \
        + [place[k] for k in "xyz"]
    assert in_eci == pytest.approx(pair[0]["position"], abs=1e-3)


def test_the_mission_frame_follows_the_lead_in_the_root_across_the_handover(to_the_moon):
    """``mission`` hangs under the root (``eci``) all along, at the probe's centre of mass:
    its state's position about Earth, and about the Moon the position composed with the
    Moon's frame (the first second after the handover; the Moon's frame is written
    once a second, the probe's samples at 1 Hz fall on it)."""
    contents = rules.read(to_the_moon)
    mission = contents.of("/mission/transform")
    states = {}
    for t, m in contents.of("/probe/state"):
        states.setdefault(t, []).append(m)
    assert {tf["parent_frame_id"] for _, tf in mission} == {"eci"}
    moon = {t: tf for t, tf in contents.of("/moon/transform") if tf["child_frame_id"] == "moon_inertial"}
    about_moon = 0
    for t, tf in mission:
        if len(states[t]) > 1:
            continue                # the handover instant: a sample in each frame
        state = states[t][0]
        where = [tf["translation"][k] for k in "xyz"]
        if state["central_body"] == "earth":
            assert where == state["position"]
        elif t in moon:
            q, place = moon[t]["rotation"], moon[t]["translation"]
            expected = Rotation.from_quat([q["x"], q["y"], q["z"], q["w"]]).apply(state["position"]) \
                + [place[k] for k in "xyz"]
            assert where == pytest.approx(expected, abs=1e-3)
            about_moon += 1
    assert about_moon > 10


# --- the layout and the checker --------------------------------------------------------

LAYOUT = ROOT / "docs" / "foxglove-layout.json"
CHECK = Path(os.environ.get("FOXGLOVE_CHECK", ROOT.parent / "shared" / "tools" / "foxglove-check" / "check"))


def _strings(value):
    if isinstance(value, dict):
        for v in value.values():
            yield from _strings(v)
    elif isinstance(value, list):
        for v in value:
            yield from _strings(v)
    elif isinstance(value, str):
        yield value


def test_the_layout_names_only_topics_fields_and_frames_the_files_carry(hop):
    """docs/foxglove-layout.json is JSON; its 3-D panel follows a frame of the hop's file,
    its plots read fields of its state messages, its map and log read its topics."""
    layout = json.loads(LAYOUT.read_text())
    contents = rules.read(hop[0])
    frames = {tf[k] for _, _, tf in contents.transforms() for k in ("parent_frame_id", "child_frame_id")}
    panels = layout["configById"]
    assert {key.split("!")[0] for key in panels} == {"3D", "Plot", "map", "RosOut"}
    assert panels["3D!rocketsim"]["followTf"] == "mission" in frames
    paths = [s for s in _strings(layout) if s.startswith("/")]
    assert paths
    state = contents.of("/falcon9-block5/state")[-1][1]
    for path in paths:
        topic, _, field = path.partition(".")
        assert topic in contents.topics, path
        assert not field or field in state, path
    assert {p.partition(".")[2] for p in paths} >= {"altitude", "inertial_speed", "surface_speed", "dynamic_pressure"}


@pytest.mark.skipif(shutil.which("node") is None or not CHECK.exists(),
                    reason="foxglove-check needs node and ../shared/tools/foxglove-check beside the repository")
def test_foxglove_check_finds_no_problem(hop, mars_entry, to_the_moon):
    """The official TypeScript MCAP readers, Foxglove's published schemas and the app's
    own JSON-schema parser (the project's foxglove-check, ../shared/tools/foxglove-check
    or $FOXGLOVE_CHECK) read the three flights without a problem."""
    done = subprocess.run([str(CHECK), str(hop[0]), str(mars_entry), str(to_the_moon)],
                          capture_output=True, text=True, timeout=600)
    if done.returncode == 2:
        pytest.skip(f"foxglove-check could not set itself up: {done.stderr.strip()[-300:]}")
    assert done.stdout.strip().splitlines()[-1] == "foxglove-check: 3 files, 0 problems", done.stdout
    assert done.returncode == 0
