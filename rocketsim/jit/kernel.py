"""The decorator of every kernel: :func:`njit`, the :class:`Kernel` it makes, and
:func:`copy_into`, the kernels' copy of an array into a slice.

``njit`` is numba's ``njit`` with the project's options (:data:`OPTIONS`):
compiled kernels are cached on disk (``cache=True``) so a second ``rocketsim fly``
starts flying without recompiling, ``fastmath`` stays off so results are
IEEE-exact and bit-identical run to run, and division by zero follows numpy
(inf/nan) rather than raising inside the hot path. ``njit(borrows=True)``
compiles without numba's reference counting (see :mod:`rocketsim.jit`).

numba itself (long to import, with the scipy it pulls in) is imported only when a
kernel is first called or compiled: ``njit`` returns a :class:`Kernel`, which
makes numba's dispatcher on first need. A command that
only reads files (``rocketsim validate``, ``schema``, ``replay`` of a summary)
imports the kernel modules for their constants and never loads numba. Another
kernel refers to a :class:`Kernel` as to the dispatcher itself (numba types it
through ``_numba_type_``), so kernels compile and inline exactly as numba's own.
"""

from __future__ import annotations

import functools

from rocketsim.jit import numba_internals
from rocketsim.jit.beside import BESIDE
from rocketsim.jit.settings import current

OPTIONS = {"cache": True, "fastmath": False, "error_model": "numpy", "_nrt": True}


def _calls_intrinsic(func) -> bool:
    """Whether ``func`` calls a numba intrinsic by a global name (machine code with no
    Python form: such a kernel is compiled even when kernels run as Python)."""
    names = func.__code__.co_names
    return any(numba_internals.is_intrinsic(func.__globals__.get(name)) for name in names)


class Kernel:
    """A function compiled by numba on first need (see the module), or run as plain Python
    (``ROCKETSIM_JIT=python``, :mod:`rocketsim.jit.settings`).

    Calling it calls the compiled function; every other attribute (``compile``,
    ``signatures``, ``stats``...) is numba's dispatcher's. ``py_func`` is the Python
    function as written.
    """

    def __init__(self, func, options: dict):
        functools.update_wrapper(self, func)
        self.py_func = func
        self._options = options
        self._dispatcher = None
        self._runs = None           # what a call runs: the dispatcher, or py_func

    @property
    def dispatcher(self):
        """numba's dispatcher of this kernel (made, and numba imported, on first use)."""
        if self._dispatcher is None:
            self._dispatcher = numba_internals.dispatcher(self.py_func, self._options)
        return self._dispatcher

    @functools.cached_property
    def python(self) -> bool:
        """Whether this kernel runs as plain Python: kernels run so
        (``ROCKETSIM_JIT=python``), and it calls no intrinsic."""
        return current().python and not _calls_intrinsic(self.py_func)

    @property
    def borrows(self) -> bool:
        """Whether this kernel is compiled without reference counting (``njit(borrows=True)``)."""
        return self._options.get("_nrt") is False

    @property
    def _numba_type_(self):
        return self.dispatcher._numba_type_

    def entry(self, signature: tuple):
        """The compiled entry for the numba types ``signature``, compiled or loaded from the
        cache on first need (waiting for the second process where it has it queued)."""
        if self in BESIDE.kernels:
            BESIDE.wait_for(self, signature)
        return numba_internals.entry(self, signature)

    def __call__(self, *args):
        if self in BESIDE.kernels:          # queued for the second process: see rocketsim.jit.beside
            BESIDE.wait_for(self, numba_internals.numba_types(self, args))
        runs = self._runs
        if runs is None:
            runs = self._runs = self.py_func if self.python else self.dispatcher
        return runs(*args)

    def __getattr__(self, name):
        if name.startswith("__"):
            raise AttributeError(name)
        return getattr(self.dispatcher, name)

    def __repr__(self) -> str:
        return f"<kernel {self.__module__}.{self.__qualname__}>"


def njit(func=None, **options):
    """Compile ``func`` on first need (use as ``@njit`` or ``@njit(inline="always")``);
    ``borrows=True``: without reference counting (see :mod:`rocketsim.jit`)."""
    settings = {**OPTIONS, **options}
    if settings.pop("borrows", False):
        settings["_nrt"] = False
    if func is None:
        return functools.partial(Kernel, options=settings)
    return Kernel(func, settings)


@njit(inline="always")     # small: typed in its callers, no kernel of its own
def copy_into(dst, start, src):
    """Write the 1-D array ``src`` into ``dst[start:start + len(src)]``, element by element.

    What ``dst[start:stop] = src`` does, without its compiled check of the two shapes: that
    check formats numba's error message ("cannot assign slice of shape ..."), whose string
    code is long to compile in each process that first needs it, on a cold cache."""
    for i in range(src.shape[0]):
        dst[start + i] = src[i]
