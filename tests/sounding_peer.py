"""The finned sounding rocket flown here and in RocketPy (a peer library used only in tests).

Used by tests/peers/test_rocketpy_peer.py (the apogees compared) and
tests/benchmarks/test_bench_rocketpy.py (the two flights timed). The rocket:
6 m x 0.3 m, 80 kg of structure, a 30 kg payload, 120 kg of propellant in one
tank, one 9 kN engine (Isp 230 s, 0.3 s dead time, 0.5 s linear spool-up),
an ogive nose and four trapezoidal fins, our nose-first axial-force table as
its drag curve against Mach; standing on its base on a pad at a desert range
(Spaceport America's latitude and longitude), vertical, no wind, the standard
atmosphere. RocketPy flies the same masses, thrust curve and drag curve off a
5 m rail (:func:`rocketpy_flight`; what is matched and what is not is said in
tests/peers/test_rocketpy_peer.py).
"""

import math

import numpy as np

from rocketsim.constants import EARTH_OMEGA, G0
from rocketsim.dynamics.rk4 import step
from rocketsim.frames.geodetic import ecef_to_geodetic, enu_basis, geodetic_to_ecef
from rocketsim.frames.quaternion import quat_from_matrix
from rocketsim.vehicle.aero import NOSE_FIRST_CA, NOSE_FIRST_MACH
from rocketsim.vehicle.build import build
from rocketsim.vehicle.engines import ignite
from tests.aero_vehicles import corotating, earth_params, spec

LAT, LON = math.radians(32.99), math.radians(-106.97)      # a desert range (Spaceport America)
THRUST, ISP, PROPELLANT = 9000.0, 230.0, 120.0             # N, s, kg
DEAD, SPOOL = 0.3, 0.5                                     # s
DRAG = [(m, c) for m, c in zip(NOSE_FIRST_MACH, NOSE_FIRST_CA)]
ROCKET = {
    "name": "peer sounding rocket",
    "stages": [{"name": "rocket", "length": "6 m", "diameter": "0.3 m", "structure_mass": "80 kg",
                "tanks": [{"name": "T", "propellant": "X", "density": 1000.0, "radius": "0.14 m",
                           "length": "3 m", "position": "0.5 m", "propellant_mass": f"{PROPELLANT} kg"}],
                "engines": [{"name": "motor", "thrust_vacuum": f"{THRUST} N", "isp_vacuum": f"{ISP} s",
                             "exit_area": "0 m2", "ignition_delay": f"{DEAD} s", "spool_up": f"{SPOOL} s"}],
                "point_masses": [{"name": "payload", "mass": "30 kg", "position": "5.2 m"}]}],
    "aero": {"nose": {"length": "1 m", "shape": "ogive"}, "axial_nose_first": DRAG,
             "fins": [{"stage": "rocket", "count": 4, "position": "0.5 m", "root_chord": "0.4 m",
                       "tip_chord": "0.2 m", "span": "0.3 m", "sweep": "0.2 m"}]},
}


def on_the_pad():
    """``(model, y, p)``: the rocket built from :data:`ROCKET`, its state standing on its
    base on the pad (the base's contact springs carry it until liftoff) with the engine
    lit at T+0, and the parameters of the bare RK4 step."""
    model = build(spec(ROCKET))
    a = model.arrays
    y0 = model.state([0, 0, 0], [0, 0, 0])
    x_cm = model.mass_properties(y0)[1]
    enu = enu_basis(LAT, LON)
    up = enu[2]
    axes = np.column_stack((up, enu[0], np.cross(up, enu[0])))
    r = np.array(geodetic_to_ecef(LAT, LON, x_cm))
    y = model.state(r, corotating(r), q=quat_from_matrix(axes), w=axes.T @ np.array([0, 0, EARTH_OMEGA]))
    ignite(y, a.eng, a.cmd, a.stage, 0, a.first_clock)
    return model, y, earth_params()


def our_apogee():
    """``(apogee m above the pad, model)``: the rocket flown by the bare RK4 step (20 ms)
    from :func:`on_the_pad` to its highest step."""
    model, y, p = on_the_pad()
    start = ecef_to_geodetic(y[0:3])[2]
    best = start
    for k in range(20_000):
        y = step(y, 0.02 * k, 0.02, p, model.arrays)
        h = float(ecef_to_geodetic(y[0:3])[2])     # ECI = ECEF turned by omega t: height is the same
        if h < best and k > 100:
            break
        best = max(best, h)
    return best - start, model


