"""A vehicle's ``aero:`` section becomes flat arrays, once, for the compiled derivative.

:func:`build_aero` is called by :func:`rocketsim.vehicle.build.build` for the
stages it builds; the result travels in ``VehicleArrays.aero``
(:class:`AeroArrays`). Parts of stages that are not built (a separated
booster's grid fins, seen from the upper stack) are left out. A vehicle
without an ``aero:`` section gets arrays with ``ref[A_ON] = 0`` and no parts:
the derivative then skips aerodynamics and contact. With ``aerodynamics: false``
(a spacecraft that only flies in vacuum) the arrays are those too, plus the
section's RCS thrusters.

The body's outline and its slender-body and fin lift are
:func:`rocketsim.vehicle.outline.body_shape`'s. The crossflow segments divide the
whole length equally, each with the diameter at its middle.
"""

from __future__ import annotations

import math
from collections import namedtuple

import numpy as np

from rocketsim.constants import FRICTION_REGULARISATION, G0
from rocketsim.layout import N_STATE
from rocketsim.errors import InputError
from rocketsim.vehicle.aero import (A_AREA, A_BASE_AREA, A_ETA, A_NOSE_AREA, A_NOSE_X, A_ON,
                                    A_REACH, A_TAIL_AREA, A_TAIL_X, A_WIND, EFFICIENCY_FINENESS,
                                    EFFICIENCY_SUBSONIC, NOSE_FIRST_CA, NOSE_FIRST_MACH, N_REF,
                                    TAIL_FIRST_CA, TAIL_FIRST_MACH)
from rocketsim.vehicle.contact import N_CONTACT
from rocketsim.vehicle.grid_fins import N_GRID, N_GRID_CMD
from rocketsim.vehicle.outline import body_shape
from rocketsim.vehicle.rcs import N_RCS

AeroArrays = namedtuple("AeroArrays", [
    "ref", "seg", "fin", "ca_nf", "ca_tf", "grid", "grid_cmd", "rcs", "rcs_cmd", "contact", "wind"])


def _table(rows, default_mach, default_ca) -> np.ndarray:
    if rows is None:
        return np.ascontiguousarray(np.column_stack((default_mach, default_ca)))
    return np.ascontiguousarray(np.array(rows, dtype=float).reshape(-1, 2))


def _empty(n_cols: int) -> np.ndarray:
    return np.zeros((0, n_cols))


def no_aero() -> AeroArrays:
    """Arrays of a vehicle without aerodynamics or contact."""
    return AeroArrays(np.zeros(N_REF), _empty(3), _empty(2), _table(None, NOSE_FIRST_MACH, NOSE_FIRST_CA),
                      _table(None, TAIL_FIRST_MACH, TAIL_FIRST_CA), _empty(N_GRID),
                      _empty(N_GRID_CMD), _empty(N_RCS), np.zeros(0), _empty(N_CONTACT), np.zeros(3))


