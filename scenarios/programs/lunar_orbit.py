"""To the Moon from a parking orbit: trans-lunar injection, cruise, lunar orbit insertion.

For a one-engine spacecraft (vehicles/lunar-orbiter.yaml) starting in a low
Earth parking orbit in the Moon's orbital plane, in a mission flown with
``gravity: n-body``.

1. Plan the injection: over one parking revolution and transfer times of
   3 to 5 days, the Lambert arc (two-body, Earth) from the parking orbit to
   an aim point beside the Moon at arrival, offset by the impact parameter
   of a 100 km periapsis (:func:`rocketsim.guidance.apsis.impact_parameter`);
   take the cheapest.
2. Burn to that arc with Lambert guidance (the arc re-solved every step from
   where the vehicle is to the same aim point and arrival time).
3. Cruise (cruise rails) until the Moon's sphere of influence takes over.
4. Trim the approach twice (at the handover and two hours before
   periapsis): turn the velocity in its own plane, speed kept, so that the
   lunar hyperbola's angular momentum is that of a 100 km periapsis.
5. Centred on periapsis, burn to the circular velocity of the current radius
   along the local horizontal (:func:`rocketsim.guidance.apsis.burn_at_periapsis`):
   a ~100 km lunar orbit.

Flown from the launch pad (scenarios/moon-from-pad.yaml: the lunar orbiter stacked on a
launcher as the scenario's ``spacecraft``), the program first flies the
launcher to the mission's target parking orbit and separates from its upper
stage (:func:`orbit_ascent.carry_to_orbit`), then does the above.

Burns and trims: :mod:`rocketsim.flight.maneuvers`.
"""

import math
from pathlib import Path

import numpy as np

from rocketsim.constants import EARTH_MU, MOON_MU, MOON_RADIUS
from rocketsim.flight.maneuvers import burn, burn_time, time_to_periapsis, trim_periapsis, unit
from rocketsim.flight.program import load_program_module
from rocketsim.guidance.apsis import burn_at_periapsis, impact_parameter
from rocketsim.orbits import propagate
from rocketsim.transfer.lambert import lambert

ASCENT = load_program_module(Path(__file__).resolve().parent / "orbit_ascent.py")

ALTITUDE = 100e3                          # m, target lunar orbit
R_P = MOON_RADIUS + ALTITUDE
DAY = 86400.0
THRUST, ISP = 45.04e3, 311.0              # N, s: the engine of vehicles/lunar-orbiter.yaml


def plan_injection(fc):
    """(burn mid-time s, arrival time s, aim point m) of the cheapest injection."""
    r0, v0, t0 = fc.position.copy(), fc.velocity.copy(), fc.time
    period = 2 * math.pi * math.sqrt(np.linalg.norm(r0) ** 3 / EARTH_MU)
    best = None
    for tof in np.arange(3.0, 5.01, 0.25) * DAY:
        starts = t0 + 900.0 + np.arange(0.0, period, 30.0)
        r1, v1 = propagate(EARTH_MU, np.tile(r0, (len(starts), 1)), np.tile(v0, (len(starts), 1)),
                           starts - t0)
        # the Moon at mid-revolution stands for the Moon at each arrival (it moves
        # 0.8 deg in a revolution): the search only picks the burn time
        moon = fc.body_state("moon", t0 + 900.0 + 0.5 * period + tof)[0]
        w1, _ = lambert(EARTH_MU, r1, np.tile(moon, (len(starts), 1)), np.full(len(starts), tof))
        dv = np.linalg.norm(w1 - v1, axis=1)
        k = int(np.argmin(dv))
        if best is None or dv[k] < best[0]:
            best = (dv[k], starts[k], starts[k] + tof)
        fc.step()               # one transfer time per step: within the CPU budget
    _, t_burn, t_arrive = best
    r1, v1 = propagate(EARTH_MU, r0, v0, t_burn - t0)
    moon, moon_v = fc.body_state("moon", t_arrive)
    _, w2 = lambert(EARTH_MU, r1, moon, t_arrive - t_burn)
    v_inf = w2 - moon_v
    b = impact_parameter(R_P, float(np.linalg.norm(v_inf)), MOON_MU)
    aim = moon + b * unit(np.cross(v_inf, unit(np.cross(moon, moon_v))))
    return t_burn, t_arrive, aim, best[0]


def main(fc):
    if len(fc.stages) > 1:      # on a launcher's stages: to the parking orbit first
        fc.log("separated", ASCENT.carry_to_orbit(fc))
    t_burn, t_arrive, aim, dv = plan_injection(fc)
    fc.log(f"TLI at {t_burn:.0f} s, {dv:.0f} m/s; arrival at {t_arrive / DAY:.2f} d")
    fc.sleep(max(t_burn - 0.5 * burn_time(fc.mass, dv, THRUST, ISP) - fc.time, 0.0))
    burn(fc, lambda: lambert(EARTH_MU, fc.position, aim, t_arrive - fc.time)[0], "tli", THRUST, ISP,
         rcs_turn=True)

    while fc.central_body != "moon":
        fc.cruise(3600.0)
    trim_periapsis(fc, R_P, "approach_trim", THRUST, ISP, rcs_turn=True)
    fc.cruise(max(time_to_periapsis(fc) - 6 * 3600.0, 0.0))
    trim_periapsis(fc, R_P, "approach_trim", THRUST, ISP, rcs_turn=True)
    burn_at_periapsis(fc, None, MOON_MU, "loi", THRUST, ISP, rcs_turn=True)
    orbit = fc.orbit
    fc.event("lunar_orbit", periapsis_altitude_m=orbit.periapsis - MOON_RADIUS,
             apoapsis_altitude_m=orbit.apoapsis - MOON_RADIUS)
