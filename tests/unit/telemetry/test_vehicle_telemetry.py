"""Telemetry of engines, propellant and heating: the state message's
``throttle``, ``thrust``, ``mass_flow``, ``engines_running``, ``propellant``,
``propellant_tanks``, ``heat_flux`` and ``shield_temperature`` fields
(:mod:`rocketsim.sim.sampling`), checked against independent computations
from the same run, the schema, the CSV export, and a flight without telemetry.

References: the Merlin 1D's published figures in vehicles/falcon9-block5.yaml
(914.1 kN and 311 s in vacuum, 0.680 m^2 exit area): full-throttle mass flow
``T_vac / (g0 Isp_vac)`` and thrust ``T_vac - p_a A_e``, with ``p_a`` from the
1976 standard atmosphere (rocketsim.atmosphere.ussa1976, the tabulated model,
not the day's interpolated table); the heat flux by Sutton & Graves (NASA TR
R-376, 1971), ``q = 1.7415e-4 sqrt(rho / r_n) v^3`` (W/m^2) with ``rho`` from
the same standard atmosphere; the shield's temperature by its energy balance
``m c dT/dt = A (q (1 - h_w/h_0) - eps sigma T^4)`` integrated by the trapezoid
rule over the samples (the world integrates it by RK4 every step).
"""

import csv
import json
import math
from pathlib import Path

import jsonschema
import numpy as np
import pytest
from mcap.reader import make_reader

from rocketsim.atmosphere.ussa1976 import us_standard_1976
from rocketsim.constants import AIR_CP, EARTH_OMEGA, G0, STEFAN_BOLTZMANN
from rocketsim.scenario.load import load
from rocketsim.api.telemetry_flight import fly_to_file as fly
from rocketsim.sim.build import build_world
from rocketsim.telemetry.reader import raw_messages
from rocketsim.telemetry.names import column_name
from rocketsim.telemetry.tables import export, table

ROOT = Path(__file__).resolve().parents[3]

# the Falcon 9 booster with the hop's 25 t of propellant; its centre engine at full
# throttle for 4 s, then shut down (8 s flown: liftoff, a short climb)
BURN = f"""\
name: burn
vehicle: {ROOT / 'vehicles' / 'falcon9-block5.yaml'}
stages: [booster]
propellant: {{booster/RP-1: 7.44 t, booster/LOX: 17.56 t}}
site: {ROOT / 'scenarios' / 'sites' / 'cape-canaveral-slc40.yaml'}
program: program.py
mission:
  epoch: 2026-11-26T15:00:00Z
  start: {{site: {{}}}}
  duration: 8 s
"""
BURN_PROGRAM = """
def main(fc):
    fc.throttle(1.0, "Merlin 1D centre")
    fc.ignite("Merlin 1D centre")
    fc.sleep(4.0)
    fc.shutdown("Merlin 1D centre")
    fc.sleep(10.0)
"""
MERLIN_THRUST, MERLIN_ISP, MERLIN_EXIT = 914.1e3, 311.0, 0.680      # N, s, m^2 (the vehicle file)

# the Mars entry capsule (4.5 m aeroshell, 1.125 m nose radius, lumped 350 kg shield)
# entering Earth's air: 95 km over the equator, 7.6 km/s, descending at 300 m/s;
# 30 s at the 0.1 s headless step (the heating's time scale is tens of seconds)
ENTRY = f"""\
name: entry
vehicle: {ROOT / 'vehicles' / 'mars-entry-capsule.yaml'}
mission:
  epoch: 2026-11-26T15:00:00Z
  start:
    state:
      position: [6473.137 km, 0 km, 0 km]
      velocity: [-0.3 km/s, 7.6 km/s, 0 km/s]
  duration: 30 s
step: 0.1 s
"""


def _fly(folder: Path, scenario: str, program: str | None = None):
    """Fly the scenario with telemetry to ``run.mcap`` (as ``rocketsim fly`` does) and
    again without any; returns the file and the world flown without telemetry."""
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "scenario.yaml").write_text(scenario)
    if program is not None:
        (folder / "program.py").write_text(program)
    loaded = load(folder / "scenario.yaml")
    out = folder / "run.mcap"
    fly(loaded, out)
    quiet = build_world(loaded)
    quiet.run(None)
    return out, quiet


