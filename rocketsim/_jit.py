"""The one way the library compiles kernels.

`njit` is numba's ``njit`` with the project's settings: compiled kernels are
cached on disk (``cache=True``) so a second ``rocketsim fly`` starts flying
without recompiling, ``fastmath`` stays off so results are IEEE-exact and
bit-identical run to run, and division by zero follows numpy (inf/nan) rather
than raising inside the hot path.
"""

from numba import njit as _numba_njit

_OPTIONS = {"cache": True, "fastmath": False, "error_model": "numpy"}


def njit(func=None, **options):
    """Compile ``func`` (use as ``@njit`` or ``@njit(inline="always")``)."""
    settings = {**_OPTIONS, **options}
    if func is None:
        return _numba_njit(**settings)
    return _numba_njit(**settings)(func)
