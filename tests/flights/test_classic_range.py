"""The classic range (docs/physics.md#classic-range): the procedural equatorial site,
the original model's switches (thrust, mass and the density above 86 km held for the
step; the standard atmosphere shifted by the day's surface temperature with
standard-gravity hydrostatics), a shipped program flying there, and determinism."""

import math

import numpy as np
import pytest

from rocketsim.atmosphere.ussa1976 import us_standard_1976
from rocketsim.bodies.gravity import point_mass_j2
from rocketsim.constants import (EARTH_J2, EARTH_MU, EARTH_OMEGA, EARTH_RADIUS_EQ,
                                 EARTH_RADIUS_POLAR, G0, GAS_CONSTANT_USSA, USSA_M0, USSA_P0,
                                 USSA_R0)
from rocketsim.dynamics.derivative import derivative, held_derivative
from rocketsim.dynamics.reference import integrate_reference
from rocketsim.dynamics.rk4 import advance
from rocketsim.frames.mean_elements import mean_elements_of_state
from rocketsim.layout import P_CLASSIC, R, V, make_params
from rocketsim.errors import InputError
from rocketsim.scenario.classic_range import DRONE_SHIP_RANGE, LANDING_ZONE_RANGE, classic_site
from rocketsim.scenario.load import load
from rocketsim.scenario.models import Scenario
from rocketsim.scenario.start_spec import SiteSpec
from rocketsim.scenario.weather import ClassicWeather, build_atmosphere
from rocketsim.scenario.yaml_source import read_yaml
from rocketsim.scenario.models import VehicleSpec
from rocketsim.api.telemetry_flight import fly_to_file as fly
from rocketsim.sim.build import build_world
from rocketsim.api.reflight import verify
from rocketsim.vehicle.engines import ignite
from rocketsim.vehicle.build import build
from tests.conftest import ROOT
from tests.plot_checks import assert_the_plot_reads

CLASSIC_ASCENT = ROOT / "scenarios" / "classic-ascent.yaml"
BURN = 70.0                     # s: the seed's "about 3 m of error after 70 s of burn"


def _params(classic: bool):
    return make_params(1.0, (1.0, 1.0, 1.0), EARTH_MU, EARTH_RADIUS_EQ, EARTH_J2, EARTH_RADIUS_POLAR,
                       classic=classic)


def _falcon9(aero: bool, air=None):
    data = read_yaml(ROOT / "vehicles" / "falcon9-block5.yaml").data
    spec = VehicleSpec.model_validate(data)
    if not aero:
        spec = spec.model_copy(update={"aero": None})
    return build(spec, air=air)


# --- the site -----------------------------------------------------------------

def test_the_classic_site_is_an_equatorial_range_launching_due_east_from_the_seed():
    site = SiteSpec.model_validate(classic_site(11))
    assert site.latitude == 0.0 and site.height == 0.0 and site.model == "classic"
    assert site.pad_azimuth == pytest.approx(math.pi / 2, abs=1e-15)
    pads = {pad.name: pad for pad in site.pads}
    assert set(pads) == {"landing zone", "drone ship"}
    for name, (low, high) in (("landing zone", LANDING_ZONE_RANGE), ("drone ship", DRONE_SHIP_RANGE)):
        pad = pads[name]
        assert pad.latitude == 0.0
        # downrange = east along the equator, an arc of a * dlon on the ellipsoid
        downrange = math.remainder(pad.longitude - site.longitude, 2 * math.pi) * EARTH_RADIUS_EQ
        assert low <= downrange < high
    assert classic_site(11) == classic_site(11)                     # the seed fixes the range
    longitudes = {SiteSpec.model_validate(classic_site(seed)).longitude for seed in range(20)}
    assert len(longitudes) == 20
    assert all(-math.pi <= lon < math.pi for lon in longitudes)


