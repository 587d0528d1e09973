"""Solid-motor thrust curves from files: RASP ``.eng`` and two-column CSV.

RASP ``.eng`` (G. Harry Stine's RASP program's format, used by
thrustcurve.org, OpenRocket and RocketPy; the format is described at
https://www.thrustcurve.org/info/raspformat.html): lines starting with ``;``
are comments; the first other line is the header

    name diameter_mm length_mm delays propellant_kg total_kg manufacturer

(``delays`` a dash-separated list of ejection delays, ``P`` for plugged; it is
kept as text), then one ``time_s thrust_N`` pair per line, times increasing.
The curve is taken to start from no thrust at ignition: a point ``(0, 0)`` is
put in front when the file's first time is above 0, as RASP does.

CSV: lines ``time_s,thrust_N`` (``;`` or ``#`` comments and a non-numeric
header line allowed). A CSV has no header figures: the motor's diameter,
length and masses must then be given in the vehicle file.

Every problem raises :class:`MotorFileError` naming the file and its line, and
so does a figure beyond the physical bounds of :mod:`rocketsim.scenario.bounds`
(a size, a mass, a thrust, a time).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

from rocketsim.scenario.bounds import BODY_MASS, BURN_TIME, CURVE_THRUST, SIZE


class MotorFileError(ValueError):
    """A thrust-curve file that cannot be read; the message names the file and line."""


@dataclass(frozen=True)
class ThrustCurve:
    """A motor file's contents (SI: m, kg, s, N). Header figures are None for a CSV."""

    points: tuple[tuple[float, float], ...]     # (time s since ignition, thrust N), from (0, 0)
    designation: str = ""
    diameter: float | None = None               # m
    length: float | None = None                 # m
    delays: str = ""
    propellant_mass: float | None = None        # kg
    total_mass: float | None = None             # kg
    manufacturer: str = ""


def read_thrust_curve(path: str | Path) -> ThrustCurve:
    """The thrust curve of a ``.eng`` (RASP) or ``.csv`` file at ``path``."""
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8", errors="replace")
    except OSError as error:
        raise MotorFileError(f"{path}: cannot be read ({error.strerror or error})") from None
    if path.suffix.lower() == ".csv":
        return ThrustCurve(points=_points(path, _csv_rows(path, text)))
    return _eng(path, text)


def _eng(path: Path, text: str) -> ThrustCurve:
    rows = [(n, line.split()) for n, line in enumerate(text.splitlines(), 1)
            if line.strip() and not line.lstrip().startswith(";")]
    if not rows:
        raise MotorFileError(f"{path}: no header line (name diameter_mm length_mm delays "
                             "propellant_kg total_kg manufacturer)")
    n, header = rows[0]
    if len(header) < 7:
        raise MotorFileError(f"{path}, line {n}: the header needs 7 fields (name diameter_mm "
                             f"length_mm delays propellant_kg total_kg manufacturer), got {len(header)}")
    name, diameter, length, delays, propellant, total = header[:6]
    figures = [_number(path, n, value, label) for value, label in (
        (diameter, "diameter_mm"), (length, "length_mm"), (propellant, "propellant_kg"),
        (total, "total_kg"))]
    if any(value <= 0 for value in figures):
        raise MotorFileError(f"{path}, line {n}: diameter, length, propellant and total mass must "
                             "be positive")
    for (value, label), bound, scale in zip(((diameter, "diameter_mm"), (length, "length_mm"),
                                             (propellant, "propellant_kg"), (total, "total_kg")),
                                            (SIZE, SIZE, BODY_MASS, BODY_MASS), (1e-3, 1e-3, 1.0, 1.0)):
        _bounded(path, n, float(value) * scale, label, bound)
    if figures[2] >= figures[3]:
        raise MotorFileError(f"{path}, line {n}: the propellant mass ({figures[2]:g} kg) must be less "
                             f"than the total mass ({figures[3]:g} kg): the case is the difference")
    points = []
    for n, fields in rows[1:]:
        if len(fields) != 2:
            raise MotorFileError(f"{path}, line {n}: expected 'time_s thrust_N', got {len(fields)} fields")
        points.append((n, _number(path, n, fields[0], "time_s"), _number(path, n, fields[1], "thrust_N")))
    return ThrustCurve(points=_points(path, points), designation=name, diameter=figures[0] / 1000.0,
                       length=figures[1] / 1000.0, delays=delays, propellant_mass=figures[2],
                       total_mass=figures[3], manufacturer=" ".join(header[6:]))


def _csv_rows(path: Path, text: str):
    rows = []
    for n, line in enumerate(text.splitlines(), 1):
        stripped = line.strip()
        if not stripped or stripped[0] in ";#":
            continue
        fields = [f.strip() for f in stripped.split(",")]
        if len(fields) != 2:
            raise MotorFileError(f"{path}, line {n}: expected 'time_s,thrust_N', got {len(fields)} fields")
        try:
            rows.append((n, float(fields[0]), float(fields[1])))
        except ValueError:
            if rows:        # only the first line may be a header of names
                raise MotorFileError(f"{path}, line {n}: expected two numbers, got {stripped!r}") from None
    return rows


def _number(path: Path, n: int, text: str, label: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise MotorFileError(f"{path}, line {n}: {label} is not a number ({text!r})") from None
    if not math.isfinite(value):
        raise MotorFileError(f"{path}, line {n}: {label} is not finite ({text!r})")
    return value


def _bounded(path: Path, n: int, value: float, label: str, bound) -> None:
    """Refuse ``value`` (SI) of ``label`` on line ``n`` beyond ``bound`` (a
    :class:`~rocketsim.scenario.bounds.Within`)."""
    try:
        bound.check(value)
    except ValueError as error:
        raise MotorFileError(f"{path}, line {n}: {label} {error} (got {value:g})") from None


def _points(path: Path, rows) -> tuple[tuple[float, float], ...]:
    """The curve from ``(line, time, thrust)`` rows: times increasing, thrusts not negative,
    starting at ``(0, 0)``."""
    if not rows:
        raise MotorFileError(f"{path}: no (time, thrust) points")
    if rows[0][1] == 0.0 and rows[0][2] != 0.0:
        raise MotorFileError(f"{path}, line {rows[0][0]}: the curve must start from no thrust at "
                             "ignition (a first point (0, T) jumps at an instant the step cannot split)")
    points = [] if rows[0][1] == 0.0 else [(0.0, 0.0)]
    previous = 0.0 if points else -math.inf
    for n, t, thrust in rows:
        if not math.isfinite(t) or not math.isfinite(thrust):
            raise MotorFileError(f"{path}, line {n}: time and thrust must be finite")
        if t < 0.0 or t <= previous:
            raise MotorFileError(f"{path}, line {n}: times must start at 0 or later and increase "
                                 f"(got {t:g} s after {previous:g} s)")
        if thrust < 0.0:
            raise MotorFileError(f"{path}, line {n}: thrust cannot be negative (got {thrust:g} N)")
        _bounded(path, n, t, "time_s", BURN_TIME)
        _bounded(path, n, thrust, "thrust_N", CURVE_THRUST)
        points.append((t, thrust))
        previous = t
    if len(points) < 2 or not any(thrust > 0.0 for _, thrust in points):
        raise MotorFileError(f"{path}: the curve has no thrust")
    return tuple(points)