def _same_end(last: dict, quiet) -> None:
    """Reading the telemetry changes nothing: the flight without it ends at the
    bit-identical state (JSON floats round-trip exactly)."""
    body = quiet.bodies[0]
    assert last["t"] == body.t
    assert last["position"] == body.position.tolist() and last["velocity"] == body.velocity.tolist()
    assert last["attitude"] == body.attitude.tolist()
    assert list(last["propellant_tanks"].values()) == body.y[body.vehicle.tanks].tolist()


def _states(path: Path, body: str) -> tuple[list[dict], dict]:
    with open(path, "rb") as stream:
        reader = make_reader(stream)
        schemas = {s.name: json.loads(s.data) for s in reader.get_summary().schemas.values()}
        messages = [json.loads(m.data) for _, _, m in reader.iter_messages(topics=[f"/{body}/state"])]
    return messages, schemas["rocketsim.BodyState"]


@pytest.fixture(scope="module")
def burn(tmp_path_factory):
    return _fly(tmp_path_factory.mktemp("burn"), BURN, BURN_PROGRAM)


@pytest.fixture(scope="module")
def entry(tmp_path_factory):
    return _fly(tmp_path_factory.mktemp("entry"), ENTRY)


def test_propellant_and_mass_flow_of_a_full_throttle_burn(burn):
    path, quiet = burn
    states, schema = _states(path, quiet.bodies[0].name)
    validator = jsonschema.validators.validator_for(schema)(schema)
    for message in states:
        validator.validate(message)
    first = states[0]
    # no engine running: no throttle (left out, the schema's type holding for every field)
    assert first["propellant"] == 25_000.0 and first["engines_running"] == 0 and "throttle" not in first
    assert first["propellant_tanks"] == {"booster_RP-1": 7440.0, "booster_LOX": 17560.0}
    mdot = MERLIN_THRUST / (G0 * MERLIN_ISP)                        # 299.7 kg/s
    full = [m for m in states if m.get("throttle") == 1.0 and m["mass_flow"] == pytest.approx(mdot, rel=1e-12)]
    assert len(full) >= 20, "the burn holds full throttle for 2 s or more (of 4 s, after ignition and spool-up)"
    for m in full:
        assert m["engines_running"] == 1
        assert m["group_throttle"] == {"booster_Merlin_1D_centre": 1.0}         # the ring does not run
        p_a = float(us_standard_1976(m["altitude"]).pressure)
        assert m["thrust"] == pytest.approx(MERLIN_THRUST - p_a * MERLIN_EXIT, rel=2e-3)
        assert m["group_thrust"]["booster_Merlin_1D_centre"] == m["thrust"]
    # at full throttle the tanks drain linearly: the drop between two samples is mdot dt
    a, b = full[0], full[-1]
    assert a["propellant"] - b["propellant"] == pytest.approx(mdot * (b["t"] - a["t"]), rel=1e-9)
    # the tanks share the flow by the 2.36 mixture ratio (LOX / RP-1 by mass)
    lox = a["propellant_tanks"]["booster_LOX"] - b["propellant_tanks"]["booster_LOX"]
    rp1 = a["propellant_tanks"]["booster_RP-1"] - b["propellant_tanks"]["booster_RP-1"]
    assert lox / rp1 == pytest.approx(17.56 / 7.44, rel=1e-9)
    for m in states:                                            # all the mass lost is propellant
        assert first["mass"] - m["mass"] == pytest.approx(first["propellant"] - m["propellant"], abs=1e-6)
        assert m["propellant"] == pytest.approx(sum(m["propellant_tanks"].values()), rel=1e-15)
    last = states[-1]
    assert last["engines_running"] == 0 and last["thrust"] == 0.0 and last["mass_flow"] == 0.0
    _same_end(last, quiet)


