"""The figures of a staged vehicle on paper: masses, Delta-v, thrust-to-weight, inertia.

Per stage ``i`` (bottom first), fired with everything above it still on
(payload and fairing included throughout: the fairing's jettison is an event
of the flight, not of this table)::

    m_ignition = sum of the wet masses of stages i..top + payload + fairing
    m_burnout  = m_ignition - 0.99 * propellant_i          (1 % unusable)
    dv         = Isp * g0 * ln(m_ignition / m_burnout)      (Tsiolkovsky)

with the stage's Isp = sum of thrust / (g0 * sum of mass flow) of its
engines, in vacuum and at sea level (``T = T_vac - p0 A_e``,
p0 = 101 325 Pa); a solid motor counts at its mean thrust and flow, and
burns all its propellant (its Isp is its total impulse over ``g0 m0``). Thrust-to-weight at liftoff: the bottom stage's sea-level
thrust over the liftoff weight (``m g0``).
"""

from __future__ import annotations

import math

import numpy as np

from rocketsim.constants import G0, UNUSABLE_PROPELLANT
from rocketsim.vehicle.build import build
from rocketsim.vehicle.stage_thrust import stage_engines


def summary(spec) -> dict:
    """A JSON-ready dict of the stack's figures (SI units, as named in the keys)."""
    model = build(spec)
    top = (spec.payload.mass if spec.payload else 0.0) + (spec.fairing.mass if spec.fairing else 0.0)
    wet = [st.dry_mass + st.propellant_mass for st in spec.stages]
    stages = []
    for i, st in enumerate(spec.stages):
        vacuum, sea, flow = stage_engines(st)
        usable = (1 - UNUSABLE_PROPELLANT) * sum(t.load for t in st.tanks if t.feeds_engines) \
            + sum(m.propellant_mass for m in st.motors)          # a solid motor burns it all
        ignition = sum(wet[i:]) + top
        burnout = ignition - usable
        ratio = math.log(ignition / burnout) if burnout > 0 else 0.0
        isp_vac = vacuum / (G0 * flow) if flow > 0 else 0.0
        isp_sea = sea / (G0 * flow) if flow > 0 else 0.0
        stages.append({
            "name": st.name,
            "wet_mass_kg": wet[i],
            "dry_mass_kg": st.dry_mass,
            "propellant_mass_kg": st.propellant_mass,
            "engines": sum(e.count for e in st.engines),
            "thrust_vacuum_N": vacuum,
            "thrust_sea_level_N": sea,
            "isp_vacuum_s": isp_vac,
            "isp_sea_level_s": isp_sea,
            "burn_time_s": usable / flow if flow > 0 else 0.0,
            "ignition_mass_kg": ignition,
            "burnout_mass_kg": burnout,
            "delta_v_vacuum_m_s": isp_vac * G0 * ratio,
            "delta_v_sea_level_m_s": isp_sea * G0 * ratio,
        })
    liftoff = sum(wet) + top
    full = model.mass_properties(model.tank_load)
    empty = model.mass_properties(UNUSABLE_PROPELLANT * model.tank_load, motors=np.zeros(model.n_motors))
    return {
        "name": spec.name,
        "length_m": model.length,
        "liftoff_mass_kg": liftoff,
        "liftoff_thrust_N": stages[0]["thrust_sea_level_N"],
        "liftoff_thrust_to_weight": stages[0]["thrust_sea_level_N"] / (liftoff * G0),
        "payload_mass_kg": spec.payload.mass if spec.payload else 0.0,
        "fairing_mass_kg": spec.fairing.mass if spec.fairing else 0.0,
        "delta_v_vacuum_m_s": sum(s["delta_v_vacuum_m_s"] for s in stages),
        "delta_v_sea_level_m_s": sum(s["delta_v_sea_level_m_s"] for s in stages),
        "full": _properties(full),
        "empty": _properties(empty),
        "stages": stages,
    }


def _properties(values) -> dict:
    mass, x_cm, ixx, iyy, izz = (float(v) for v in values)
    return {"mass_kg": mass, "centre_of_mass_m": x_cm, "inertia_kg_m2": [ixx, iyy, izz]}
