"""Quantities on the command line, read as the scenario files read them.

``--duration 10s``, ``--duration "10 s"``, ``--step 20ms`` or a bare number in SI:
the parser and the errors of the scenario files (:func:`rocketsim.api.parse_quantity`); a bad unit exits 2
with click's usage error naming the option. An option whose users think in a unit
that is not SI (C3 in km^2/s^2, v-infinity in km/s) refuses a bare number rather
than read ``20`` as 20 m^2/s^2.
"""

from __future__ import annotations

import click

from rocketsim.api import UNITS, UnitError, parse_quantity


class Quantity(click.ParamType):
    """A click option type: a quantity of ``dimension``, stored in SI."""

    def __init__(self, dimension: str, example: str | None = None):
        """``example`` (e.g. ``"20 km2/s2"``): a unit is required, and the error shows this."""
        if dimension not in UNITS:
            raise KeyError(dimension)
        self.dimension = dimension
        self.name = dimension
        self.example = example

    def convert(self, value, param, ctx):
        if isinstance(value, float):
            return value
        if self.example is not None and _bare_number(value):
            self.fail(f"{value!r} needs a unit: write e.g. '{self.example}'", param, ctx)
        try:
            return parse_quantity(value, self.dimension)
        except UnitError as error:
            self.fail(str(error), param, ctx)


def _bare_number(value) -> bool:
    try:
        float(value)
    except (TypeError, ValueError):
        return False
    return True
