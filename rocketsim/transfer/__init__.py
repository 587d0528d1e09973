"""Transfers: Lambert's problem (Izzo), universal-variable Kepler, burns, windows.

    from rocketsim.transfer import lambert, propagate
    v1, v2 = lambert(mu, r1, r2, tof)          # SI units, arrays broadcast
    r, v = propagate(mu, r1, v1, tof)          # back to r2

The window search lives in :mod:`rocketsim.transfer.windows` (it loads the
ephemerides only when used).
"""

from rocketsim.transfer.kepler import propagate
from rocketsim.transfer.lambert import lambert, lambert_detailed

__all__ = ["lambert", "lambert_detailed", "propagate"]
