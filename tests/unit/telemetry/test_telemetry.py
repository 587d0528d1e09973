"""MCAP telemetry: channels, schemas, rate, attachments, determinism."""

import json

import jsonschema
import pytest

from rocketsim.scenario.load import load
from rocketsim.api.telemetry_flight import fly_to_file as fly
from rocketsim.telemetry.reader import attachments, messages, metadata, raw_messages

PROGRAM = """
def main(fc):
    fc.sleep(1.0)
    fc.log("one second")
    fc.event("marker", altitude_m=fc.altitude)
"""


def test_state_channel_rate_schema_and_attachments(scenario, tmp_path):
    path = scenario(PROGRAM, duration="3 s")
    out = tmp_path / "run.mcap"
    fly(load(path), out)
    states = list(messages(out, ["/probe/state"]))
    # default 10 Hz: t = 0, 0.1, ..., 3.0
    assert [m["t"] for _, _, m in states] == pytest.approx([k / 10 for k in range(31)])
    # timestamps are the mission epoch (2026-11-26T12:00:00Z) plus mission time
    assert states[0][1] == 1795694400 * 10**9
    assert states[-1][1] - states[0][1] == 3 * 10**9
    from mcap.reader import make_reader
    with open(out, "rb") as stream:
        summary = make_reader(stream).get_summary()
    schemas = {s.name: json.loads(s.data) for s in summary.schemas.values()}
    for _, _, message in states:
        jsonschema.validate(message, schemas["rocketsim.BodyState"])
    files = attachments(out)
    assert files["scenario/scenario.yaml"] == path.read_bytes()
    assert files["program/program.py"] == path.with_name("program.py").read_bytes()
    assert files["vehicle/vehicle.yaml"] == path.with_name("vehicle.yaml").read_bytes()
    assert files["mission/mission.yaml"] == path.with_name("mission.yaml").read_bytes()
    info = metadata(out)
    assert info["rocketsim"]["epoch_utc"] == "2026-11-26T12:00:00+00:00"
    assert json.loads(info["summary"]["json"])["bodies"]["probe"]["events"][0]["name"] == "marker"


def test_configurable_rate(scenario, tmp_path):
    out = tmp_path / "run.mcap"
    fly(load(scenario(duration="2 s", extra="telemetry:\n  rate: 2 Hz\n")), out)
    assert [m["t"] for _, _, m in messages(out, ["/probe/state"])] == pytest.approx([0, 0.5, 1, 1.5, 2])


def test_the_same_run_twice_gives_identical_bytes(scenario, tmp_path):
    path = scenario(PROGRAM, duration="20 s")
    first, second = tmp_path / "a.mcap", tmp_path / "b.mcap"
    fly(load(path), first)
    fly(load(path), second)
    assert raw_messages(first) == raw_messages(second)
    assert first.read_bytes() == second.read_bytes()


def test_telemetry_samples_agree_with_the_geodetic_conversion(scenario, tmp_path):
    """Latitude/longitude/height in telemetry are the WGS84 conversion of the
    ECI position turned into the Earth-fixed frame at that mission time."""
    import numpy as np
    from rocketsim.frames.earth_fixed import eci_to_ecef
    from rocketsim.frames.geodetic import ecef_to_geodetic
    out = tmp_path / "run.mcap"
    fly(load(scenario(duration="60 s")), out)
    for _, _, m in list(messages(out, ["/probe/state"]))[::100]:
        lat, lon, h = ecef_to_geodetic(eci_to_ecef(np.array(m["position"]), m["t"]))
        assert m["latitude_deg"] == pytest.approx(np.degrees(lat), abs=1e-12)
        assert m["longitude_deg"] == pytest.approx(np.degrees(lon), abs=1e-12)
        assert m["altitude"] == pytest.approx(h, abs=1e-6)