def build_aero(spec, chosen, stage_base, top: bool, with_fairing: bool, tank_names, has_wind: bool) -> AeroArrays:
    """The :class:`AeroArrays` of stages ``chosen`` (their specs, bottom to top) based at
    ``stage_base`` (m); ``top``: the top stage is among them (payload and fairing too)."""
    aero = getattr(spec, "aero", None)
    if aero is None:
        return no_aero()
    names = [st.name for st in chosen]
    base_of = dict(zip(names, stage_base))
    shape = body_shape(spec, chosen, stage_base, top, with_fairing)
    diameter, total, nose_base, base_d = shape.diameter, shape.length, shape.nose_base, shape.nose_base_diameter
    area = math.pi * shape.reference_diameter ** 2 / 4

    ref = np.zeros(N_REF)
    ref[A_ON] = 1.0
    ref[A_AREA] = area
    ref[A_ETA] = float(np.interp(total / shape.reference_diameter, EFFICIENCY_FINENESS, EFFICIENCY_SUBSONIC))
    if shape.nose is not None:
        ref[A_NOSE_X], ref[A_NOSE_AREA] = shape.nose
    if shape.boattail is not None:
        ref[A_TAIL_X], ref[A_TAIL_AREA] = shape.boattail
    ref[A_BASE_AREA] = math.pi * diameter(0.0) ** 2 / 4
    ref[A_WIND] = 1.0 if has_wind else 0.0

    n = aero.segments
    dx = total / n
    seg = np.array([((i + 0.5) * dx, dx, diameter((i + 0.5) * dx)) for i in range(n)])
    fins = shape.fins

    grid = []
    for k, g, base in _built(spec, aero.grid_fins, base_of, "grid_fins"):
        for j in range(g.count):
            phi = 2 * math.pi * j / g.count
            grid.append((base + g.position, phi, g.radius, g.area, g.max_deflection, g.rate, g.stall,
                         math.cos(phi), math.sin(phi)))

    rcs = []
    for k, th, base in _built(spec, aero.rcs, base_of, "rcs"):
        key = f"{th.stage}/{th.tank}"
        if key not in tank_names:
            raise InputError(f"thruster {k + 1} draws from tank {th.tank!r}, which stage "
                             f"{th.stage!r} does not have", field=f"aero.rcs[{k}].tank")
        d = np.array(th.direction, dtype=float)
        d /= np.linalg.norm(d)
        rcs.append((base + th.position, th.y, th.z, *d, th.thrust, th.thrust / (G0 * th.isp),
                    N_STATE + tank_names.index(key)))

    contact = []
    for k, leg, base in _built(spec, aero.legs, base_of, "legs"):
        for j in range(leg.count):
            phi = 2 * math.pi * (j + 0.5) / leg.count
            contact.append((base + leg.position, leg.radius * math.cos(phi),
                            leg.radius * math.sin(phi), leg.stiffness, leg.damping, leg.friction,
                            leg.friction_speed))
    # the body: a ring at the base (engine bells, skirt), a ring below the nose and the tip
    dry = sum(st.dry_mass for st in chosen) + sum(
        part.mass for part, on in ((spec.payload, top), (spec.fairing, with_fairing)) if on and part is not None)
    kb, cb = aero.body_springs(dry)
    for x, r in ((0.0, 0.5 * diameter(0.0)), (nose_base, 0.5 * base_d)):
        for j in range(4):
            phi = 0.5 * math.pi * j
            contact.append((x, r * math.cos(phi), r * math.sin(phi), kb, cb, 0.6, FRICTION_REGULARISATION))
    contact.append((total, 0.0, 0.0, kb, cb, 0.6, FRICTION_REGULARISATION))
    contact = np.array(contact, dtype=float).reshape(-1, N_CONTACT)
    reach = max(math.sqrt(max(x * x, (x - total) ** 2) + y * y + z * z) for x, y, z in contact[:, :3])
    ref[A_REACH] = reach

    if not aero.aerodynamics:           # a vacuum spacecraft: its thrusters only
        return no_aero()._replace(rcs=np.array(rcs, dtype=float).reshape(-1, N_RCS),
                                  rcs_cmd=np.zeros(len(rcs)))
    return AeroArrays(
        ref, np.ascontiguousarray(seg),
        np.array(fins, dtype=float).reshape(-1, 2),
        _table(aero.axial_nose_first, NOSE_FIRST_MACH, NOSE_FIRST_CA),
        _table(aero.axial_tail_first, TAIL_FIRST_MACH, TAIL_FIRST_CA),
        np.array(grid, dtype=float).reshape(-1, N_GRID), np.zeros((len(grid), N_GRID_CMD)),
        np.array(rcs, dtype=float).reshape(-1, N_RCS), np.zeros(len(rcs)),
        np.ascontiguousarray(contact), np.zeros(3))


def _built(spec, parts, base_of, label):
    """``(index, part, base of its stage)`` for the parts on stages being built; a part
    naming no stage of the vehicle is an input error."""
    for k, part in enumerate(parts):
        if part.stage in base_of:
            yield k, part, base_of[part.stage]
        elif part.stage not in [st.name for st in spec.stages]:
            raise InputError(f"no stage is named {part.stage!r} (stages: "
                             f"{', '.join(st.name for st in spec.stages)})", field=f"aero.{label}[{k}].stage")
