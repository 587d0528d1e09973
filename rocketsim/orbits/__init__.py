"""Orbits: two-body propagation of any conic (universal-variable Kepler).

    from rocketsim.orbits import propagate
    r, v = propagate(mu, r0, v0, dt)           # SI units, any inertial frame

Below the dynamics and the transfers, which both use it.
"""

from rocketsim.orbits.kepler import propagate

__all__ = ["propagate"]
