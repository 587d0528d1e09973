"""Transfers: Lambert's problem (Izzo), burns, windows.

    from rocketsim.transfer import lambert
    v1, v2 = lambert(mu, r1, r2, tof)          # SI units, arrays broadcast

Two-body propagation is :func:`rocketsim.orbits.propagate`. The window search
lives in :mod:`rocketsim.transfer.windows` (it loads the ephemerides only when
used).
"""

from rocketsim.transfer.lambert import lambert, lambert_detailed

__all__ = ["lambert", "lambert_detailed"]
