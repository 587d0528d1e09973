"""A scenario's changes to its vehicle file: fly only the lower stages, reload tanks,
stack a spacecraft on top.

``stages: [booster]`` in a scenario flies only the named stages of the vehicle
file (the lowest ones, bottom first, as a first-stage hop does): the stages
above, the payload and the fairing are left off, with the aerodynamic parts
(fins, grid fins, legs, thrusters) of the stages that remain; the stack's nose
then tops the highest stage kept. ``propellant: {booster/LOX: 28 t}`` sets a
tank's load (kg) in place of the vehicle file's (a hop flies light enough to
hover). ``spacecraft: ../vehicles/lunar-orbiter.yaml`` stacks a staged
spacecraft's stages above the launcher's (its payload in place of the
launcher's, under the launcher's fairing): after the launcher's last stage
separates, the program flies on with the spacecraft. All are pure functions
of the vehicle spec.
"""

from __future__ import annotations


def keep_stages(spec, names: list[str]):
    """``spec`` (a staged VehicleSpec) with only its lowest stages, named ``names`` in
    order from the bottom; no payload or fairing. ValueError if ``names`` is not the
    vehicle's lowest stages."""
    have = [s.name for s in spec.stages]
    if not names or have[:len(names)] != list(names):
        raise ValueError(f"'stages' must name the vehicle's lowest stages, bottom first "
                         f"(the vehicle has {', '.join(have)}), got {', '.join(names) or 'none'}")
    kept = set(names)
    aero = spec.aero
    if aero is not None:
        aero = aero.model_copy(update={
            part: [item for item in getattr(aero, part) if item.stage in kept]
            for part in ("fins", "grid_fins", "legs", "rcs")})
    return spec.model_copy(update={"stages": spec.stages[:len(names)], "payload": None,
                                   "fairing": None, "aero": aero})


def reload_tanks(spec, loads: dict[str, float]):
    """``spec`` with the propellant of the tanks named ``"stage/tank"`` in ``loads`` (kg)
    set in place of the file's. ValueError for a tank the vehicle does not have or a
    load that does not fit."""
    stages = []
    left = dict(loads)
    for stage in spec.stages:
        tanks = []
        for tank in stage.tanks:
            key = f"{stage.name}/{tank.name}"
            if key in left:
                load = left.pop(key)
                if load > tank.capacity * (1 + 1e-9):
                    raise ValueError(f"propellant {key}: {load:g} kg does not fit "
                                     f"(the tank holds {tank.capacity:g} kg)")
                tank = tank.model_copy(update={"propellant_mass": load})
            tanks.append(tank)
        stages.append(stage.model_copy(update={"tanks": tanks}))
    if left:
        names = [f"{s.name}/{t.name}" for s in spec.stages for t in s.tanks]
        raise ValueError(f"propellant: no tank {', '.join(left)} (the vehicle has {', '.join(names)})")
    return spec.model_copy(update={"stages": stages})


def stack_spacecraft(launcher, spacecraft):
    """``launcher`` (a staged VehicleSpec) with the stages of ``spacecraft`` (a staged
    VehicleSpec) stacked above its own, bottom to top, the spacecraft's payload in
    place of the launcher's and the launcher's fairing over it; the spacecraft's
    thrusters join the launcher's aerodynamic parts (the launcher's nose and body
    aerodynamics stay). ValueError if a stage name appears in both."""
    if spacecraft.stages is None:
        raise ValueError(f"spacecraft {spacecraft.name!r} is a rigid body: give a staged vehicle "
                         "(or fly it as the 'payload')")
    clash = {s.name for s in launcher.stages} & {s.name for s in spacecraft.stages}
    if clash:
        raise ValueError(f"stage names in both the vehicle and the spacecraft: {', '.join(sorted(clash))}")
    aero = launcher.aero
    if aero is not None and spacecraft.aero is not None:
        aero = aero.model_copy(update={"rcs": list(aero.rcs) + list(spacecraft.aero.rcs)})
    return launcher.model_copy(update={
        "name": f"{launcher.name} + {spacecraft.name}",
        "stages": list(launcher.stages) + list(spacecraft.stages),
        "payload": spacecraft.payload, "aero": aero})
