"""The truncated series are laid out at import with the plans the generator wrote into
_tables.py (rocketsim.ephemeris.layouts): the same arrays, to the bit, dtype, shape and
memory order, as laying them out afresh (the plans worked out again) gives."""

import numpy as np
import pytest

from rocketsim.ephemeris import _tables, elp2000, vsop87
from rocketsim.ephemeris.layouts import prepare_elp, prepare_vsop


def _same(written, laid_out):
    assert type(written) is type(laid_out)
    for name, a, b in zip(type(laid_out)._fields, written, laid_out):
        assert a.dtype == b.dtype and a.shape == b.shape, name
        assert a.flags.c_contiguous and b.flags.c_contiguous, name
        assert np.array_equal(a, b), name
        assert a.tobytes() == b.tobytes(), name        # the bits, signed zeros included


@pytest.mark.parametrize("body", ["earth", "mars"])
def test_the_written_vsop87_layouts_are_those_of_the_truncated_series(body):
    name = body.upper()
    laid_out = prepare_vsop(*(getattr(_tables, f"{name}_{f}") for f in ("COORD", "POWER", "A", "B", "C")))
    _same(vsop87.TABLES[body], laid_out)


def test_the_written_elp2000_layout_is_that_of_the_truncated_series():
    _same(elp2000.TABLE, prepare_elp(_tables.MOON_COORD, _tables.MOON_MULT, _tables.MOON_A))
