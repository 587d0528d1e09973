"""The inlined sine/cosine pair of the ephemeris kernels against the C
library (numpy's ``sin``/``cos``), over the arguments the series produce."""

from __future__ import annotations

import numpy as np

from rocketsim.jit import njit
from rocketsim.ephemeris.sincos import sincos


@njit
def _many(x, s, c):
    for i in range(x.shape[0]):
        a, b = sincos(x[i])
        s[i] = a
        c[i] = b


def test_agrees_with_the_c_library():
    rng = np.random.default_rng(20261126)
    # VSOP arguments reach |C t| ~ 1e4 rad over 1950-2100; ELP rows ~ 150 rad.
    x = np.concatenate([rng.uniform(-1e5, 1e5, 50_000), rng.uniform(-200.0, 200.0, 50_000),
                        np.arange(-64, 65) * (np.pi / 4),      # quadrant boundaries
                        [0.0, -0.0, 1e-300, 1.5e6]])
    s = np.empty_like(x)
    c = np.empty_like(x)
    _many(x, s, c)
    # a few units in the last place of values of order 1
    assert np.abs(s - np.sin(x)).max() < 4e-16
    assert np.abs(c - np.cos(x)).max() < 4e-16