def test_site_classic_in_a_scenario_and_its_pads_as_targets(tmp_path):
    loaded = load(CLASSIC_ASCENT)
    site = loaded.scenario.site
    assert site == SiteSpec.model_validate(classic_site(loaded.scenario.seed))
    assert "site" not in loaded.files                               # generated, not read
    data = {"name": "x", "vehicle": loaded.scenario.vehicle, "site": "classic", "seed": 4,
            "mission": {"epoch": "2026-11-26T15:00:00Z", "start": {"site": {}}, "duration": 10,
                        "target": {"pad": "drone ship"}}}
    scenario = Scenario.model_validate(data)
    ship = [p for p in scenario.site.pads if p.name == "drone ship"][0]
    assert scenario.mission.target.pad == ship
    with pytest.raises(ValueError, match="not one of the site's pads"):
        Scenario.model_validate({**data, "mission": {**data["mission"], "target": {"pad": "LZ-1"}}})
    with pytest.raises(ValueError, match="classic range flies the original model's air"):
        Scenario.model_validate({**data, "weather": {"kind": "random", "seed": 3}})
    # the shipped booster landing names the range's landing zone and flies the booster's
    # return program of the real-site mission
    landing = load(ROOT / "scenarios" / "classic-booster-landing.yaml")
    zone = [p for p in landing.scenario.site.pads if p.name == "landing zone"][0]
    assert landing.scenario.mission.target.pad == zone
    assert landing.stage_program_paths["booster"] == \
        load(ROOT / "scenarios" / "falcon9-leo.yaml").stage_program_paths["booster"]
    # the switch reaches the body's parameters; a real site keeps the realistic model
    assert build_world(loaded, duration=1.0).bodies[0].p[P_CLASSIC] == 1.0
    real = load(ROOT / "scenarios" / "falcon9-leo.yaml")
    assert build_world(real, duration=1.0).bodies[0].p[P_CLASSIC] == 0.0
    bad = tmp_path / "bad.yaml"
    bad.write_text("name: bad\nsite: clasic\nvehicle: {name: v, rigid_body: {mass: 1, inertia: [1, 1, 1]}}\n"
                   "mission: {epoch: 2026-11-26T15:00:00Z, start: {site: {}}, duration: 1}\n")
    with pytest.raises(InputError, match="neither a site file .* nor 'classic'") as caught:
        load(bad)
    assert caught.value.field == "site"


def test_the_range_written_as_a_site_file_is_the_same_site(tmp_path, cli):
    """``rocketsim classic-range --seed 11 -o FILE``: a site file that flies the same range."""
    site_file = tmp_path / "classic-11.yaml"
    assert cli("classic-range", "--seed", 11, "-o", site_file).exit_code == 0
    scenario = tmp_path / "scenario.yaml"
    scenario.write_text(f"name: s\nsite: {site_file.name}\nseed: 11\n"
                        "vehicle: {name: v, rigid_body: {mass: 1, inertia: [1, 1, 1]}}\n"
                        "mission: {epoch: 2026-11-26T15:00:00Z, start: {site: {}}, duration: 1}\n")
    assert load(scenario).scenario.site == SiteSpec.model_validate(classic_site(11))


# --- the original model's switches ---------------------------------------------

