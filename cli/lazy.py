"""What a command module needs from the library at definition time, read on first use.

``rocketsim --help`` imports every command module to list the commands; a
module that imported the simulator (numpy, pydantic models, the compiled
kernels) at its top would make every light command pay for it. So command
modules import the library inside their functions, and an option whose
choices come from the library takes a :class:`LibraryChoice`.
"""

from __future__ import annotations

from typing import Callable, Sequence

import click


class LibraryChoice(click.Choice):
    """A :class:`click.Choice` whose choices are ``read()``, called when first needed
    (to check a value or to print the option's help), not when the command is defined."""

    def __init__(self, read: Callable[[], Sequence[str]], case_sensitive: bool = True):
        self._read = read
        self._choices = None
        super().__init__((), case_sensitive=case_sensitive)

    @property
    def choices(self) -> Sequence[str]:
        if self._choices is None:
            self._choices = tuple(self._read())
        return self._choices

    @choices.setter
    def choices(self, value: Sequence[str]) -> None:
        """click's constructor stores the (empty) choices given to it: ignored."""