def test_heat_flux_and_shield_temperature_of_an_entry(entry):
    path, quiet = entry
    body = quiet.bodies[0]
    shield = body.checks.shield
    states, schema = _states(path, body.name)
    validator = jsonschema.validators.validator_for(schema)(schema)
    for message in states:
        validator.validate(message)
    assert "throttle" not in states[0] and states[0]["engines_running"] == 0
    air = us_standard_1976(np.array([m["altitude"] for m in states]))
    rates = []
    for m, rho, air_temperature in zip(states, air.density, air.temperature):
        r, v = np.array(m["position"]), np.array(m["velocity"])
        speed = float(np.linalg.norm(v - np.cross((0.0, 0.0, EARTH_OMEGA), r)))      # still air
        q = 1.7415e-4 * math.sqrt(rho / shield.nose_radius) * speed ** 3
        # the world reads the day's table (interpolated rows) at the radial height: 1e-4
        assert m["heat_flux"] == pytest.approx(q, rel=1e-4)
        total = AIR_CP * air_temperature + 0.5 * speed ** 2
        hot = q * max(0.0, 1.0 - AIR_CP * m["shield_temperature"] / total)
        rates.append(shield.area * (hot - shield.emissivity * STEFAN_BOLTZMANN * m["shield_temperature"] ** 4)
                     / (shield.mass * shield.specific_heat))
    t = np.array([m["t"] for m in states])
    temperature = np.array([m["shield_temperature"] for m in states])
    assert temperature[0] == shield.initial_temperature
    rise = float(np.sum(0.5 * (np.array(rates[1:]) + np.array(rates[:-1])) * np.diff(t)))
    assert temperature[-1] - temperature[0] > 100.0, "the shield heats by more than 100 K"
    assert temperature[-1] - temperature[0] == pytest.approx(rise, rel=1e-2)
    assert max(m["heat_flux"] for m in states) > 1e5
    _same_end(states[-1], quiet)
    assert states[-1]["shield_temperature"] == body.checks.temperature


def test_the_new_columns_are_exported_row_for_row(burn, tmp_path):
    path, quiet = burn
    body = quiet.bodies[0].name
    states, _ = _states(path, body)
    columns = table(path, body)
    for key in ("throttle", "thrust", "mass_flow", "engines_running", "propellant",
                "propellant_tanks_booster_LOX", "group_thrust_booster_Merlin_1D_centre"):
        assert len(columns[key]) == len(states)
    assert columns["propellant"] == [m["propellant"] for m in states]
    assert columns["propellant_tanks_booster_LOX"] == [m["propellant_tanks"]["booster_LOX"] for m in states]
    written = {p.name: p for p in export(path, tmp_path, "csv")}
    with open(written[f"{body}.csv"], newline="") as stream:
        rows = list(csv.DictReader(stream))
    assert len(rows) == len(states)
    assert "propellant_kg" in rows[0]          # the file's names carry their unit
    assert [float(r[column_name("propellant")]) for r in rows] == [m["propellant"] for m in states]
    assert [r[column_name("throttle")] for r in rows][:1] == [""]        # no engine running at t = 0


def _propulsion_lines(path: Path) -> list[np.ndarray]:
    """The y data of the curves drawn on the replay plot's propulsion panel (its left axis:
    throttle or thrust; the events' vertical marks left out) of the run ``path``; None:
    the plot has no such panel."""
    from rocketsim.plots import flight_panels
    from rocketsim.plots.canvas import pyplot
    figure = flight_panels.figure(path)
    try:
        panels = [ax for ax in figure.axes if ax.get_title().startswith("propulsion")]
        return [np.asarray(line.get_ydata(), float) for line in panels[0].lines
                if len(line.get_ydata()) > 2] if panels else None
    finally:
        pyplot().close(figure)


def test_the_plot_draws_throttle_and_propellant(burn, tmp_path):
    path, _ = burn
    states, _ = _states(path, burn[1].bodies[0].name)
    lines = _propulsion_lines(path)
    # the throttle flown, sample for sample: full while the centre engine burns
    flown = np.array([np.nan if m.get("throttle") is None else m["throttle"] for m in states])
    assert len(lines) == 1 and np.array_equal(lines[0], flown, equal_nan=True)
    assert np.nanmax(lines[0]) > 0.99
    # a rigid body's run (no throttle, no propellant) has no propulsion panel
    rigid = tmp_path / "rigid"
    rigid.mkdir()
    (rigid / "vehicle.yaml").write_text("name: probe\nrigid_body:\n  mass: 10 kg\n  inertia: [0.15, 0.12, 0.05]\n")
    (rigid / "scenario.yaml").write_text(
        "name: rigid\nvehicle: vehicle.yaml\nmission:\n  epoch: 2026-11-26T12:00:00Z\n"
        "  start: {orbit: {altitude: 415 km, inclination: 51.6 deg}}\n  duration: 2 s\n")
    fly(load(rigid / "scenario.yaml"), rigid / "run.mcap")
    assert _propulsion_lines(rigid / "run.mcap") is None