def rocketpy_flight(model, rtol: float = 1e-8):
    """RocketPy's ``Flight`` of the rocket (``model``: ours, built from :data:`ROCKET`, for
    its masses) to apogee (``terminate_on_apogee``, ``rtol``: 1e-8 for the apogee's
    comparison, RocketPy's default 1e-6 for its speed; its other settings the defaults).
    Its apogee above the pad is ``flight.apogee - flight.z(0.0)``."""
    from rocketpy import Environment, Flight, GenericMotor, Rocket
    mdot = THRUST / (G0 * ISP)
    usable = 0.99 * PROPELLANT
    full = (usable - mdot * SPOOL / 2) / mdot
    end = DEAD + SPOOL + full
    # RocketPy's clock starts when the thrust first lifts the weight (before that our
    # rocket stands on the pad; RocketPy's rail does not start from zero thrust): the
    # spool ramp from there on, and the propellant left then
    weight = (model.mass_properties(np.concatenate((np.zeros(13), [PROPELLANT], np.zeros(1))))[0]
              * 9.7955)                                        # Somigliana at 33 deg
    t_lift = SPOOL * weight / THRUST
    burnt = mdot * t_lift ** 2 / (2 * SPOOL)
    weight = (model.mass_properties(np.concatenate((np.zeros(13), [PROPELLANT - burnt], np.zeros(1))))[0]
              * 9.7955)
    t_lift = SPOOL * weight / THRUST * 1.001
    burnt = mdot * t_lift ** 2 / (2 * SPOOL)
    curve = [(0.0, THRUST * t_lift / SPOOL), (SPOOL - t_lift, THRUST), (end - DEAD - t_lift, THRUST)]
    usable -= burnt
    end -= DEAD + t_lift
    motor = GenericMotor(thrust_source=curve, burn_time=(0.0, end), chamber_radius=0.14, chamber_height=3.0,
                         chamber_position=2.0, propellant_initial_mass=usable, nozzle_radius=0.05,
                         dry_mass=0.0, center_of_dry_mass_position=0.0, nozzle_position=0.0,
                         coordinate_system_orientation="nozzle_to_combustion_chamber")
    # everything but the usable propellant: structure, payload, tank's unusable 1 %
    dry = model.mass_properties(np.concatenate((np.zeros(13), [0.01 * PROPELLANT], np.zeros(1))))
    # (RocketPy's chamber: a cylinder of the tank's size; its inertia differs from our
    # settled column's, which matters little in a vertical flight)
    dry_mass, dry_cm, ixx, iyy = dry[0], dry[1], dry[2], dry[3]
    rocket = Rocket(radius=0.15, mass=dry_mass, inertia=(iyy, iyy, ixx),
                    power_off_drag=DRAG, power_on_drag=DRAG, center_of_mass_without_motor=dry_cm,
                    coordinate_system_orientation="tail_to_nose")
    rocket.add_motor(motor, position=0.0)
    rocket.add_nose(length=1.0, kind="tangent", position=6.0)
    rocket.add_trapezoidal_fins(n=4, root_chord=0.4, tip_chord=0.2, span=0.3, position=0.5, sweep_length=0.2)
    env = Environment(latitude=math.degrees(LAT), longitude=math.degrees(LON), elevation=0.0)
    env.set_atmospheric_model(type="standard_atmosphere")
    return Flight(rocket=rocket, environment=env, rail_length=5.0, inclination=90.0, heading=0.0,
                  terminate_on_apogee=True, rtol=rtol)


def light_the_engine(fc):
    """The scenario's program: the engine lit at T+0, nothing more."""
    fc.ignite()


def scenario(duration: float) -> dict:
    """The rocket as a scenario (a mapping for :func:`rocketsim.scenario.load.load`): standing
    upright on its base on the pad at :data:`LAT`, :data:`LON` (on the ellipsoid), its
    engine lit by the program at T+0, flown for ``duration`` s in 20 ms steps with
    10 Hz telemetry."""
    return {"name": "sounding-peer", "vehicle": ROCKET,
            "site": {"name": "pad", "latitude": f"{math.degrees(LAT)} deg",
                     "longitude": f"{math.degrees(LON)} deg", "height": "0 m"},
            "mission": {"epoch": "2026-06-13T15:00:00Z", "duration": f"{duration} s", "start": {"site": {}}},
            "program": light_the_engine, "step": "0.02 s", "telemetry": {"rate": "10 Hz"}}
