"""The body of a staged vehicle as its aerodynamics see it: its outline and the lifts that
act at small angles of attack. Pure Python (no array library), for the compiled
aerodynamics' arrays (:mod:`rocketsim.vehicle.aero_build`) and the design review alike
(:mod:`rocketsim.vehicle.review`, which ``rocketsim validate`` reads without numpy).

The outline is the stack of the stages' cylinders, then the fairing (or the payload) on
top; the top ``nose.length`` of it tapers to the tip as a cone or a tangent ogive
(docs/physics.md#the-stack-and-its-nose), and a ``boattail`` narrows the bottom of the
lowest stage to its base as a cone frustum. Stations are metres above the base of the
lowest stage built.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable


@dataclass(frozen=True)
class BodyShape:
    """The outline and small-angle lifts of the stages built (see the module)."""

    diameter: Callable[[float], float]      # m, of the body at a station (m)
    length: float                           # m, base to tip
    nose_base: float                        # m, station of the nose's base
    nose_base_diameter: float               # m
    reference_diameter: float               # m, the largest
    nose: tuple[float, float] | None        # (station m, base area m^2) of its slender-body lift
    boattail: tuple[float, float] | None    # (station m, S_aft - S_fore m^2)
    fins: list[tuple[float, float]]         # (station m, C_N_alpha S m^2 per rad) of each set

    def lift_slopes(self) -> list[tuple[float, float]]:
        """``(station m, dC_N/dalpha S m^2 per rad)`` of every lift at zero angle of attack:
        the slender body's ``2 S`` (a nose's base area, a boattail's change of area) and
        the fins'."""
        found = []
        for part in (self.nose, self.boattail):
            if part is not None:
                found.append((part[0], 2.0 * part[1]))
        return found + list(self.fins)


def body_shape(spec, chosen, stage_base, top: bool, with_fairing: bool) -> BodyShape:
    """The :class:`BodyShape` of stages ``chosen`` (their specs, bottom to top) of ``spec``
    based at ``stage_base`` (m); ``top``: the top stage is among them (payload, and the
    fairing while ``with_fairing``, on it)."""
    aero = spec.aero
    top_parts = []
    if top and with_fairing:
        top_parts.append((spec.fairing.length, spec.fairing.diameter))
    elif top and spec.payload is not None:
        top_parts.append((spec.payload.length, spec.payload.diameter))
    stages = [(b, st.length, st.diameter) for b, st in zip(stage_base, chosen)]
    nose_len = aero.nose.length if top else 0.0
    shape = aero.nose.shape if top else "blunt"
    tail = aero.boattail
    if tail is not None and tail.stage != chosen[0].name:      # it left with its stage
        tail = None
    diameter, total, nose_base, base_d = outline(
        stages, top_parts, nose_len, shape, None if tail is None else (tail.length, tail.diameter))
    nose = None
    if nose_len > 0.0 and shape != "blunt":
        nose = (transition_centre_of_pressure(diameter, total - nose_len, total), math.pi * base_d ** 2 / 4)
    boattail = None
    if tail is not None:
        boattail = (transition_centre_of_pressure(diameter, 0.0, tail.length),
                    math.pi * (tail.diameter ** 2 - chosen[0].diameter ** 2) / 4)
    base_of = {st.name: b for st, b in zip(chosen, stage_base)}
    fins = []
    for fin in aero.fins:
        if fin.stage in base_of:
            d = diameter(base_of[fin.stage] + fin.position)
            cna, xf = barrowman(fin, d)
            fins.append((base_of[fin.stage] + fin.position - xf, cna * math.pi * d ** 2 / 4))
    largest = max(max(d for _, _, d in stages), max((d for _, d in top_parts), default=0.0))
    return BodyShape(diameter, total, nose_base, base_d, largest, nose, boattail, fins)


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
    volume = sum(math.pi * diameter(a + (k + 0.5) * (b - a) / n) ** 2 / 4 for k in range(n)) * (b - a) / n
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