def test_the_burn_writes_the_same_bytes_twice(burn, tmp_path):
    path, _ = burn
    again = tmp_path / "again.mcap"
    fly(load(path.parent / "scenario.yaml"), again)
    assert raw_messages(again) == raw_messages(path)


def test_parquet_export_keeps_the_rows_and_types_a_column_never_set_as_float(burn, tmp_path):
    pyarrow = pytest.importorskip("pyarrow")
    import pyarrow.parquet
    path, quiet = burn
    body = quiet.bodies[0].name
    states, _ = _states(path, body)
    export(path, tmp_path, "parquet")
    written = pyarrow.parquet.read_table(tmp_path / f"{body}.parquet")
    assert written.num_rows == len(states)
    assert written.column("thrust_N").to_pylist() == [m["thrust"] for m in states]
    # the ring never runs: no throttle of it in any state, no column; the centre's throttle
    # is missing before ignition and after the shutdown: float, null there
    assert column_name("group_throttle_booster_Merlin_1D_ring") not in written.schema.names
    centre = written.schema.field(column_name("group_throttle_booster_Merlin_1D_centre"))
    missing = sum("booster_Merlin_1D_centre" not in m["group_throttle"] for m in states)
    assert centre.type == pyarrow.float64() and written.column(centre.name).null_count == missing > 0


