"""What every scenario model is built on: :class:`Strict`, the base whose unknown fields are
errors (a misspelt field is named, never ignored; :data:`rocketsim.scenario.units.STRICT`);
the types of a vehicle's figures within the physical bounds of
:mod:`rocketsim.scenario.bounds`; and :func:`field_error`, the located validation error a
model's own check raises."""

from __future__ import annotations

from typing import Annotated

from pydantic import BaseModel
from pydantic_core import InitErrorDetails, PydanticCustomError, ValidationError

from rocketsim.scenario.bounds import BODY_MASS, COUNT, EXTENT, PART_MASS, SIZE
from rocketsim.scenario.units import STRICT, Length, Mass

# a vehicle's figures, within the physical bounds of rocketsim.scenario.bounds
PositiveLength = Annotated[Length, SIZE]
NonNegativeLength = Annotated[Length, EXTENT]
NonNegativeMass = Annotated[Mass, PART_MASS]
PositiveMass = Annotated[Mass, BODY_MASS]
Count = Annotated[int, COUNT]


class Strict(BaseModel):
    """Base of every scenario model: unknown fields are errors."""

    model_config = STRICT


# the error type of a field this file needs although the schema has a default for others
REQUIRED = "required"


def field_error(loc: tuple, message: str, value, kind: str = "vehicle") -> ValidationError:
    """A validation error at ``loc`` (relative to the model raising it).

    Raised from a model validator, pydantic prefixes the model's own location,
    so the loader names the exact field (and its line) of the problem. ``kind``
    :data:`REQUIRED`: the field is needed here and not written (the loader then
    names it, as it does a missing field, at its parent's line).
    """
    return ValidationError.from_exception_data("vehicle", [InitErrorDetails(
        type=PydanticCustomError(kind, message), loc=loc, input=value)])
