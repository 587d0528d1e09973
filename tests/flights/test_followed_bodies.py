"""A scenario that follows some of its bodies (``follow``): the others end where they are.

The two-stage solid rocket of ``test_solid_staging.py`` (a 7 s flight at 20 ms, the
booster separating at T+2.6 s) flown three ways: every body to the end, following
the booster alone, and following the sustainer (the vehicle's own body) alone. The
reference is the first flight: a followed body's samples, events and summary are
those of the flight that follows every body, bit for bit (no body acts on another
once split: rocketsim.sim.staging); a body not followed ends at the separation with
the event ``not followed``, its last sample there. A name no body of the flight can
have is an input error naming the file, line and field.
"""

from pathlib import Path

import pytest
import yaml

import rocketsim
from rocketsim.errors import InputError
from tests.flights.test_solid_staging import K1000T, LIGHT, PROGRAM

SEPARATION = 2.6


def scenario(tmp_path: Path, follow=None) -> dict:
    (tmp_path / "program.py").write_text(PROGRAM + LIGHT)
    stage = {"length": "1 m", "diameter": "0.1 m", "motors": [{"name": "K1000T", "file": K1000T}]}
    vehicle = {"name": "two-stage", "stages": [
        {**stage, "name": "booster", "structure_mass": "2 kg"},
        {**stage, "name": "sustainer", "structure_mass": "3 kg",
         "motors": [{"name": "K1000T", "file": K1000T, "ignition": "program"}]}],
        "aero": {"nose": {"length": "0.3 m", "shape": "ogive"},
                 "fins": [{"stage": name, "count": 4, "position": "0.2 m", "root_chord": "0.2 m",
                           "tip_chord": "0.1 m", "span": "0.12 m", "sweep": "0.1 m"}
                          for name in ("booster", "sustainer")],
                 "body_contact_stiffness": 2e4, "body_contact_damping": 2e2,
                 "limits": {"axial_load": "40 g"}}}
    data = {"name": "two-stage", "vehicle": vehicle, "program": str(tmp_path / "program.py"),
            "site": {"name": "pad", "latitude": "32.99 deg", "longitude": "-106.975 deg", "height": "0 m"},
            "mission": {"epoch": "2026-06-13T15:00:00Z", "duration": "7 s",
                        "start": {"site": {"rail": {"length": "5 m", "inclination": "88 deg"}}}}}
    if follow is not None:
        data["follow"] = follow
    return data


@pytest.fixture(scope="module")
def every_body(tmp_path_factory):
    return rocketsim.fly(scenario(tmp_path_factory.mktemp("every")))


def same_body(run, reference, name: str) -> None:
    a, b = run.bodies[name], reference.bodies[name]
    assert a.table().equals(b.table())
    assert a.final == b.final and a.flight == b.flight
    assert [e for e in run.file.events if e["body"] == name] == \
        [e for e in reference.file.events if e["body"] == name]


@pytest.mark.parametrize("followed, left", [(["booster"], "two-stage"), (["two-stage"], "booster")])
def test_a_followed_body_flies_as_it_does_with_every_body_flown(tmp_path, every_body, followed, left):
    run = rocketsim.fly(scenario(tmp_path, followed))
    assert set(run.events["body"]) == {"two-stage", "booster"}
    same_body(run, every_body, followed[0])
    # the one not followed: its flight to the separation as before, then nothing more
    ended = run.events[(run.events["body"] == left) & (run.events["name"] == "not followed")]
    assert ended["t_s"].tolist() == [pytest.approx(SEPARATION, abs=1e-9)]
    table, reference = run.bodies[left].table(), every_body.bodies[left].table()
    assert table.index[-1] == pytest.approx(SEPARATION, abs=1e-9)
    assert reference.index[-1] == pytest.approx(7.0)                   # it flew on there
    before = reference.loc[reference.index <= SEPARATION + 1e-9]
    # the samples to the separation as before, and one more: the body as it was left, split
    assert len(table) == len(before) + 1
    assert table.iloc[:-1].equals(before)
    assert run.bodies[left].final["time_s"] == pytest.approx(SEPARATION, abs=1e-9)


def test_a_name_no_body_can_have_is_an_error_naming_its_line(tmp_path):
    data = scenario(tmp_path, ["booster", "sustainer"])      # the top stage never flies alone
    path = tmp_path / "two-stage.yaml"
    path.write_text(yaml.safe_dump(data, sort_keys=False))
    with pytest.raises(InputError) as raised:
        rocketsim.fly(path)
    error = raised.value
    assert error.file == str(path) and error.field == "follow[1]"
    assert path.read_text().splitlines()[error.line - 1].strip() == "- sustainer"
    assert "'sustainer'" in str(error) and "two-stage, booster" in str(error)
