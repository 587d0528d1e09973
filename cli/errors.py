"""Turn user-input errors into one paragraph on stderr and exit status 2; output
paths that cannot be written are refused before any work is done."""

from __future__ import annotations

import functools
import os
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


def check_folder(path: Path, option: str) -> None:
    """Refuse an output folder ``path`` that cannot be made or written into (a file of
    that name, or above it; no permission) with an :class:`InputError` naming ``option``;
    nothing is created."""
    above = path
    while not above.exists() and above != above.parent:
        above = above.parent
    if not above.is_dir():
        problem = f"{above} is not a folder"
    elif not os.access(above, os.W_OK | os.X_OK):
        problem = f"no permission to write in {above}"
    else:
        return
    raise InputError(f"cannot create the folder {path}: {problem}; nothing was written", field=option)


class _CheckedPath(click.Path):
    """A click path option the command writes to, refused (exit 2, the option named)
    by ``check(path, option)`` before any work is done."""

    def __init__(self, check, **kinds):
        super().__init__(path_type=Path, **kinds)
        self.check = check

    def convert(self, value, param, ctx):
        path = super().convert(value, param, ctx)
        try:
            self.check(path, param.opts[-1] if param is not None else "output")
        except InputError as error:
            self.fail(error.message, param, ctx)
        return path


def output_file() -> click.Path:
    """A file the command writes, checked as :func:`check_writable`."""
    return _CheckedPath(check_writable, dir_okay=False)


def output_folder() -> click.Path:
    """A folder the command writes into, checked as :func:`check_folder`."""
    return _CheckedPath(check_folder, file_okay=False)
