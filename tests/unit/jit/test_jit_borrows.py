"""Kernels compiled without reference counting (``njit(borrows=True)``) return no arrays.

A borrowing kernel takes its caller's arrays without counting references to them
(:mod:`rocketsim.jit`). numba refuses to compile one that makes an array; one that
returned an array (its argument, or a view of one) would hand its caller a
reference that was never counted, and the caller's release would free the array
under whoever still holds it. The flights here go through the derivative's
borrowing kernels (a rail launch under parachutes with a solid motor, a finned
rocket with an engine, a booster on its legs with grid fins and RCS), and every
signature of a borrowing kernel in the kernel cache (where a kernel compiled
inside another's compiling saves its own signatures) is loaded and read for its
return type.
"""

import sys

import numpy as np
import pytest
from numba import types
from numba.core.errors import TypingError

import rocketsim
from rocketsim.jit import Kernel, njit
from rocketsim.jit.numba_internals import cached_signatures


def _holds_array(t) -> bool:
    """Whether numba type ``t`` is, or holds, an array."""
    if isinstance(t, types.Array):
        return True
    if isinstance(t, types.BaseTuple):
        return any(_holds_array(item) for item in t.types)
    return False


def _borrowing_kernels() -> dict[str, Kernel]:
    """Every borrowing kernel of the library's loaded modules, by qualified name."""
    found = {}
    for name, module in list(sys.modules.items()):
        if name.startswith("rocketsim.") and module is not None:
            for value in vars(module).values():
                if isinstance(value, Kernel) and value.borrows:
                    found[f"{value.__module__}.{value.__qualname__}"] = value
    return found


def _signatures(kernel: Kernel) -> list:
    """Every signature of ``kernel`` compiled in this process or in the kernel cache (loaded)."""
    for signature in cached_signatures(kernel):
        kernel.compile(signature)           # loaded from the cache
    return kernel.nopython_signatures


def _array_returns(kernel: Kernel) -> list:
    """The signatures of ``kernel`` that return an array (or a tuple holding one)."""
    return [sig for sig in _signatures(kernel) if _holds_array(sig.return_type)]


FORCES = {"rocketsim.dynamics.derivative.held_derivative", "rocketsim.vehicle.aero.body_aero",
          "rocketsim.vehicle.engines.engine_forces"}


# each flight's own borrowing kernels are required (a test process may have flown others
# before it, or none): the ballistic capsule is a rigid body, whose derivative sums no
# aerodynamics and no engines
@pytest.mark.parametrize("scenario, duration, flown", [("hobby-rocket", 30.0, FORCES), ("falcon9-hop", 40.0, FORCES),
                                                       ("spaceport-ballistic", 20.0,
                                                        {"rocketsim.dynamics.derivative.held_derivative"})])
def test_no_borrowing_kernel_returns_an_array(scenario, duration, flown, tmp_path):
    rocketsim.fly(f"scenarios/{scenario}.yaml", tmp_path / "run.mcap", duration=duration)
    compiled = {name: k for name, k in _borrowing_kernels().items() if _signatures(k)}
    # the derivative and the forces it sums were compiled borrowing for this flight
    assert flown <= set(compiled)
    assert {name: _array_returns(k) for name, k in compiled.items() if _array_returns(k)} == {}


def test_a_borrowing_kernel_that_returns_its_argument_is_found():
    def passes_on(a):
        return a

    kernel = njit(borrows=True, cache=False)(passes_on)
    np.testing.assert_array_equal(kernel(np.arange(3.0)), np.arange(3.0))
    assert len(_array_returns(kernel)) == 1


def test_numba_refuses_a_borrowing_kernel_that_makes_an_array():
    def makes(n):
        return np.zeros(n)

    with pytest.raises(TypingError, match="Only accept returning of array passed into the function"):
        njit(borrows=True, cache=False)(makes)(3)
