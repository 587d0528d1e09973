"""Every environment variable the kernels' compiling reads, read here and only here.

==========================  =================================================================
``ROCKETSIM_JIT``           ``compiled`` (the default): kernels run as numba's machine code;
                            ``python``: every kernel runs as the plain Python function it is
                            written as, to step through it in a debugger or read a Python
                            traceback from inside it (see :mod:`rocketsim.jit`).
``ROCKETSIM_CACHE_DIR``     the folder below which compiled kernels are cached, in a folder
                            per source (:func:`rocketsim.jit.cache.cache_dir`); default
                            ``$XDG_CACHE_HOME/rocketsim``.
``XDG_CACHE_HOME``          the user's cache folder (the XDG base directory specification);
                            default ``~/.cache``.
``NUMBA_CACHE_DIR``         numba's own: if set, the cache folder itself, with no folder per
                            source (clear it when rocketsim changes).
``NUMBA_OPT``               numba's own: LLVM's optimisation level of the kernels; unset, the
                            kernels are optimised at :data:`OPT_LEVEL`.
``ROCKETSIM_COMPILE_BESIDE`` ``1``: on a cold cache a second process compiles the compiled runs
                            a flight will call while this one compiles the rest
                            (:mod:`rocketsim.jit.beside`); default ``0``, off.
==========================  =================================================================

:func:`current` reads them once, when a kernel is first called or compiled
(inside a command, whose error handling reports a wrong value as a user's
error), so a process's kernels all run one way; :func:`read` reads them from
any mapping.
numba reads its other ``NUMBA_*`` variables itself (``NUMBA_CPU_NAME=generic``
compiles for any CPU of the architecture); ``NUMBA_DISABLE_JIT`` is not for
rocketsim's kernels, which it cannot run: the telemetry's framing calls a
machine-code intrinsic that has no Python form (``ROCKETSIM_JIT=python`` keeps
that one kernel compiled).
"""

from __future__ import annotations

import functools
import os
from dataclasses import dataclass
from typing import Mapping

from rocketsim.errors import InputError

COMPILED, PYTHON = "compiled", "python"
OPT_LEVEL = 1       # LLVM's optimisation level of the kernels, unless NUMBA_OPT is set


@dataclass(frozen=True)
class Settings:
    """The kernels' settings as the environment gives them (see the module)."""

    mode: str                   # COMPILED or PYTHON
    cache_root: str             # the folder below which each source's kernels are cached
    numba_cache_dir: str | None # NUMBA_CACHE_DIR: the cache folder itself, if set
    opt_level: str              # LLVM's optimisation level, as numba's NUMBA_OPT spells it
    opt_from_numba: bool        # whether NUMBA_OPT set it (numba then applies it itself)
    compile_beside: bool        # whether a cold cache's compiled runs are compiled in a second process

    @property
    def python(self) -> bool:
        """Whether kernels run as plain Python."""
        return self.mode == PYTHON


def _switch(environ: Mapping[str, str], name: str) -> bool:
    value = environ.get(name, "").strip()
    if value in ("", "0"):
        return False
    if value == "1":
        return True
    raise InputError(f"{value!r} is not a switch: expected 1 (on) or 0 (off)", field=name)


def read(environ: Mapping[str, str] = os.environ) -> Settings:
    """The settings given by ``environ`` (default: this process's environment); a value
    that names no setting is an :class:`~rocketsim.errors.InputError` naming the variable."""
    mode = environ.get("ROCKETSIM_JIT", "").strip().lower() or COMPILED
    if mode not in (COMPILED, PYTHON):
        raise InputError(f"{mode!r} is not a way to run the kernels: expected {COMPILED!r} "
                         f"(numba's machine code, the default) or {PYTHON!r} (plain Python, "
                         "to debug a kernel)", field="ROCKETSIM_JIT")
    home = environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return Settings(
        mode=mode,
        cache_root=environ.get("ROCKETSIM_CACHE_DIR") or os.path.join(home, "rocketsim"),
        numba_cache_dir=environ.get("NUMBA_CACHE_DIR") or None,
        opt_level=environ.get("NUMBA_OPT") or str(OPT_LEVEL),
        opt_from_numba=bool(environ.get("NUMBA_OPT")),
        compile_beside=_switch(environ, "ROCKETSIM_COMPILE_BESIDE"),
    )


@functools.cache
def current() -> Settings:
    """This process's settings, read from its environment on first need (see the module)."""
    return read()