@pytest.mark.parametrize("start_height, expected_classic", [
    (0.0, 2.40),            # from the pad through the classic day's air
    (1_000e3, 2.17),        # above the air: the mass hold alone
])
def test_powered_flight_is_first_order_on_the_classic_range(start_height, expected_classic):
    """A Falcon 9-class first stage (full stack, nine engines at full throttle, no aero so
    the burn stays vertical and smooth) burns 70 s straight up, against DOP853 (rtol 1e-13)
    on the continuous model (the plain derivative: nothing held).

    Seed: "thrust, mass and the density above 86 km held for the step ... makes powered
    flight first order in the step -- about 3 m of error after 70 s of burn". Measured:
    2.40 m from the pad (thrust and mass held) and 2.17 m above the air (mass held) at
    20 ms, halving with the step (ratio 2.000). The realistic model on the same burn:
    2.5e-4 m from the pad at 20 ms and at 10 ms alike -- that is the reference's own floor
    (DOP853 across the air table's 50 m rows; the RK4 runs at 80, 40, 20 and 10 ms agree
    with one another to 3e-7 m) -- and 3.5e-8 m above the air, the rounding of a 7e6 m
    position: on a burn this smooth RK4's fourth-order term (h^4 / 2880 times the fourth
    derivative of T/m, ~1e-15 m/s at 20 ms) is below double precision. Its fourth order
    through a turning burn is measured in test_vehicle_burn.py."""
    air = build_atmosphere(ClassicWeather(kind="classic", surface_temperature="27 C"), 0.0, ".",
                           standard_gravity=True)
    m = _falcon9(aero=False, air=air)
    a = m.arrays
    r0 = EARTH_RADIUS_EQ + start_height
    y0 = m.state([r0, 0.0, 0.0], [0.0, EARTH_OMEGA * r0, 0.0])     # nose up, moving with the ground
    for e in m.stage_engines(0):
        assert ignite(y0, a.eng, a.cmd, a.stage, e, a.first_clock)
        y0[a.first_clock + e] = 10.0                                # spooled: full thrust
    reference = integrate_reference(y0, 0.0, BURN, _params(False), rtol=1e-13, atol=1e-9, veh=a)

    def error(h, classic):
        y, taken = advance(y0.copy(), 0, h, round(BURN / h), _params(classic), a)
        assert taken == round(BURN / h)
        return float(np.linalg.norm(y[R:R + 3] - reference[R:R + 3]))

    classic_20, classic_10 = error(0.02, True), error(0.01, True)
    realistic_20, realistic_10 = error(0.02, False), error(0.01, False)
    # "about 3 m" (measured: expected_classic; a band, so a retuned vehicle file keeps it)
    assert 1.5 < classic_20 < 4.5 and classic_20 == pytest.approx(expected_classic, rel=0.25)
    assert 1.95 < classic_20 / classic_10 < 2.05                    # first order: halves
    floor = 1e-3 if start_height == 0.0 else 1e-7                   # the reference's floor
    assert realistic_20 < floor and realistic_10 < floor
    assert classic_20 / realistic_20 > 2000.0


def test_the_density_above_86_km_is_held_for_the_step():
    """Drag in the classic model comes from the density at the step's start when that is
    above 86 km, and from the stage's own height below. Independent figures: the 1976
    standard's densities (ussa1976 module, checked against the published tables)."""
    m = _falcon9(aero=True)
    y = m.state([EARTH_RADIUS_EQ + 100e3, 0.0, 0.0], [300.0, 2000.0, 0.0])
    gx, gy, gz = point_mass_j2(y[R], y[R + 1], y[R + 2], EARTH_MU, EARTH_RADIUS_EQ, EARTH_J2)

    def drag(p, y_held):
        dy = np.zeros_like(y)
        held_derivative(0.01, y, p, dy, m.arrays, 0.0, y_held)
        return np.array(dy[V:V + 3]) - (gx, gy, gz)

    realistic = np.zeros_like(y)
    derivative(0.01, y, _params(False), realistic, m.arrays)
    at_100 = np.array(realistic[V:V + 3]) - (gx, gy, gz)
    assert np.linalg.norm(at_100) > 0.0
    for held_height, held in ((90e3, True), (80e3, False)):
        y_held = y.copy()
        y_held[R] = EARTH_RADIUS_EQ + held_height
        classic = drag(_params(True), y_held)
        ratio = (us_standard_1976(held_height).density / us_standard_1976(100e3).density
                 if held else 1.0)
        np.testing.assert_allclose(classic, at_100 * ratio, rtol=2e-4)
        # the realistic model ignores the hold altogether
        np.testing.assert_array_equal(drag(_params(False), y_held), at_100)


