"""Land and sea on a 0.1 degree grid, for the ground-track map of the flight plot.

The table ``_land.npz`` (written by :mod:`rocketsim.telemetry.generate_land`
from the GLOBE dataset) holds the land fraction of each 0.1 x 0.1 degree
cell, rows from the south pole, columns from 180 W (geodetic latitude and
longitude, degrees). A coastline is its 0.5 contour.
"""

from __future__ import annotations

from functools import lru_cache
from pathlib import Path

import numpy as np

_TABLE = Path(__file__).with_name("_land.npz")
MAX_CELLS = 600                  # cells per axis drawn at most (coarser for a wide view)


@lru_cache(maxsize=1)
def _table() -> tuple[np.ndarray, float]:
    with np.load(_TABLE) as data:
        return data["land"], float(data["cell_deg"])


def land_fraction(latitude_deg: float, longitude_deg: float) -> float:
    """Land fraction (0..1) of the cell holding the point (degrees, longitude any turn)."""
    land, cell = _table()
    row = min(int((latitude_deg + 90.0) / cell), land.shape[0] - 1)
    col = int(((longitude_deg + 180.0) % 360.0) / cell) % land.shape[1]
    return land[row, col] / 255.0


def draw_coastline(ax, lon_limits: tuple[float, float], lat_limits: tuple[float, float]) -> None:
    """Draw the coastlines inside the given longitude/latitude box (degrees) on ``ax``."""
    land, cell = _table()
    lat0, lat1 = max(-90.0, lat_limits[0]), min(90.0, lat_limits[1])
    lon0, lon1 = max(-180.0, lon_limits[0]), min(180.0, lon_limits[1])
    rows = slice(max(0, int((lat0 + 90.0) / cell) - 1), min(land.shape[0], int((lat1 + 90.0) / cell) + 2))
    cols = slice(max(0, int((lon0 + 180.0) / cell) - 1), min(land.shape[1], int((lon1 + 180.0) / cell) + 2))
    stride = max(1, max(rows.stop - rows.start, cols.stop - cols.start) // MAX_CELLS)
    part = land[rows, cols][::stride, ::stride]
    if part.shape[0] < 2 or part.shape[1] < 2 or part.min() > 127 or part.max() < 128:
        return                   # all land or all sea here: no coastline to draw
    lat = -90.0 + (np.arange(rows.start, rows.stop, stride) + 0.5) * cell
    lon = -180.0 + (np.arange(cols.start, cols.stop, stride) + 0.5) * cell
    ax.contour(lon, lat, part, levels=[127.5], colors="0.55", linewidths=0.6)