def _both_encodings(bodies, folder: Path, monkeypatch, trials: int = 120) -> None:
    """The template path (``TelemetryWriter.sample``: the numbers spliced into byte
    templates of the three messages, :mod:`rocketsim.telemetry.splice`) writes the same
    file, byte for byte, as the straightforward one (``TelemetryWriter.state``:
    ``orjson.dumps`` of each message built as a dictionary, ``fields(values.tolist(),
    int)``), for the body's own numbers and for the same
    message shape filled with numbers of every kind: NaN and infinities,
    -0.0, subnormal, the largest double, exponents from -300 to 300 (a NaN or an
    infinity is left out of an object, null in a vector). Small chunks, so
    that chunks end inside a sample's records (the chunk ends where one-by-one
    messages end it); times 0.37 s apart, so the Earth's transform comes between
    samples' state and transform messages every second or so; events and log lines
    between samples, and samples still waiting at the end of the file, so that the
    waiting samples (``TelemetryWriter.PENDING``) are written in the flight's order. The
    same samples handed over in blocks of rows (``TelemetryWriter.sample_rows``, as a
    compiled run's samples are) write the same bytes again. ``bodies``: ``(world,
    body)`` pairs; several bodies' samples are interleaved, sample by sample, as the
    world's loop writes them (blocks of one row each), so templates of several bodies
    and shapes alternate within one batch."""
    import orjson
    import rocketsim.telemetry.writer as writer_module
    from rocketsim.sim import sampling
    from rocketsim.stepping.sample_figures import SAMPLE_VEHICLE
    from rocketsim.telemetry.writer import TelemetryWriter
    monkeypatch.setattr(writer_module, "CHUNK_SIZE", 3_000)
    rng = np.random.default_rng(10)
    special = np.array([math.nan, math.inf, -math.inf, -0.0, 0.0, 5e-324, 1.7976931348623157e308,
                        1e16, 1e-7, 0.1, 123456789.0, 2.0 ** 53])
    samples = []        # (body's name, its numbers, fields), in the flight's order
    for k in range(trials):
        for world, body in bodies:
            values, fields = sampling.values(body, world.gmst0, world.where)
            v = values.copy()
            if k:
                odd = rng.random(v.size) < 0.3
                v[odd] = rng.normal(size=odd.sum()) * 10.0 ** rng.integers(-300, 300, odd.sum())
                chosen = rng.random(v.size) < 0.2
                v[chosen] = rng.choice(special, chosen.sum())
                v[-2] = values[-2] + 0.37 * k                  # the time: finite, increasing
                if body.vehicle is not None:
                    v[SAMPLE_VEHICLE + 3] = rng.integers(0, 40)   # engines running: a count
            samples.append((body.name, v, fields))
    alone = len(bodies) == 1
    if not alone:       # and again later: every template made, so interleaved blocks are spliced at once
        again = [(name, v.copy(), fields) for name, v, fields in samples]
        for _, v, _ in again:
            v[-2] += 0.37 * trials
        samples += again
    folder.mkdir(parents=True, exist_ok=True)
    # the same samples as dictionaries, one by one from their numbers, and in blocks of rows
    # (as a compiled run hands them over: a block between two events); several bodies' also
    # as interleaved blocks, each body's rows between two events in one block, handed over
    # together (as a window hands over its runs' samples: step k of body i at rank i)
    paths = folder / "dictionaries.mcap", folder / "templates.mcap", folder / "rows.mcap", \
        folder / "interleaved.mcap"
    for path in paths[:3] if alone else paths:
        with TelemetryWriter(path, 1_795_694_400 * 10**9) as telemetry:
            for _, body in bodies:
                telemetry.add_body(body.name)
            block, blocks = [], {}
            for k, (name, v, fields) in enumerate(samples):
                if path is paths[0]:
                    telemetry.state(name, fields(v.tolist(), int), fields.frame)
                elif path is paths[1]:
                    telemetry.sample(name, v, fields)
                elif alone:
                    block.append(v)
                elif path is paths[2]:
                    telemetry.sample_rows(name, v.reshape(1, -1), fields)
                else:
                    rank = k % len(bodies)
                    blocks.setdefault(rank, (name, [], fields, k // len(bodies), 1, rank))[1].append(v)
                if k % 7 == 3 or k == len(samples) - 1:     # written in the flight's order
                    if block:
                        telemetry.sample_rows(name, np.array(block), fields)
                    if blocks:
                        telemetry.sample_interleaved([(name, np.array(rows), *rest)
                                                      for name, rows, *rest in blocks.values()])
                    block, blocks = [], {}
                    telemetry.event(v[-2], name, "mark", {"k": k})
                    telemetry.log(v[-2], name, f"line {k}")
    assert paths[0].read_bytes() == paths[1].read_bytes() == paths[2].read_bytes()
    if not alone:
        assert paths[3].read_bytes() == paths[0].read_bytes()
    name, values, fields = samples[0]
    first = json.loads(next(m for topic, _, m in raw_messages(paths[1]) if topic == f"/{name}/state"))
    # the body's own numbers, less the values it has not (None in the dictionary)
    expected = orjson.loads(orjson.dumps(fields(values.tolist(), int)))
    assert first == {k: {g: x for g, x in v.items() if x is not None} if isinstance(v, dict) else v
                     for k, v in expected.items() if v is not None}


def test_templates_write_what_dictionaries_write_for_a_staged_vehicle(burn, entry, tmp_path, monkeypatch):
    # the booster with engine groups and tanks (after the burn: no throttles), then the
    # capsule with its heat shield (heat flux, shield temperature)
    for k, (_, quiet) in enumerate((burn, entry)):
        _both_encodings([(quiet, quiet.bodies[0])], tmp_path / str(k), monkeypatch)


def test_templates_write_what_dictionaries_write_for_a_rigid_body_and_about_mars(scenario, tmp_path,
                                                                                monkeypatch):
    coast = build_world(load(scenario(duration="1 s")))
    coast.run(None)
    _both_encodings([(coast, coast.bodies[0])], tmp_path / "coast", monkeypatch)
    mars = build_world(load(ROOT / "scenarios" / "mars-entry.yaml"), duration=0.2)
    mars.run(None)
    assert mars.bodies[0].central == "mars"
    _both_encodings([(mars, mars.bodies[0])], tmp_path / "mars", monkeypatch)


def test_templates_write_what_dictionaries_write_for_bodies_interleaved(tmp_path, monkeypatch):
    # the Falcon 9 mission at 230 s: the upper stage, the booster and the fairing's halves
    # (two staged vehicles and two tumbling parts) sampled in turn, as the world's loop
    # samples several bodies: each batch of samples mixes their templates
    mission = build_world(load(ROOT / "scenarios" / "falcon9-leo.yaml"), duration=230.0)
    mission.run(None)
    assert len(mission.bodies) == 4
    _both_encodings([(mission, body) for body in mission.bodies], tmp_path / "mission", monkeypatch, trials=60)
