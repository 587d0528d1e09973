"""Hydrostatic integration of log-pressure on a height grid.

The atmospheres above their formula regions (the 1976 standard above 86 km,
Mars above 40 km, the day's air from the measured surface pressure) all solve
``d ln p / dz = -g(z) M(z) / (R* T(z))``. The right-hand side is known on a
fine grid of rows; ``ln p`` is integrated between the rows (Simpson's rule on
each interval, using the midpoint value), and evaluated between rows by cubic
Hermite interpolation with the exact derivative at both rows, so a lookup
between rows is an integration of the hydrostatic equation, not an
interpolation of pressure. Heights in metres, pressure in pascals.
"""

from __future__ import annotations

import numpy as np


def integrate_log_pressure(z, rate, rate_mid, log_p0):
    """Cumulative ``ln p`` at the rows ``z`` (m) from ``ln p(z[0]) = log_p0``.

    ``rate`` is ``d ln p / dz`` (1/m) at the rows, ``rate_mid`` at the
    midpoints of the intervals; Simpson's rule on each interval.
    """
    dz = np.diff(z)
    steps = dz * (rate[:-1] + 4.0 * rate_mid + rate[1:]) / 6.0
    return log_p0 + np.concatenate(([0.0], np.cumsum(steps)))


def hermite(z_rows, y, dy, z, slope=False):
    """Cubic Hermite value (and with ``slope=True`` also the slope) at ``z`` of a
    function known with its slope at rows ``z_rows`` (ascending, m); ``z`` is
    clamped to ``[z_rows[0], z_rows[-1]]``.
    """
    z = np.clip(np.asarray(z, dtype=float), z_rows[0], z_rows[-1])
    i = np.clip(np.searchsorted(z_rows, z, side="right") - 1, 0, len(z_rows) - 2)
    h = z_rows[i + 1] - z_rows[i]
    t = (z - z_rows[i]) / h
    t2, t3 = t * t, t * t * t
    value = ((2 * t3 - 3 * t2 + 1) * y[i] + (t3 - 2 * t2 + t) * h * dy[i]
             + (-2 * t3 + 3 * t2) * y[i + 1] + (t3 - t2) * h * dy[i + 1])
    if not slope:
        return value
    d = ((6 * t2 - 6 * t) * (y[i] - y[i + 1]) / h + (3 * t2 - 4 * t + 1) * dy[i]
         + (3 * t2 - 2 * t) * dy[i + 1])
    return value, d
