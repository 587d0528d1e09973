"""Structural limits: the bending load ``q alpha`` and the axial load.

docs/physics.md#structural-limits: ``q alpha <= 250 kPa deg`` of bending
load and an axial load of at most 15 g.
``q`` is the dynamic pressure (Pa), ``alpha`` the total angle of attack
(deg; measured from the nearer end of the body's axis, so a booster flying
tail first at 180 degrees carries no bending), and the axial load the
non-gravitational acceleration along the body's x axis in units of g0
(compression either way). A vehicle past either limit breaks up: the world
records the event with these figures and ends the body.
"""

from __future__ import annotations

from rocketsim.jit import njit
from rocketsim.constants import DEG, G0, STRUCTURE_AXIAL_LIMIT_G, STRUCTURE_Q_ALPHA_LIMIT


@njit
def bending_alpha(alpha: float) -> float:
    """Angle (rad) between the flow and the nearer end of the axis, 0 to 90 degrees."""
    return min(alpha, 180.0 * DEG - alpha)


def breakup(q: float, alpha: float, axial_acceleration: float, q_alpha_limit: float = STRUCTURE_Q_ALPHA_LIMIT,
            axial_limit_g: float = STRUCTURE_AXIAL_LIMIT_G) -> dict | None:
    """The breakup figures if a limit is passed, else None.

    ``q`` dynamic pressure (Pa), ``alpha`` total angle of attack (rad),
    ``axial_acceleration`` sensed acceleration along body x (m/s^2); the limits
    (Pa deg, g0) are the defaults above unless the vehicle file's ``aero.limits``
    gives its own.
    """
    q_alpha = q * bending_alpha(alpha) / DEG
    load = abs(axial_acceleration) / G0
    if q_alpha > q_alpha_limit:
        cause = "bending"
    elif load > axial_limit_g:
        cause = "axial load"
    else:
        return None
    return {"cause": cause, "q_alpha_Pa_deg": q_alpha, "dynamic_pressure_Pa": q,
            "angle_of_attack_deg": alpha / DEG, "axial_load_g": load}
