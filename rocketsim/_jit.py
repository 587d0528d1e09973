"""The kernels' names where they were imported from before :mod:`rocketsim.jit`: removed with
the rename of those imports."""

from rocketsim.jit import *  # noqa: F401,F403
from rocketsim.jit.entries import _kinds  # noqa: F401
