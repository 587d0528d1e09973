"""The optional dependencies, by the extra of ``pyproject.toml`` that installs them.

A plain install flies, replays, exports CSV and draws plots. What only some
commands need is an extra (``pip install 'rocketsim[campaign]'``; ``.[test]``
installs them all):

* ``campaign``: Dask distributed (a campaign's runs on a local or a user's cluster)
  and pyarrow (a campaign's ``inputs.parquet`` and ``results.parquet``);
* ``weather``: xarray over netCDF4 (reanalysis and forecast weather files, NetCDF);
* ``parquet``: pyarrow (``rocketsim replay --export parquet``).

Where one is needed and missing, :func:`needs` raises :class:`MissingExtra`: one
line naming what needs it and the pip command, exit status 2 on the command line
(an :class:`~rocketsim.errors.InputError`), and an ``ImportError`` for a library
caller who tests for one.
"""

from __future__ import annotations

import importlib

from rocketsim.errors import InputError

# extra -> the modules it installs (tests/house/test_extras.py checks them against pyproject.toml)
EXTRAS = {
    "campaign": ("distributed", "pyarrow"),
    "weather": ("xarray", "netCDF4"),
    "parquet": ("pyarrow",),
}


class MissingExtra(InputError, ImportError):
    """An optional dependency a command needs is not installed; the message says which
    extra installs it, and how."""


def needs(extra: str, what: str, *modules: str) -> None:
    """Import each of ``modules`` (default: every module of ``extra``), or raise
    :class:`MissingExtra` for the first that cannot be: ``what`` (e.g. "a campaign")
    needs it, and ``pip install 'rocketsim[extra]'`` installs it."""
    for module in modules or EXTRAS[extra]:
        try:
            importlib.import_module(module)
        except ImportError as error:
            raise MissingExtra(f"{what} needs {module}, which is not installed here: "
                               f"pip install 'rocketsim[{extra}]'") from error
