"""The one way the library compiles kernels.

`njit` is numba's ``njit`` with the project's settings: compiled kernels are
cached on disk (``cache=True``) so a second ``rocketsim fly`` starts flying
without recompiling, ``fastmath`` stays off so results are IEEE-exact and
bit-identical run to run, and division by zero follows numpy (inf/nan) rather
than raising inside the hot path.

numba's cache checks only the source file of the function it compiled, not
the functions that function calls from other modules: after an edit to
``bodies/gravity.py`` a cached ``dynamics/derivative.py`` kernel would still
run the old gravity. So the cache lives in a folder named for a hash of the
whole library's source (``~/.cache/rocketsim/numba-<hash>``, or below
``$ROCKETSIM_CACHE_DIR``): any change to any module starts a fresh cache.
Hashing the sources costs about a millisecond at import.
"""

import hashlib
import os
from pathlib import Path

import numba
from numba import njit as _numba_njit

_OPTIONS = {"cache": True, "fastmath": False, "error_model": "numpy"}


def _source_hash() -> str:
    digest = hashlib.sha256(numba.__version__.encode())
    package = Path(__file__).resolve().parent
    for path in sorted(package.rglob("*.py")):
        digest.update(path.relative_to(package).as_posix().encode())
        digest.update(path.read_bytes())
    return digest.hexdigest()[:16]


def _cache_dir() -> str:
    root = os.environ.get("ROCKETSIM_CACHE_DIR") or os.path.join(
        os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache"), "rocketsim")
    return os.path.join(root, f"numba-{_source_hash()}")


if not os.environ.get("NUMBA_CACHE_DIR"):
    numba.config.CACHE_DIR = _cache_dir()


def njit(func=None, **options):
    """Compile ``func`` (use as ``@njit`` or ``@njit(inline="always")``)."""
    settings = {**_OPTIONS, **options}
    if func is None:
        return _numba_njit(**settings)
    return _numba_njit(**settings)(func)
