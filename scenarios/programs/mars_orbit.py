"""To Mars in the 2026 window: trans-Mars injection, cruise, Mars orbit insertion.

For a spacecraft with its own engines (vehicles/mars-orbiter.yaml) starting
in a low Earth parking orbit at the departure epoch of the window that
``rocketsim windows --target mars`` finds (mission time 0), flown with
``gravity: n-body``.

1. The heliocentric Lambert arc from Earth now to Mars at arrival (the
   window's 310.23-day transfer) gives the departure excess velocity
   ``v_inf``. The escape hyperbola's periapsis lies ``nu_inf = acos(-1/e)``
   before the asymptote in the parking plane (``e = 1 + r_p v_inf^2 / mu``):
   the injection is centred there.
2. Burn to the hyperbola's velocity at the current position
   (:func:`rocketsim.flight.maneuvers.hyperbola_velocity`), re-aimed every step.
3. Cruise out of Earth's sphere of influence; two course corrections to a
   point on the incoming asymptote of a 400 km periapsis, five days before
   arrival: Lambert arcs (the Sun alone) re-aimed until the full field's
   prediction (``fc.predict``) hits it.
4. In Mars's sphere: trim the periapsis to 400 km twice (``fc.predict``
   through the full field), then, centred on periapsis, burn to the velocity
   of a 400 x 33 000 km orbit along the local horizontal
   (:func:`rocketsim.guidance.apsis.burn_at_periapsis`).

Flown from the launch pad (scenarios/mars-from-pad.yaml: the Mars orbiter stacked on a
launcher as the scenario's ``spacecraft``), the program first flies the
launcher to the mission's target parking orbit and separates from its upper
stage (:func:`orbit_ascent.carry_to_orbit`), then does the above.

The course corrections and trims first turn the orbiter with its RCS
thrusters, engines off (``rcs_turn=True``): the engines' 10 % minimum throttle
would otherwise over-burn a small correction while the vehicle turns (flown
from the pad, the first correction's 17 m/s became 1210 m/s and emptied the
tanks). The insertion does not: near periapsis its direction turns faster than
an RCS turn settles (one took 183 s and the late burn ran dry), and at its
~1 km/s the engines' turn costs little.
Burns and trims: :mod:`rocketsim.flight.maneuvers`.
"""

import math
from pathlib import Path

import numpy as np

from rocketsim.constants import EARTH_MU, MARS_MU, MARS_RADIUS_EQ, SUN_MU
from rocketsim.flight.maneuvers import (burn, burn_time, hyperbola_velocity, time_to_periapsis,
                                        trim_periapsis, unit)
from rocketsim.flight.program import load_program_module
from rocketsim.guidance.apsis import burn_at_periapsis, impact_parameter
from rocketsim.transfer.lambert import lambert

ASCENT = load_program_module(Path(__file__).resolve().parent / "orbit_ascent.py")

DAY = 86400.0
TRANSFER = 310.2311 * DAY                 # s, the window's time of flight (mission fragment)
R_P = MARS_RADIUS_EQ + 400e3              # m, capture periapsis
R_A = MARS_RADIUS_EQ + 33000e3            # m, capture apoapsis
THRUST, ISP = 2 * 45.04e3, 311.0          # N, s: the two engines of vehicles/mars-orbiter.yaml
LEAD = 5 * DAY                            # s before arrival the course corrections aim at


def heliocentric(fc, name, t):
    """Position and velocity of ``name`` relative to the Sun at mission time ``t``
    (frame axes), from the ephemeris about the current central body."""
    r, v = fc.body_state(name, t) if name != fc.central_body else (np.zeros(3), np.zeros(3))
    if fc.central_body == "sun":
        return r, v
    sun, sun_v = fc.body_state("sun", t)
    return r - sun, v - sun_v


def injection(fc):
    """(burn mid-time s, departure v-infinity m/s) for the window's arc."""
    r_earth, v_earth = heliocentric(fc, "earth", 0.0)
    r_mars, _ = heliocentric(fc, "mars", TRANSFER)
    v1, _ = lambert(SUN_MU, r_earth, r_mars, TRANSFER)
    v_inf = v1 - v_earth
    r, v = fc.position, fc.velocity
    normal = unit(np.cross(r, v))
    u = unit(v_inf - (v_inf @ normal) * normal)          # the asymptote in the parking plane
    rn = float(np.linalg.norm(r))
    e = 1.0 + rn * float(v_inf @ v_inf) / EARTH_MU
    nu_inf = math.acos(-1.0 / e)
    periapsis = math.cos(nu_inf) * u - math.sin(nu_inf) * np.cross(normal, u)
    angle = math.atan2(float(np.cross(r / rn, periapsis) @ normal), float(r @ periapsis) / rn)
    rate = float(np.linalg.norm(np.cross(r, v))) / rn ** 2
    return fc.time + (angle % (2 * math.pi)) / rate, v_inf


