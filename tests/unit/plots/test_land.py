"""The coastline table of the flight plot against places whose land or sea is not in doubt.

Reference points (geodetic degrees, from any atlas): Orlando FL 28.54 N 81.38 W
and Madrid 40.42 N 3.70 W (land, far inland); the Sahara at 23 N 10 E; the
open Atlantic 28.5 N 79.0 W (east of Cape Canaveral, beyond the Gulf Stream
shelf) and 30 N 40 W; the Pacific at 0 N 150 W; Antarctica at 80 S 0 E; the
longitude wraps (190 E is 170 W).
"""

import matplotlib
import pytest

from rocketsim.telemetry.land import draw_coastline, land_fraction

matplotlib.use("Agg")


@pytest.mark.parametrize("lat, lon", [(28.54, -81.38), (40.42, -3.70), (23.0, 10.0), (-80.0, 0.0)])
def test_land_is_land(lat, lon):
    assert land_fraction(lat, lon) == 1.0


@pytest.mark.parametrize("lat, lon", [(28.5, -79.0), (30.0, -40.0), (0.0, -150.0), (0.0, 210.0)])
def test_sea_is_sea(lat, lon):
    assert land_fraction(lat, lon) == 0.0


def test_a_coast_is_drawn_near_the_cape_and_none_over_open_sea():
    import matplotlib.pyplot as plt
    figure, ax = plt.subplots()
    draw_coastline(ax, (-81.0, -80.0), (28.0, 29.0))       # Cape Canaveral's coast
    assert len(ax.collections) == 1
    draw_coastline(ax, (-45.0, -35.0), (25.0, 35.0))       # mid-Atlantic: nothing to draw
    assert len(ax.collections) == 1
    plt.close(figure)
