"""RocketPy's ``Rocket`` of one of our single-stage finned vehicle files (RocketPy is a peer
library used only in tests).

The same rocket as :func:`rocketsim.vehicle.build.build` makes of the file: the rocket
without its motor as one body of our mass model's mass, centre of mass and inertia (the
inputs), the solid motor's case as its dry mass (a thin shell's inertia) at its centre and
its grains (the file's BATES segments burning on their cores only, or one segment of the
motor's size: our default uniform cylinder, whose centre stays at the motor's centre too),
the nozzle at the motor's aft end (its radius and throat's 0.33 and 0.143 of the motor's
diameter, the 75 mm 4895L1395's in RocketPy's Notre Dame set-up); the nose (a tangent ogive or a cone) with its tip at the
top of the stack, the fin sets and the boattail at the file's stations. Stations are
RocketPy's ``tail_to_nose`` coordinates from the vehicle's base, ours.
"""

from __future__ import annotations

import copy
import math
from pathlib import Path

from rocketsim.vehicle.build import build
from rocketsim.vehicle.mass_properties import shell

NOSE_KINDS = {"ogive": "tangent", "cone": "conical"}


def rocketpy_rocket(spec, drag, parachutes: bool = False):
    """``(Rocket, SolidMotor)`` of ``spec`` (a validated VehicleSpec, one stage, one solid
    motor, aerodynamics); ``drag``: its drag curve (a coefficient or (Mach, C_D) pairs),
    power on and off; ``parachutes``: add the stage's, each at its lag (RocketPy has no
    inflation time: our lag plus half the inflation, the centroid of our linear growth)."""
    from rocketpy import Rocket, SolidMotor
    (stage,) = spec.stages
    (motor_spec,) = stage.motors
    bare = copy.deepcopy(spec)
    bare.stages[0].motors.clear()
    dry_mass, dry_cm, ixx, iyy, _ = build(bare).mass_properties([])
    case = motor_spec.case_mass
    case_ixx, case_iyy = shell(case, 0.5 * motor_spec.diameter, motor_spec.length)
    grain = motor_spec.grain
    if grain is None:           # one segment of the motor's size, a vanishing core
        count, outer, core, height, gap = 1, 0.5 * motor_spec.diameter, 1e-4, motor_spec.length, 0.0
    else:
        count, outer, core = grain.count, 0.5 * grain.outer_diameter, 0.5 * grain.core_diameter
        height, gap = grain.length, grain.separation
    density = motor_spec.propellant_mass / (count * math.pi * (outer ** 2 - core ** 2) * height)
    source = motor_spec.file if motor_spec.file is not None else [list(p) for p in motor_spec.thrust]
    motor = SolidMotor(
        thrust_source=str(Path(source)) if isinstance(source, str) else source, dry_mass=case,
        dry_inertia=(case_iyy, case_iyy, case_ixx), nozzle_radius=0.33 * motor_spec.diameter,
        throat_radius=0.143 * motor_spec.diameter, grain_number=count, grain_density=density,
        grain_outer_radius=outer, grain_initial_inner_radius=core, grain_initial_height=height,
        grain_separation=gap, grains_center_of_mass_position=0.5 * motor_spec.length,
        center_of_dry_mass_position=0.5 * motor_spec.length, nozzle_position=0.0,
        interpolation_method="linear", coordinate_system_orientation="nozzle_to_combustion_chamber",
        only_radial_burn=True)
    aero = spec.aero
    largest = max([stage.diameter] + [p.diameter for p in (spec.payload, spec.fairing) if p is not None])
    rocket = Rocket(radius=0.5 * largest, mass=dry_mass, inertia=(iyy, iyy, ixx), power_off_drag=drag,
                    power_on_drag=drag, center_of_mass_without_motor=dry_cm,
                    coordinate_system_orientation="tail_to_nose")
    rocket.add_motor(motor, position=motor_spec.position)
    rocket.add_nose(length=aero.nose.length, kind=NOSE_KINDS[aero.nose.shape], position=build(spec).length)
    for fins in aero.fins:
        rocket.add_trapezoidal_fins(n=fins.count, root_chord=fins.root_chord, tip_chord=fins.tip_chord,
                                    span=fins.span, position=fins.position, sweep_length=fins.sweep)
    if aero.boattail is not None:
        rocket.add_tail(top_radius=0.5 * stage.diameter, bottom_radius=0.5 * aero.boattail.diameter,
                        length=aero.boattail.length, position=aero.boattail.length)
    if parachutes:
        for chute in stage.parachutes:
            trigger = "apogee" if chute.deploy == "apogee" else chute.deploy.height
            rocket.add_parachute(chute.name, cd_s=chute.cd_s, trigger=trigger, sampling_rate=100,
                                 lag=chute.lag + 0.5 * chute.inflation)
    return rocket, motor
