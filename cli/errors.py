"""Turn user-input errors into one paragraph on stderr and exit status 2; output
paths that cannot be written are refused before any work is done, and the system's
errors while writing them (a full disk, a device, no permission) are one located
line and exit status 2 as well."""

from __future__ import annotations

import functools
import os
import stat
import sys
from pathlib import Path

import click

from rocketsim.errors import ArgumentError, InputError

# a front door's argument -> the parameter of the command that gives it, where their names differ
ALIASES = {"directory": "output", "telemetry": "output", "live.port": "port", "live.host": "host",
           "live.warp": "warp"}


def reports_input_errors(command):
    """Decorate a click callback: an :class:`InputError` exits 2, no traceback; so does an
    OSError (the system refusing a read or a write), naming its file, or else the
    outputs the command was writing (:func:`check_writable`, :func:`check_folder`)."""

    @functools.wraps(command)
    def wrapper(*args, **kwargs):
        try:
            return command(*args, **kwargs)
        except InputError as error:
            if isinstance(error, ArgumentError):
                error.field = option_of(error.field)
            click.echo(f"error: {error}", err=True)
            sys.exit(2)
        except OSError as error:
            click.echo(f"error: {system_error(error)}", err=True)
            sys.exit(2)

    return wrapper


def option_of(argument: str) -> str:
    """The running command's option (``--scheduler-file``) or argument (``DIR``) that gives
    the front door's ``argument`` (``scheduler_file``); ``argument`` if none does."""
    context = click.get_current_context(silent=True)
    if context is None:
        return argument
    params = {param.name: param for param in context.command.params}
    param = params.get(argument) or params.get(ALIASES.get(argument, ""))
    if param is None:
        return argument
    if isinstance(param, click.Argument):
        return param.human_readable_name
    return max(param.opts, key=len)


def system_error(error: OSError) -> str:
    """One line for an OSError: what failed, on which file (the command's checked outputs
    when the error names none)."""
    what = error.strerror or str(error) or type(error).__name__
    if error.filename is not None:
        return f"{error.filename}: {what}"
    context = click.get_current_context(silent=True)
    outputs = context.meta.get(_OUTPUTS, []) if context is not None else []
    if not outputs:
        return what
    return f"{what}, while writing " + ", ".join(f"{path} ({option})" for option, path in outputs)


_OUTPUTS = "rocketsim.outputs"      # click context meta: the (option, path) a command writes


def _writes(path: Path, option: str) -> None:
    context = click.get_current_context(silent=True)
    if context is not None:         # its meta is shared by the command's nested contexts
        context.meta.setdefault(_OUTPUTS, []).append((option, path))


def check_writable(path: Path, option: str) -> None:
    """Refuse an output ``path`` that cannot be created (no such folder, no permission, a
    folder of that name, a FIFO, a device or a socket: writing one could block or fail
    after the work) with an :class:`InputError` naming ``option``, before any work is
    done; a file the check creates is removed again, an existing one left as it is."""
    _writes(path, option)
    try:
        mode = path.stat().st_mode
    except OSError:
        mode = None
    if mode is not None and not stat.S_ISREG(mode) and not stat.S_ISDIR(mode):
        kind = ("a FIFO" if stat.S_ISFIFO(mode) else "a device" if stat.S_ISCHR(mode) or stat.S_ISBLK(mode)
                else "a socket" if stat.S_ISSOCK(mode) else "not a regular file")
        raise InputError(f"cannot write {path}: it is {kind}, not a file; nothing was written",
                         field=option)
    existed = mode is not None
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
    _writes(path, option)
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
