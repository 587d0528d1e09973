"""Transfers: Lambert's problem (Izzo), burns, windows.

    from rocketsim.transfer import lambert
    v1, v2 = lambert(mu, r1, r2, tof)          # SI units, arrays broadcast

Two-body propagation is :func:`rocketsim.orbits.propagate`. The transfer arcs over a
grid of dates live in :mod:`rocketsim.transfer.arcs`, the window search over them in
:mod:`rocketsim.transfer.windows` (both load the ephemerides only when used).
"""

from rocketsim.transfer.lambert import lambert, lambert_detailed

__all__ = ["lambert", "lambert_detailed"]
