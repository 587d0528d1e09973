"""A stage's thrust and propellant flow on paper, from its file alone (pure Python, for the
stack's summary and the design review: :mod:`rocketsim.vehicle.summary`,
:mod:`rocketsim.vehicle.review`)."""

from __future__ import annotations

from rocketsim.constants import G0, USSA_P0


def stage_engines(stage) -> tuple[float, float, float]:
    """``(vacuum thrust N, sea-level thrust N, mass flow kg/s)`` of a stage's engines at full
    throttle, and of its solid motors at their mean thrust and flow (total impulse and
    propellant over the curve's duration; the same at sea level: a curve is measured there)."""
    vacuum = sum(e.count * e.thrust_vacuum for e in stage.engines)
    sea = sum(e.count * max(0.0, e.thrust_vacuum - USSA_P0 * e.exit_area) for e in stage.engines)
    flow = sum(e.count * e.thrust_vacuum / (G0 * e.isp) for e in stage.engines)
    for m in stage.motors:
        burn = m.thrust[-1][0]
        vacuum, sea, flow = vacuum + m.total_impulse / burn, sea + m.total_impulse / burn, \
            flow + m.propellant_mass / burn
    return vacuum, sea, flow
