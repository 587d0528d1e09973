"""The names a package exports from its modules, each module imported when one of its
names is first read (PEP 562).

A package's ``__init__`` lists its names and their homes and takes its module
``__getattr__`` and ``__dir__`` from :func:`lazy`: importing the package then costs
nothing but this module, so ``import rocketsim`` and the command line's light
commands do not import what the names they do not use need (numpy, the compiled
kernels, matplotlib).
"""

from __future__ import annotations

import importlib


def lazy(namespace: dict, homes: dict[str, str | tuple[str, str]]) -> tuple:
    """``(__getattr__, __dir__)`` of the module whose globals are ``namespace``: ``homes``
    maps each exported name to the module that defines it, or to ``(module, its name
    there)``. A name read once is kept in ``namespace``. An exported name must not be the
    name of one of the package's own modules: importing that module would bind its name
    to the module first."""

    def __getattr__(name: str):
        home = homes.get(name)
        if home is None:
            raise AttributeError(f"module {namespace['__name__']!r} has no attribute {name!r}")
        module, attribute = home if isinstance(home, tuple) else (home, name)
        value = getattr(importlib.import_module(module), attribute)
        namespace[name] = value
        return value

    def __dir__() -> list[str]:
        return sorted(set(namespace) | set(homes))

    return __getattr__, __dir__
