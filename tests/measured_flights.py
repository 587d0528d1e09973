"""Measured flights: the flight computers' logs, and RocketPy flying the same rockets.

The logs and weather are RocketPy's (scenarios/measured/README.md); the
rockets' figures and RocketPy's set-up are those of RocketPy's acceptance
tests (tests/acceptance/test_ndrt_2020_rocket.py and test_bella_lui_rocket.py
in that repository, MIT licence), flown here with RocketPy's default
settings (its weather dictionary named ``ECMWF_v0``, the one RocketPy falls
back to, with a warning, when its tests' ``ECMWF`` does not match these
files' old ERA5 names). Used by tests/peers/test_measured_flights.py and by
tests/fixtures/measured/plot_comparison.py (the table and plot of docs/validation.md).

Every figure is taken the same way from a log and from a simulation:

- apogee: the highest altitude above the pad (m AGL) and its time (s);
- peak vertical speed: the largest upward speed (m/s); a barometric log's
  altitude is differentiated with a Savitzky-Golay filter (cubic, 1.05 s
  window) first, as RocketPy's test does;
- descent rate: the slope (m/s, positive down) of a straight line fitted to
  the altitude while it falls through the window :data:`DESCENT` (under the
  main parachute for Notre Dame, under the only one for Bella Lui).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

DATA = Path(__file__).parent / "fixtures" / "measured"
SCENARIOS = Path(__file__).parents[1] / "scenarios" / "measured"
WEATHER = SCENARIOS / "weather"
MOTORS = Path(__file__).parents[1] / "motors"            # the RASP .eng files
FEET = 0.3048                                    # m
# (lowest, highest) altitude AGL of the descent-rate window, m: under the open main for
# Notre Dame (its log shows the main opening at about 110 m, 65 s, below the 550 ft
# trigger's 168 m), under the one parachute for Bella Lui
DESCENT = {"ndrt-2020": (10.0, 80.0), "bella-lui": (100.0, 300.0)}


@dataclass(frozen=True)
class Figures:
    """One flight's altitude trace (s, m AGL) and its figures (SI, see the module)."""

    time: np.ndarray
    altitude: np.ndarray
    apogee: float
    apogee_time: float
    peak_vertical_speed: float
    descent_rate: float
    apogee_drift: float = float("nan")     # m, horizontal distance from the pad at apogee


def figures(name: str, time, altitude, vertical_speed=None) -> Figures:
    """The figures of a trace; the vertical speed, when not given, from the altitude."""
    time, altitude = np.asarray(time, dtype=float), np.asarray(altitude, dtype=float)
    if vertical_speed is None:
        from scipy.signal import savgol_filter
        dt = float(np.median(np.diff(time)))
        window = int(round(1.05 / dt)) | 1
        vertical_speed = savgol_filter(altitude, window, 3, deriv=1, delta=dt)
    top = int(np.argmax(altitude))
    low, high = DESCENT[name]
    falling = np.arange(len(time)) > top
    inside = falling & (altitude >= low) & (altitude <= high)
    slope = np.polyfit(time[inside], altitude[inside], 1)[0]
    return Figures(time, altitude, float(altitude[top]), float(time[top]),
                   float(np.max(vertical_speed)), float(-slope))


def measured(name: str) -> Figures:
    """The flight computer's log: Notre Dame's Raven altimeter (20 Hz, feet AGL, barometric),
    Bella Lui's filtered altitude and vertical speed (m), to touchdown."""
    if name == "ndrt-2020":
        import pandas as pd
        log = pd.read_csv(DATA / "ndrt_2020_flight_data.csv")
        t = log[" Time (s)"].to_numpy(float)
        h = log[" Altitude (Ft-AGL)"].to_numpy(float) * FEET
        keep = np.concatenate(([True], np.diff(t) > 0))    # the log repeats its last sample
        return figures(name, t[keep], h[keep])
    log = np.loadtxt(DATA / "bella_lui_flight_data_filtered.csv", skiprows=1, delimiter=",",
                     usecols=(2, 3, 4))
    return figures(name, log[:, 0], log[:, 1], log[:, 2])


def rocketsim_figures(name: str) -> Figures:
    """rocketsim's flight of scenarios/measured/<name>.yaml (in memory) as :class:`Figures`."""
    import rocketsim
    return figures_of_run(name, rocketsim.fly(SCENARIOS / f"{name}.yaml"))


