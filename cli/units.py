"""Quantities on the command line, read as the scenario files read them.

``--duration 10s``, ``--duration "10 s"``, ``--step 20ms`` or a bare number in SI:
the parser and the errors of :mod:`rocketsim.scenario.units`; a bad unit exits 2
with click's usage error naming the option.
"""

from __future__ import annotations

import click

from rocketsim.scenario.units import UNITS, UnitError, parse_quantity


class Quantity(click.ParamType):
    """A click option type: a quantity of ``dimension``, stored in SI."""

    def __init__(self, dimension: str):
        if dimension not in UNITS:
            raise KeyError(dimension)
        self.dimension = dimension
        self.name = dimension

    def convert(self, value, param, ctx):
        if isinstance(value, float):
            return value
        try:
            return parse_quantity(value, self.dimension)
        except UnitError as error:
            self.fail(str(error), param, ctx)
