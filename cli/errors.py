"""Turn user-input errors into one paragraph on stderr and exit status 2."""

from __future__ import annotations

import functools
import sys

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
