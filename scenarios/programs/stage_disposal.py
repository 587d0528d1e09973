"""Disposal of a spent upper stage left in low Earth orbit: a deorbit burn.

After it has released the spacecraft it carried (``programs: {second stage:
programs/stage_disposal.py}`` in the scenario), the stage waits CLEAR_DELAY
to drift clear, turns retrograde, and burns until its periapsis lies
DISPOSAL_PERIAPSIS below the surface (altitude, m): it re-enters within half
an orbit instead of staying in orbit as debris, as launchers' upper stages are
required to. (In the simulation it also leaves the spacecraft the only body in
flight, so the spacecraft's cruise rails can run.)
"""

CLEAR_DELAY = 60.0             # s after separation before turning
TURN_TIME = 30.0               # s to turn retrograde and settle
THROTTLE = 0.4                 # the engine's low end: a gentle ~100 m/s burn
DISPOSAL_PERIAPSIS = -500e3    # m: the stage's periapsis altitude after the burn


def main(fc):
    fc.sleep(CLEAR_DELAY)
    fc.hold("retrograde")
    fc.sleep(TURN_TIME)
    fc.ignite()
    fc.throttle(THROTTLE)
    fc.wait_until(lambda: fc.periapsis < DISPOSAL_PERIAPSIS or sum(fc.propellant.values()) < 1.0)
    fc.shutdown()
    fc.release()
    fc.event("deorbit", periapsis_altitude_m=fc.periapsis)
