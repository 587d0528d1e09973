"""The late-2026 Earth-Mars window against an independent peer stack.

Our window search (project VSOP87D ephemerides, our Izzo solver) is checked
against a computation that shares none of its code: the Earth from ERFA's
``eraEpv00`` and Mars from ERFA's ``eraPlan94`` (Simon et al. 1994; IAU
SOFA/ERFA, via pyerfa), and lamberthub's ``izzo2015`` Lambert solver, all
used only in tests. On a grid around our optimum the peer's minimum C3 must
fall at the same dates (within the grid's spacing) and agree within 1 %.
"""

import datetime as dt

import erfa
import numpy as np
import pytest
from lamberthub import izzo2015

from rocketsim.constants import AU, SECONDS_PER_DAY, SUN_MU
from rocketsim.timescales import Epoch
from rocketsim.transfer import windows


def jd_tt(year, month, day):
    return Epoch.from_utc(dt.datetime(year, month, day)).jd_tt()


def peer_c3(departure_jd_tt, arrival_jd_tt):
    """C3 (m^2/s^2) of the zero-revolution prograde transfer, peer stack only."""
    earth = erfa.epv00(departure_jd_tt, 0.0)[0]                 # heliocentric, au and au/day
    mars = erfa.plan94(arrival_jd_tt, 0.0, 4)
    r1, v_earth = earth[0] * AU, earth[1] * AU / SECONDS_PER_DAY
    r2 = mars[0] * AU
    v1, _ = izzo2015(SUN_MU, r1, r2, (arrival_jd_tt - departure_jd_tt) * SECONDS_PER_DAY)
    return float(np.sum((v1 - v_earth) ** 2))


def test_the_2026_mars_window_agrees_with_erfa_and_lamberthub():
    found = windows.search(jd_tt(2026, 8, 1) + np.arange(0.0, 180.0, 2.0),
                           jd_tt(2027, 3, 1) + np.arange(0.0, 330.0, 2.0), objective="c3", count=1)
    best = found.windows[0]
    offsets_departure = np.arange(-6.0, 6.5, 1.0)
    offsets_arrival = np.arange(-12.0, 13.0, 2.0)
    grid = np.array([[peer_c3(best.departure_jd_tt + d, best.arrival_jd_tt + a)
                      for a in offsets_arrival] for d in offsets_departure])
    i, j = np.unravel_index(np.argmin(grid), grid.shape)
    assert abs(offsets_departure[i]) <= 1.0 and abs(offsets_arrival[j]) <= 2.0
    assert best.c3 == pytest.approx(grid[i, j], rel=0.01)
    assert best.c3 == pytest.approx(peer_c3(best.departure_jd_tt, best.arrival_jd_tt), rel=0.001)
