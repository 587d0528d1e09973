"""Quantities in scenario files: SI numbers, or strings with a unit.

A field declared with a dimension accepts a plain number (already SI) or a
string ``"<number> <unit>"`` from the table below, and stores the SI value
(angles in radians). Angles are the exception to "a bare number is SI": a bare
number for an angle is refused, because ``latitude: 28.5`` is almost always
meant in degrees and silently reading it as radians would fly from the wrong
place. Write ``"28.5 deg"`` or ``"0.497 rad"``.

The table is small on purpose; every unit is listed with its factor to SI.
"""

from __future__ import annotations

import math
import re
import typing
from dataclasses import dataclass
from typing import Annotated, Any

from pydantic import BeforeValidator, ConfigDict, WithJsonSchema

from rocketsim.constants import (ATMOSPHERE, AU, CELSIUS_ZERO, DEG, G0, KNOT, NAUTICAL_MILE,
                                 SECONDS_PER_DAY)
from rocketsim.limits import MAX_QUANTITY
from rocketsim.scenario.bounds import document_bounds

# dimension -> {unit spelling: factor to the SI unit}
UNITS: dict[str, dict[str, float]] = {
    "length": {"m": 1.0, "km": 1e3, "cm": 1e-2, "mm": 1e-3, "ft": 0.3048,
               "mi": 1609.344, "nmi": NAUTICAL_MILE, "au": AU},
    "mass": {"kg": 1.0, "g": 1e-3, "t": 1e3, "lb": 0.45359237},
    "time": {"s": 1.0, "ms": 1e-3, "min": 60.0, "h": 3600.0, "d": SECONDS_PER_DAY,
             "day": SECONDS_PER_DAY, "days": SECONDS_PER_DAY},
    "angle": {"rad": 1.0, "deg": DEG, "°": DEG,
              "arcmin": math.pi / 10800.0, "arcsec": math.pi / 648000.0},
    "speed": {"m/s": 1.0, "km/s": 1e3, "km/h": 1 / 3.6, "kn": KNOT, "ft/s": 0.3048},
    "force": {"N": 1.0, "kN": 1e3, "MN": 1e6, "lbf": 4.4482216152605},
    "pressure": {"Pa": 1.0, "hPa": 100.0, "kPa": 1e3, "MPa": 1e6, "bar": 1e5, "mbar": 100.0,
                 "atm": ATMOSPHERE, "psi": 6894.757293168},
    "temperature": {"K": 1.0},        # Celsius is an offset: handled below
    "density": {"kg/m3": 1.0, "kg/m^3": 1.0, "g/cm3": 1000.0},
    "area": {"m2": 1.0, "m^2": 1.0, "cm2": 1e-4},
    "inertia": {"kg m2": 1.0, "kg*m^2": 1.0, "kg m^2": 1.0},
    "angular_rate": {"rad/s": 1.0, "deg/s": DEG, "rpm": 2 * math.pi / 60.0},
    "frequency": {"Hz": 1.0, "kHz": 1e3},
    "specific_impulse": {"s": 1.0},
    "mass_flow": {"kg/s": 1.0},
    "acceleration": {"m/s2": 1.0, "m/s^2": 1.0, "g": G0},
    # C3 (twice the orbital energy per unit mass), as launch windows quote it in km^2/s^2
    "specific_energy": {"m2/s2": 1.0, "m^2/s^2": 1.0, "km2/s2": 1e6, "km^2/s^2": 1e6},
    "dimensionless": {"": 1.0, "%": 0.01},
}

# a value of each dimension as a file writes it, for the schema's examples
EXAMPLES: dict[str, str] = {
    "length": "2.5 m", "mass": "1500 kg", "time": "10 s", "angle": "28.5 deg", "speed": "7.5 km/s",
    "force": "914 kN", "pressure": "101325 Pa", "temperature": "288 K", "density": "1141 kg/m3",
    "area": "0.5 m2", "inertia": "12 kg m2", "angular_rate": "10 deg/s", "frequency": "10 Hz",
    "specific_impulse": "311 s", "mass_flow": "300 kg/s", "acceleration": "40 g",
    "specific_energy": "12 km2/s2", "dimensionless": "0.8",
}
# an example in a field's description: "e.g. '5 deg'"
_EXAMPLE = re.compile(r"e\.g\. '([^']+)'")


@dataclass(frozen=True)
class Dimension:
    """The dimension a quantity field reads (its annotation's marker, for the schema)."""

    name: str

    def text(self) -> str:
        units = ", ".join(u for u in UNITS[self.name] if u)
        how = "a string with one of" if self.name == "angle" else "a number in SI or a string with one of"
        return f"({self.name.replace('_', ' ')}: {how}: {units})"