def aim_point(fc):
    """Where to be (heliocentric, m) :data:`LEAD` before arrival: on the incoming
    asymptote of a hyperbola whose periapsis is 400 km above Mars (impact
    parameter, :func:`~rocketsim.guidance.apsis.impact_parameter`), moving with Mars."""
    r_mars, v_mars = heliocentric(fc, "mars", TRANSFER)
    _, v2 = lambert(SUN_MU, fc.position, r_mars, TRANSFER - fc.time)
    v_inf = v2 - v_mars
    b = impact_parameter(R_P, float(np.linalg.norm(v_inf)), MARS_MU)
    offset = b * unit(np.cross(v_inf, np.cross(r_mars, v_mars)))
    r_then, _ = heliocentric(fc, "mars", TRANSFER - LEAD)
    return r_then + offset - v_inf * LEAD


def correct_course(fc, aim, label):
    """Burn so that the full field (``fc.predict``: the Sun, Earth, Moon and Mars)
    brings the vehicle to ``aim`` :data:`LEAD` before arrival: the Lambert arc
    (two-body, the Sun) aimed at a point moved by the predicted miss, repeated."""
    target = aim.copy()
    for _ in range(8):
        v1, _ = lambert(SUN_MU, fc.position, target, TRANSFER - LEAD - fc.time)
        change = v1 - fc.velocity
        _, r_end, _ = fc.predict(TRANSFER - LEAD - fc.time, change)
        miss = r_end - aim
        if np.linalg.norm(miss) < 100e3:
            break
        target = target - miss
    fc.log(f"{label}: {np.linalg.norm(change):.2f} m/s, predicted miss {np.linalg.norm(miss) / 1e3:.1f} km")
    start = fc.velocity.copy()
    if np.linalg.norm(change) >= 1.0:
        burn(fc, lambda: start + change, label, THRUST, ISP, rcs_turn=True)


def main(fc):
    if len(fc.stages) > 1:      # on a launcher's stages: to the parking orbit first
        fc.log("separated", ASCENT.carry_to_orbit(fc))
    t_mid, v_inf = injection(fc)
    dv = float(np.linalg.norm(hyperbola_velocity(fc.position, v_inf, EARTH_MU)) - np.linalg.norm(fc.velocity))
    fc.log(f"TMI centred at {t_mid:.0f} s, v_inf {np.linalg.norm(v_inf):.0f} m/s, ~{dv:.0f} m/s")
    start = t_mid - 0.5 * burn_time(fc.mass, dv, THRUST, ISP)
    if start < fc.time + 60.0:
        start += 2 * math.pi * math.sqrt(np.linalg.norm(fc.position) ** 3 / EARTH_MU)
    fc.sleep(start - fc.time)
    burn(fc, lambda: hyperbola_velocity(fc.position, v_inf, EARTH_MU), "tmi", THRUST, ISP)

    while fc.central_body != "sun":
        fc.cruise(6 * 3600.0)
    aim = aim_point(fc)
    correct_course(fc, aim, "course_correction")
    fc.cruise(TRANSFER - 30 * DAY - fc.time)
    correct_course(fc, aim, "course_correction")
    while fc.central_body != "mars":
        fc.cruise(6 * 3600.0)

    trim_periapsis(fc, R_P, "approach_trim", THRUST, ISP, horizon=10 * DAY, rcs_turn=True)
    fc.cruise(max(time_to_periapsis(fc, 10 * DAY) - 12 * 3600.0, 0.0))
    trim_periapsis(fc, R_P, "approach_trim", THRUST, ISP, horizon=10 * DAY, rcs_turn=True)
    burn_at_periapsis(fc, R_A, MARS_MU, "moi", THRUST, ISP, horizon=10 * DAY)
    orbit = fc.orbit
    fc.event("mars_orbit", periapsis_altitude_m=orbit.periapsis - MARS_RADIUS_EQ,
             apoapsis_altitude_m=orbit.apoapsis - MARS_RADIUS_EQ, period_s=orbit.period)