def figures_of_run(name: str, run) -> Figures:
    """A rocketsim run's :class:`Figures`: the altitude above its first sample's (an altimeter
    zeroed on the pad), the vertical speed its central differences at the 50 Hz samples."""
    from dataclasses import replace
    from rocketsim.frames.geodetic import enu_basis, geodetic_to_ecef
    table = next(iter(run.bodies.values())).table()
    t = table.index.to_numpy(float)
    height = table["altitude_m"].to_numpy(float)
    h = height - height[0]
    found = figures(name, t, h, np.gradient(h, t))
    lat = np.radians(table["latitude_deg"].to_numpy(float))
    lon = np.radians(table["longitude_deg"].to_numpy(float))
    top = int(np.argmax(h))
    moved = geodetic_to_ecef(lat[top], lon[top], height[top]) - geodetic_to_ecef(lat[0], lon[0],
                                                                             height[0])
    east, north, _ = enu_basis(lat[0], lon[0]) @ moved
    return replace(found, apogee_drift=float(np.hypot(east, north)))


# --- RocketPy, set up as its acceptance tests -----------------------------------------

NDRT = {"latitude": 41.775447, "longitude": -86.572467, "date": (2020, 2, 23, 16),
        "elevation": 206.0, "weather": "ndrt_2020_weather_data_ERA5.nc"}
BELLA = {"latitude": 47.213476, "longitude": 9.003336, "date": (2020, 2, 22, 13),
         "elevation": 407.0, "weather": "bella_lui_weather_data_ERA5.nc"}