def _dimension_of(annotation) -> Dimension | None:
    """The :class:`Dimension` marker inside an annotation (through Annotated, Optional, Union)."""
    for meta in getattr(annotation, "__metadata__", ()):
        if isinstance(meta, Dimension):
            return meta
    for arg in typing.get_args(annotation):
        if not isinstance(arg, Dimension):
            found = _dimension_of(arg)
            if found is not None:
                return found
    return None


def document_fields(schema: dict, model) -> None:
    """``json_schema_extra`` of the scenario models: each quantity field's description says
    its dimension and units and the schema gives an example (the description's ``e.g.``,
    else one of its dimension); then its bounds (:func:`document_bounds`)."""
    for name, info in model.model_fields.items():
        prop = schema.get("properties", {}).get(name)
        dimension = next((m for m in info.metadata if isinstance(m, Dimension)), None) \
            or _dimension_of(info.annotation)
        if prop is None or dimension is None:
            continue
        text = prop.get("description", "")
        if f"({dimension.name.replace('_', ' ')}:" not in text:
            prop["description"] = f"{text} {dimension.text()}".strip()
        found = _EXAMPLE.search(text)
        prop.setdefault("examples", [found.group(1) if found else EXAMPLES[dimension.name]])
    document_bounds(schema, model)


# the settings of every scenario model: unknown fields are errors, and so is a number
# that is not finite (nan, inf, or a quantity such as "1e308 km" whose SI value overflows);
# the schema's descriptions name the dimension, units and physical bounds of fields
STRICT = ConfigDict(extra="forbid", frozen=True, allow_inf_nan=False,
                    json_schema_extra=document_fields)

_QUANTITY = re.compile(r"^\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*(.*?)\s*$")


class UnitError(ValueError):
    """A quantity that could not be read; the message says what was expected."""


def parse_quantity(value: Any, dimension: str) -> float:
    """Return the SI value of ``value`` (number or ``"<number> <unit>"``), a finite number."""
    si = _si_value(value, dimension)
    if not math.isfinite(si):
        raise UnitError(f"expected a finite {dimension.replace('_', ' ')}")
    if abs(si) > MAX_QUANTITY:
        raise UnitError(f"{si:g} (SI) is beyond the {MAX_QUANTITY:g} any {dimension.replace('_', ' ')} "
                        "may have")
    return si


def _si_value(value: Any, dimension: str) -> float:
    if isinstance(value, bool):
        raise UnitError(f"expected a {dimension}, got a boolean")
    if isinstance(value, (int, float)):
        if dimension == "angle":
            raise UnitError("an angle needs a unit: write e.g. '28.5 deg' or '0.497 rad'")
        try:
            return float(value)
        except OverflowError:       # an integer of hundreds of digits
            raise UnitError(f"expected a finite {dimension.replace('_', ' ')}, got an integer of "
                            f"{len(str(abs(value)))} digits") from None
    if not isinstance(value, str):
        raise UnitError(f"expected a {dimension} as a number or a string with a unit")
    match = _QUANTITY.match(value)
    if not match:
        raise UnitError(f"expected '<number> <unit>' for a {dimension}, got {value!r}")
    number, unit = float(match.group(1)), match.group(2)
    if dimension == "temperature" and unit in ("C", "°C", "degC"):
        return number + CELSIUS_ZERO
    table = UNITS[dimension]
    if unit not in table:
        if unit == "" and dimension != "angle":
            return number
        known = ", ".join(repr(u) for u in table if u)
        raise UnitError(f"unknown unit {unit!r} for a {dimension}; use one of {known}")
    return number * table[unit]


def quantity(dimension: str, description: str = "") -> Any:
    """A pydantic float type reading ``dimension`` quantities, stored in SI."""
    if dimension not in UNITS:
        raise KeyError(dimension)
    marker = Dimension(dimension)
    schema = {"anyOf": [{"type": "number"}, {"type": "string"}],
              "description": (f"{description} " if description else "") + marker.text()}
    if dimension == "angle":
        schema = {"type": "string", "description": schema["description"]}
    return Annotated[float, BeforeValidator(lambda v: parse_quantity(v, dimension)),
                     WithJsonSchema(schema), marker]


Length = quantity("length")
Mass = quantity("mass")
Duration = quantity("time")
Angle = quantity("angle")
Speed = quantity("speed")
Force = quantity("force")
Pressure = quantity("pressure")
Temperature = quantity("temperature")
Density = quantity("density")
Area = quantity("area")
Inertia = quantity("inertia")
AngularRate = quantity("angular_rate")
Frequency = quantity("frequency")
SpecificImpulse = quantity("specific_impulse")
MassFlow = quantity("mass_flow")
Acceleration = quantity("acceleration")
Fraction = quantity("dimensionless")
