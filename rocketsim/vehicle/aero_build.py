"""A vehicle's ``aero:`` section becomes flat arrays, once, for the compiled derivative.

:func:`build_aero` is called by :func:`rocketsim.vehicle.build.build` for the
stages it builds; the result travels in ``VehicleArrays.aero``
(:class:`AeroArrays`). Parts of stages that are not built (a separated
booster's grid fins, seen from the upper stack) are left out. A vehicle
without an ``aero:`` section gets arrays with ``ref[A_ON] = 0`` and no parts:
the derivative then skips aerodynamics and contact. With ``aerodynamics: false``
(a spacecraft that only flies in vacuum) the arrays are those too, plus the
section's RCS thrusters.

The body's outline is the stack of stage cylinders, then the fairing (or the
payload) on top; the top ``nose.length`` of it tapers to the tip as a cone or
a tangent ogive, and a ``boattail`` narrows the bottom of the lowest stage to
its base as a cone frustum. The crossflow segments divide the whole length
equally, each with the diameter at its middle.
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


def outline(stages, top_parts, nose_length: float, nose_shape: str, boattail=None):
    """``diameter(x)`` (m) of the body at station ``x`` (m), its length, the station of the
    nose's base and the nose's base diameter.

    ``stages``: (base, length, diameter) of each stage bottom to top;
    ``top_parts``: (length, diameter) of what sits on the top stage; ``boattail``:
    (length, diameter at the base) of a cone frustum narrowing the lowest stage to its
    base, or None.
    """
    pieces = list(stages)
    top = pieces[-1][0] + pieces[-1][1]
    for length, diameter in top_parts:
        pieces.append((top, length, diameter))
    total = max(b + l for b, l, _ in pieces)
    nose_base = total - nose_length

    def cylinder(x):
        for base, length, diameter in reversed(pieces):
            if base <= x <= base + length + 1e-12:
                return diameter
        return pieces[0][2]

    base_d = cylinder(max(nose_base - 1e-9, 0.0))

    def diameter(x):
        if boattail is not None and x < pieces[0][0] + boattail[0]:
            length, aft = boattail
            return aft + (pieces[0][2] - aft) * max(0.0, x - pieces[0][0]) / length
        if nose_length <= 0.0 or x < nose_base:
            return cylinder(x)
        s = (total - x) / nose_length          # 1 at the nose's base, 0 at the tip
        if nose_shape == "cone":
            return base_d * s
        if nose_shape == "ogive":
            # tangent ogive of radius R, base radius r, length L: rho = R cos(.) ...
            r = 0.5 * base_d
            big = (r * r + nose_length ** 2) / (2 * r)
            xi = nose_length * s                # distance from the tip
            return 2.0 * (math.sqrt(big * big - (nose_length - xi) ** 2) + r - big)
        return base_d
    return diameter, total, nose_base, base_d


def transition_centre_of_pressure(diameter, a: float, b: float) -> float:
    """Station (m) of the slender-body lift of the body between stations ``a < b`` (m),
    where its cross-section goes from ``S(a)`` to ``S(b)``: the mean station weighted by
    ``dS/dx``, ``(b S(b) - a S(a) - V) / (S(b) - S(a))`` (``V`` the volume between, by
    parts). A nose (``S(tip) = 0``): ``tip - (L - V / S_base)``; a cone frustum: Barrowman's
    ``L/3 (1 + (1 - d_1/d_2) / (1 - (d_1/d_2)^2))`` from the end of diameter ``d_1``."""
    n = 400
    xs = a + (np.arange(n) + 0.5) * (b - a) / n
    volume = sum(math.pi * diameter(x) ** 2 / 4 for x in xs) * (b - a) / n
    area_a, area_b = (math.pi * diameter(x) ** 2 / 4 for x in (a, b))
    return (b * area_b - a * area_a - volume) / (area_b - area_a)


def barrowman(fin, body_d: float) -> tuple[float, float]:
    """``(C_N_alpha per rad on the body's cross-section, centre of pressure aft of the
    root's leading edge, m)`` of a fin set: J. S. Barrowman, "The practical calculation of
    the aerodynamic characteristics of slender finned vehicles", NASA/Catholic Univ.
    thesis (1967), eqs. for fins with body interference ``1 + r / (s + r)``."""
    cr, ct, s, xt = fin.root_chord, fin.tip_chord, fin.span, fin.sweep
    mid = math.hypot(s, xt + 0.5 * ct - 0.5 * cr)
    r = 0.5 * body_d
    cna = (1.0 + r / (s + r)) * 4.0 * fin.count * (s / body_d) ** 2 / (
        1.0 + math.sqrt(1.0 + (2.0 * mid / (cr + ct)) ** 2))
    xf = xt / 3.0 * (cr + 2.0 * ct) / (cr + ct) + (cr + ct - cr * ct / (cr + ct)) / 6.0
    return cna, xf


def build_aero(spec, chosen, stage_base, top: bool, with_fairing: bool, tank_names, has_wind: bool) -> AeroArrays:
    """The :class:`AeroArrays` of stages ``chosen`` (their specs, bottom to top) based at
    ``stage_base`` (m); ``top``: the top stage is among them (payload and fairing too)."""
    aero = getattr(spec, "aero", None)
    if aero is None:
        return no_aero()
    names = [st.name for st in chosen]
    base_of = dict(zip(names, stage_base))
    top_parts = []
    if top and with_fairing:
        top_parts.append((spec.fairing.length, spec.fairing.diameter))
    elif top and spec.payload is not None:
        top_parts.append((spec.payload.length, spec.payload.diameter))
    stages = [(b, st.length, st.diameter) for b, st in zip(stage_base, chosen)]
    nose_len = aero.nose.length if top else 0.0
    shape = aero.nose.shape if top else "blunt"
    boattail = aero.boattail
    if boattail is not None and boattail.stage != chosen[0].name:      # it left with its stage
        boattail = None
    diameter, total, nose_base, base_d = outline(
        stages, top_parts, nose_len, shape, None if boattail is None else (boattail.length, boattail.diameter))
    d_max = max(max(d for _, _, d in stages), max((d for _, d in top_parts), default=0.0))
    area = math.pi * d_max ** 2 / 4

    ref = np.zeros(N_REF)
    ref[A_ON] = 1.0
    ref[A_AREA] = area
    ref[A_ETA] = float(np.interp(total / d_max, EFFICIENCY_FINENESS, EFFICIENCY_SUBSONIC))
    if nose_len > 0.0 and shape != "blunt":
        ref[A_NOSE_X] = transition_centre_of_pressure(diameter, total - nose_len, total)
        ref[A_NOSE_AREA] = math.pi * base_d ** 2 / 4
    if boattail is not None:
        ref[A_TAIL_X] = transition_centre_of_pressure(diameter, 0.0, boattail.length)
        ref[A_TAIL_AREA] = math.pi * (boattail.diameter ** 2 - chosen[0].diameter ** 2) / 4
    ref[A_BASE_AREA] = math.pi * diameter(0.0) ** 2 / 4
    ref[A_WIND] = 1.0 if has_wind else 0.0

    n = aero.segments
    dx = total / n
    seg = np.array([((i + 0.5) * dx, dx, diameter((i + 0.5) * dx)) for i in range(n)])

    fins = []
    for k, fin, base in _built(spec, aero.fins, base_of, "fins"):
        d = diameter(base + fin.position)
        cna, xf = barrowman(fin, d)
        fins.append((base + fin.position - xf, cna * math.pi * d ** 2 / 4))

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