def rocketpy_flight(name: str, motors: Path, weather: Path | None = None,
                    to_apogee: bool = False, physical: bool = False):
    """RocketPy's Flight of ``name`` and its Environment (``motors``: the folder of the RASP
    .eng files; ``weather``: an ERA5 file in place of the day's; ``to_apogee``: stop there,
    RocketPy's ``terminate_on_apogee``).

    ``physical`` (Notre Dame): the rocket as vehicles/ndrt-2020.yaml builds it
    (tests/rocketpy_rockets.py: our masses, centre of mass and inertia, the motor in the
    tail), in place of two figures of the acceptance test no rocket has: the motor hung
    1.2 m below the tail (its nozzle at -1.255 m, where the test adds the motor's own
    -1.255 m nozzle position once more) and a pitch inertia of 83.351 kg m^2; the rail
    buttons the acceptance test's."""
    from rocketpy import Environment, Flight, Function, Rocket, SolidMotor
    site = NDRT if name == "ndrt-2020" else BELLA
    env = Environment(gravity=9.81, latitude=site["latitude"], longitude=site["longitude"],
                      date=site["date"], elevation=site["elevation"])
    env.set_atmospheric_model(type="Reanalysis", file=str(weather or WEATHER / site["weather"]),
                              dictionary="ECMWF_v0")
    env.max_expected_height = 2000

    def drogue(p, h, y):          # at apogee (vertical speed below zero)
        return y[5] < 0

    if name == "ndrt-2020" and physical:
        from tests.aero_vehicles import shipped
        from tests.rocketpy_rockets import rocketpy_rocket
        rocket, _ = rocketpy_rocket(shipped("ndrt-2020.yaml"), 0.44, parachutes=True)
        base = 1.321656                     # the acceptance test's stations are from the CM
        rocket.set_rail_buttons(base + 0.2, base - 0.5, 45)
        return Flight(rocket=rocket, environment=env, rail_length=3.353, inclination=90,
                      heading=181, terminate_on_apogee=to_apogee), env
    if name == "ndrt-2020":
        motor = SolidMotor(
            thrust_source=str(motors / "Cesaroni_4895L1395-P.eng"), burn_time=3.45,
            dry_mass=1, dry_inertia=(0, 0, 0), center_of_dry_mass_position=0,
            grains_center_of_mass_position=-0.85704, grain_number=5, grain_separation=0.003,
            grain_density=1519.708, grain_outer_radius=0.033, grain_initial_inner_radius=0.015,
            grain_initial_height=0.120, nozzle_radius=49.5 / 2000, throat_radius=21.5 / 2000,
            interpolation_method="linear", nozzle_position=-1.255)
        rocket = Rocket(radius=203 / 2000, mass=23.321 - 2.475 - 1,
                        inertia=(83.351, 83.351, 0.15982), power_off_drag=0.44,
                        power_on_drag=0.44, center_of_mass_without_motor=0)
        rocket.set_rail_buttons(0.2, -0.5, 45)
        rocket.add_motor(motor, -1.255)
        rocket.add_nose(length=0.610, kind="tangent", position=0.71971 + 0.610)
        rocket.add_trapezoidal_fins(3, span=0.165, root_chord=0.152, tip_chord=0.0762,
                                    position=-1.04956)
        rocket.add_tail(top_radius=203 / 2000, bottom_radius=155 / 2000, length=0.127,
                        position=-1.194656)

        def main(p, h, y):        # 550 ft AGL, falling
            return y[5] < 0 and h < 167.64

        inch = 0.0254
        rocket.add_parachute("Drogue", cd_s=1.5 * np.pi * (24 * inch) ** 2 / 4, trigger=drogue,
                             sampling_rate=105, lag=1, noise=(0, 8.3, 0.5))
        rocket.add_parachute("Main", cd_s=2.2 * np.pi * (120 * inch) ** 2 / 4, trigger=main,
                             sampling_rate=105, lag=1, noise=(0, 8.3, 0.5))
        return Flight(rocket=rocket, environment=env, rail_length=3.353, inclination=90,
                      heading=181, terminate_on_apogee=to_apogee), env
    motor = SolidMotor(
        thrust_source=str(motors / "AeroTech_K828FJ.eng"), burn_time=2.43, dry_mass=1,
        dry_inertia=(0, 0, 0), center_of_dry_mass_position=0, grains_center_of_mass_position=-1,
        grain_number=3, grain_separation=0.003, grain_density=782.4,
        grain_outer_radius=85.598 / 2000, grain_initial_inner_radius=33.147 / 1000,
        grain_initial_height=152.4 / 1000, nozzle_radius=44.45 / 1000,
        throat_radius=21.4376 / 1000, interpolation_method="linear", nozzle_position=-1.1356)
    rocket = Rocket(radius=156 / 2000, mass=18.227 - 1, inertia=(0.78267, 0.78267, 0.064244),
                    power_off_drag=0.43, power_on_drag=0.43, center_of_mass_without_motor=0)
    rocket.set_rail_buttons(0.1, -0.5)
    rocket.add_motor(motor, -1.1356)
    rocket.add_nose(length=0.242, kind="tangent", position=1.3 + 0.242)
    rocket.add_trapezoidal_fins(3, span=0.200, root_chord=0.280, tip_chord=0.125, position=-0.75)
    rocket.add_tail(top_radius=156 / 2000, bottom_radius=135 / 2000, length=0.050,
                    position=-1.0856)
    rocket.add_parachute("Drogue", cd_s=np.pi / 4, trigger=drogue, sampling_rate=105, lag=1,
                         noise=(0, 8.3, 0.5))
    drag = Function(BELLA_DRAG, "Mach Number", "Drag Coefficient", "linear", "constant")
    seven = ["alpha", "beta", "mach", "reynolds", "pitch_rate", "yaw_rate", "roll_rate"]
    for attribute in ("power_off_drag_7d", "power_on_drag_7d"):
        setattr(rocket, attribute, Function(
            lambda alpha, beta, mach, reynolds, pitch, yaw, roll: drag.get_value_opt(mach),
            seven, ["Drag Coefficient"], interpolation="linear", extrapolation="constant"))
    return Flight(rocket=rocket, environment=env, rail_length=4.2, inclination=89,
                  heading=45, terminate_on_apogee=to_apogee), env


# Bella Lui's drag coefficient against Mach (RocketPy's acceptance test)
BELLA_DRAG = [(0.01, 0.51), (0.02, 0.46), (0.04, 0.43), (0.28, 0.43), (0.29, 0.44),
              (0.45, 0.44), (0.49, 0.46)]


def rocketpy_figures(name: str, motors: Path, weather: Path | None = None) -> Figures:
    """RocketPy's flight of ``name`` as :class:`Figures` (its solution's own samples)."""
    flight, env = rocketpy_flight(name, motors, weather)
    solution = np.asarray(flight.solution)
    t, z, vz = solution[:, 0], solution[:, 3] - env.elevation, solution[:, 6]
    return figures(name, t, z, vz)
