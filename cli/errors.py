"""Turn user-input errors into one paragraph on stderr and exit status 2."""

from __future__ import annotations

import functools
import sys
from pathlib import Path

import click

from rocketsim.errors import InputError


def reports_input_errors(command):
    """Decorate a click callback: an :class:`InputError` exits 2, no traceback."""

    @functools.wraps(command)
    def wrapper(*args, **kwargs):
        try:
            return command(*args, **kwargs)
        except InputError as error:
            click.echo(f"error: {error}", err=True)
            sys.exit(2)

    return wrapper


def check_writable(path: Path, option: str) -> None:
    """Refuse an output ``path`` that cannot be created (no such folder, no permission, a
    folder of that name) with an :class:`InputError` naming ``option``, before any work
    is done; a file the check creates is removed again, an existing one left as it is."""
    existed = path.exists()
    try:
        with open(path, "ab"):
            pass
    except OSError as error:
        raise InputError(f"cannot create {path}: {error.strerror or error}; nothing was written",
                         field=option) from None
    if not existed:
        path.unlink()