def test_the_classic_day_is_the_standard_shifted_by_the_surface_temperature():
    """The classic-ascent day (27 C) on the classic range: below the 11 km tropopause the
    temperature is the standard's plus 12 K, and with standard gravity the pressure is the
    1976 standard's own barometric law (NOAA-S/T 76-1562, eq. 33a) from the shifted base:
    p = p0 (T_b / (T_b - L H))^(-g0 M0 / (R* L)), T_b = 300.15 K, L = 6.5 K/km, H the
    geopotential height. A real site's hydrostatics (WGS84 normal gravity at the equator,
    0.27 % weaker) miss it by 0.38 % at 11 km."""
    table = load(CLASSIC_ASCENT).atmosphere()
    z = np.arange(0.0, 11_001.0, 500.0)
    H = USSA_R0 * z / (USSA_R0 + z)
    lapse, base = 0.0065, 300.15
    temperature = base - lapse * H
    pressure = USSA_P0 * (temperature / base) ** (G0 * USSA_M0 / (GAS_CONSTANT_USSA * lapse))
    density = pressure * USSA_M0 / (GAS_CONSTANT_USSA * temperature)
    rho, p, t = table.at(z)[:3]
    np.testing.assert_allclose(t, temperature, rtol=1e-12)
    np.testing.assert_allclose(p, pressure, rtol=1e-7)
    np.testing.assert_allclose(rho, density, rtol=1e-7)
    real_site = build_atmosphere(load(CLASSIC_ASCENT).scenario.weather, 0.0, ".")
    assert real_site.at([11_000.0])[1][0] / pressure[-1] - 1.0 == pytest.approx(3.83e-3, rel=0.01)


# --- programs and determinism ----------------------------------------------------

def test_the_ascent_program_reaches_orbit_on_the_classic_range(tmp_path):
    """scenarios/classic-ascent.yaml flies programs/orbit_ascent.py unchanged -- the file
    falcon9-leo.yaml flies from SLC-40, where test_falcon9_ascent.py checks the orbit --
    due east to a 200 km equatorial orbit on the original model. A 0.05 s headless step
    and 525 s of mission time (insertion is at ~523 s) keep it short. The target is in
    Kozai mean elements (the mission's default), whose osculating orbit, equatorial and
    circular at 200 km, is 190.0 x 210.0 km (J2's short-period terms,
    rocketsim.frames.mean_elements): the check reads the insertion's mean elements,
    within 3 km of 200 km (the classic model is first order in the step, and at 0.05 s
    a step at the end of the burn gains 1 m/s)."""
    loaded = load(CLASSIC_ASCENT)
    real = load(ROOT / "scenarios" / "falcon9-leo.yaml")
    assert loaded.program_path == real.program_path                 # the same program file
    summary = fly(loaded, tmp_path / "classic.mcap", step=0.05, duration=525.0)
    assert_the_plot_reads(tmp_path / "classic.mcap", "classic-ascent")
    body = summary["bodies"]["falcon9-block5"]
    events = {e["name"]: e for e in body["events"]}
    assert {"liftoff", "MECO", "separation", "orbit"} <= set(events)
    mean = mean_elements_of_state(np.array(body["final"]["position_m"]), np.array(body["final"]["velocity_m_s"]))
    for radius in (mean.periapsis, mean.apoapsis):
        assert radius - EARTH_RADIUS_EQ == pytest.approx(200e3, abs=3e3)
    assert events["orbit"]["inclination_deg"] == pytest.approx(0.0, abs=0.1)


def test_a_classic_flight_is_bit_identical_run_to_run(tmp_path):
    """Flown twice (the second from the file's own attachments, ``replay --verify``): every
    message the same bits. 200 s at a 0.1 s step: through staging and above 86 km, where
    the density is held."""
    out = tmp_path / "classic.mcap"
    summary = fly(load(CLASSIC_ASCENT), out, step=0.1, duration=200.0)
    assert summary["bodies"]["falcon9-block5"]["final"]["altitude_m"] > 86e3
    verdict = verify(out, trust=True)
    assert verdict.identical, verdict
