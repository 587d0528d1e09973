"""Errors that reach the user as one clear paragraph and exit status 2.

Anything wrong with what a user gave us (a file, a field, a unit, a step, a
program that raises) is an :class:`InputError`. It carries where the problem
is – file, line, column, field path – and what was expected, and renders as
one paragraph. The command line turns it into exit status 2 with no
traceback; library callers can catch it and read the attributes.
"""

from __future__ import annotations

from pathlib import Path


class InputError(Exception):
    """Bad input from the user: names the file, line, column and field."""

    def __init__(self, message: str, *, file: str | Path | None = None,
                 line: int | None = None, column: int | None = None,
                 field: str | None = None):
        super().__init__(message)
        self.message = message
        self.file = str(file) if file is not None else None
        self.line = line
        self.column = column
        self.field = field

    def __str__(self) -> str:
        where = ""
        if self.file:
            where = self.file
            if self.line is not None:
                where += f":{self.line}"
                if self.column is not None:
                    where += f":{self.column}"
            where += ": "
        field = f"{self.field}: " if self.field else ""
        return f"{where}{field}{self.message}"


class ArgumentError(InputError):
    """A bad argument of a call of the front door (:mod:`rocketsim.api`, :mod:`rocketsim.campaigns`):
    ``field`` is the argument's Python name (``duration``, ``scheduler_file``); the command
    line shows the option that gives it (``--duration``, ``--scheduler-file``) in its place."""

    def __init__(self, message: str, argument: str):
        super().__init__(message, field=argument)


def signal_behind(error: BaseException) -> BaseException:
    """The Ctrl-C, or other exception that is not an :class:`Exception` (a signal
    handler's, a program's CPU budget running out), behind ``error``, else ``error``.

    A signal handler that raises while a compiled kernel is being called
    surfaces as ``SystemError: ... returned a result with an exception set``
    whose cause is the signal's exception, or another such SystemError (a
    kernel that calls back into Python, e.g. numba's unpickling of a constant,
    when the signal lands there): the caller must see the signal.
    """
    cause = error
    while isinstance(cause, SystemError) and cause.__cause__ is not None:
        cause = cause.__cause__
        if not isinstance(cause, Exception):
            return cause
    return error
