"""From Mars orbit down under a parachute: deorbit, a ballistic entry, the disk-gap-band.

For a capsule with a deorbit engine and a heat shield
(vehicles/mars-entry-capsule.yaml) starting in a low circular Mars orbit.

1. Deorbit: burn (:func:`rocketsim.flight.maneuvers.burn`) to the velocity,
   along the local horizontal, of an ellipse from here to a periapsis 40 km
   below the surface (:func:`rocketsim.guidance.apsis.apsis_velocity`; an
   entry flight-path angle near -3 deg at 125 km).
2. Point the heat shield (the nose) along the velocity while the engine
   still has thrust to steer with, then release: the capsule falls ballistic.
3. Watch the descent: ``fc.mach`` (about Mars, in the Mars reference
   atmosphere turning with Mars) and ``fc.altitude`` (over Mars's ellipsoid).
   The parachute conditions: Mach below 2 more than 7 km up (the supersonic
   disk-gap-band parachutes of Viking, Phoenix and the Mars Science
   Laboratory opened between Mach 1.1 and 2.1, 6 to 13 km up).
4. Open the disk-gap-band there and descend on it; the flight ends (the
   scenario's duration) near 2 km, where the Mars Science Laboratory left its
   parachute for the powered descent, which is not flown.
"""

import numpy as np

from rocketsim.constants import MARS_MU, MARS_RADIUS_EQ
from rocketsim.flight.maneuvers import burn
from rocketsim.guidance.apsis import apsis_velocity

THRUST, ISP = 4.0e3, 220.0                # N, s: the deorbit engine of the capsule
PERIAPSIS = MARS_RADIUS_EQ - 40e3         # m
PARACHUTE_MACH, PARACHUTE_HEIGHT = 2.0, 7e3


def main(fc):
    def deorbit():
        return apsis_velocity(fc.position, fc.velocity, PERIAPSIS, MARS_MU)
    burn(fc, deorbit, "deorbit", THRUST, ISP)
    fc.wait_until(fc.below("altitude", 150e3))
    fc.event("entry_interface", inertial_speed_m_s=float(np.linalg.norm(fc.velocity)))
    fc.wait_until(lambda: fc.mach < PARACHUTE_MACH or fc.altitude < PARACHUTE_HEIGHT)
    fc.event("parachute_conditions", mach=fc.mach, altitude_m=fc.altitude,
             inertial_speed_m_s=float(np.linalg.norm(fc.velocity)))
    fc.deploy_parachute("disk-gap-band")
