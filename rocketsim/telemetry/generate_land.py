"""Generate the land mask the flight plot draws its coastlines from.

Run from the repository root (needs the ``generate`` extra)::

    pip install -e ".[generate]" && python -m rocketsim.telemetry.generate_land

Source: the GLOBE digital elevation dataset (NOAA NGDC, 30 arc-second grid,
public domain) as packaged ocean/not-ocean by ``global-land-mask`` (a 21 600 x
43 200 boolean grid, 1/120 degree). This script averages it over blocks of
``BLOCK`` x ``BLOCK`` cells (0.1 degree, about 11 km) and writes
``_land.npz`` beside itself: the land fraction of each block as a uint8
(0..255), 1 800 x 3 600 cells, rows from the south pole, columns from
180 W. The plot draws the 0.5 contour of that fraction as the coastline.
The full grid (930 MB in memory) is never shipped.
"""

from pathlib import Path

import numpy as np

BLOCK = 12                       # 1/120 deg cells per table cell: 0.1 deg
OUT = Path(__file__).with_name("_land.npz")


def block_fraction(mask: np.ndarray, block: int) -> np.ndarray:
    """Mean of ``mask`` over ``block`` x ``block`` cells, as uint8 0..255 (rows kept in order)."""
    rows, cols = mask.shape[0] // block, mask.shape[1] // block
    total = np.zeros((rows, cols), dtype=np.float64)
    for i in range(block):           # row by row of each block: bounded memory
        part = mask[i:rows * block:block, :cols * block].reshape(rows, cols, block)
        total += part.sum(axis=2)
    return np.round(255.0 * total / (block * block)).astype(np.uint8)


def main() -> None:
    from global_land_mask import globe

    ocean, lat = globe._mask, globe._lat          # the package's grid is True at sea
    fraction = 255 - block_fraction(ocean, BLOCK)
    if lat[0] > lat[-1]:             # the table's rows run from the south
        fraction = fraction[::-1]
    np.savez_compressed(OUT, land=fraction, cell_deg=np.float64(BLOCK / 120.0))
    print(f"wrote {OUT} ({fraction.shape[0]} x {fraction.shape[1]}, {OUT.stat().st_size} bytes)")


if __name__ == "__main__":
    main()
