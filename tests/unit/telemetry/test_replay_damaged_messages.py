"""A run whose messages lack what a summary reads is damaged: exit 2, not a KeyError.

Found by tests/fuzz: a changed byte turned a state message's "longitude_deg" into
another key (the JSON still valid), and replay's summary raised KeyError.
"""

import json

from mcap.writer import Writer

from tests.unit.scenario.test_scenario_errors import assert_clean_error


def _run(path, topic, message):
    with open(path, "wb") as stream:
        writer = Writer(stream)
        writer.start()
        schema = writer.register_schema("x", "jsonschema", b"{}")
        channel = writer.register_channel(topic, "json", schema)
        writer.add_message(channel, 1, json.dumps(message).encode(), 1)
        writer.finish()


def test_a_state_message_without_its_fields_is_damage(cli, tmp_path):
    path = tmp_path / "run.mcap"
    _run(path, "/probe/state", {"t": 0.0, "altitude": 1.0, "latitude_deg": 0.0, "longitudf_deg": 0.0,
                                "speed": 1.0})
    assert_clean_error(cli("replay", path), "is damaged", "a damaged /state message")


def test_an_event_that_is_not_a_mapping_is_damage(cli, tmp_path):
    path = tmp_path / "run.mcap"
    _run(path, "/events", [1, 2, 3])
    assert_clean_error(cli("replay", path), "is damaged", "a damaged /events message")


def test_a_weather_file_whose_kind_is_a_list_is_an_input_error(write, cli):
    write("vehicle.yaml", "name: probe\nrigid_body: {mass: 10 kg, inertia: [0.15, 0.12, 0.05]}\n")
    write("weather.yaml", "kind: [random]\nseed: 7\n")
    path = write("scenario.yaml", "name: x\nvehicle: vehicle.yaml\nweather: weather.yaml\nmission:\n"
                                  "  epoch: 2026-11-26T12:00:00Z\n  start: {orbit: {altitude: 415 km, "
                                  "inclination: 0 deg}}\n  duration: 1 s\n")
    assert_clean_error(cli("validate", path), "weather.yaml:1:1")
