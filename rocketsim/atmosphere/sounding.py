"""Measured soundings: the University of Wyoming text format, and the same columns from CSV/YAML.

A sounding is read into a :class:`Sounding` of SI arrays, one row per level,
bottom up. The columns keep the Wyoming names and units:

=======  ======  ===================================  ==========
column   unit    meaning                              needed
=======  ======  ===================================  ==========
PRES     hPa     pressure                             yes
HGHT     m       geopotential height above sea level  yes
TEMP     °C      temperature                          yes
DWPT     °C      dew point                            no
RELH     %       relative humidity                    no
MIXR     g/kg    water-vapour mixing ratio            no
DRCT     deg     direction the wind blows FROM        no (with SKNT)
SKNT     knot    wind speed                           no (with DRCT)
=======  ======  ===================================  ==========

Humidity comes from MIXR if present, else DWPT, else RELH (with TEMP), else
the air is dry. In the Wyoming format a level without a temperature (a
wind-only level, or a mandatory level below the ground) is skipped; a level
missing only humidity or wind takes those from its neighbours. Every error
names the file, the line and the column.
"""

from __future__ import annotations

import csv
import io
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import yaml

from rocketsim.constants import CELSIUS_ZERO, KNOT, WATER_AIR_MOLAR_RATIO
from rocketsim.errors import InputError
from rocketsim.limits import MAX_TEXT_BYTES, compose_yaml, read_bounded

COLUMNS = ("PRES", "HGHT", "TEMP", "DWPT", "RELH", "MIXR", "DRCT", "SKNT")
REQUIRED = ("PRES", "HGHT", "TEMP")
# Plausible ranges, in the file's units; a value outside is refused.
PLAUSIBLE = {"PRES": (1.0, 1100.0), "HGHT": (-500.0, 60_000.0), "TEMP": (-120.0, 60.0),
             "DWPT": (-130.0, 60.0), "RELH": (0.0, 100.5), "MIXR": (0.0, 40.0),
             "DRCT": (0.0, 360.0), "SKNT": (0.0, 300.0)}


@dataclass(frozen=True)
class Sounding:
    """Levels bottom up, SI: heights (m), pressure (Pa), temperature (K),
    water-vapour mixing ratio (kg/kg), wind speed (m/s) and the direction it
    blows from (rad, clockwise from north).

    ``geopotential`` says whether the heights are geopotential (radiosondes)
    or already geometric (synthetic days).
    """

    height: np.ndarray
    pressure: np.ndarray
    temperature: np.ndarray
    mixing_ratio: np.ndarray
    wind_speed: np.ndarray
    wind_from: np.ndarray
    geopotential: bool = True
    source: str = ""


def saturation_vapour_pressure(t_celsius):
    """Saturation vapour pressure over water (hPa) at ``t_celsius`` (°C); Bolton (1980) eq. 10."""
    t = np.asarray(t_celsius, dtype=float)
    return 6.112 * np.exp(17.67 * t / (t + 243.5))


def mixing_ratio_from_vapour(e_hpa, p_hpa):
    """Mixing ratio (kg/kg) of vapour pressure ``e`` in air at pressure ``p`` (both hPa)."""
    return WATER_AIR_MOLAR_RATIO * e_hpa / (p_hpa - e_hpa)


def _fill(values, heights):
    """Fill NaNs by linear interpolation in height (NaN everywhere -> None)."""
    ok = np.isfinite(values)
    if not ok.any():
        return None
    return np.interp(heights, heights[ok], values[ok])


def from_columns(columns: dict, lines: dict | None, source: str = "",
                 prefix: str = "", header_line: int | None = None) -> Sounding:
    """A :class:`Sounding` from file-unit columns (lists of floats, NaN = blank).

    ``lines[name][i]`` is the line (1-based) of cell ``i`` of column ``name``
    for error messages (``lines=None``: cells are named ``NAME[i]`` instead,
    for columns written inline in a scenario); ``source`` names the file and
    ``header_line`` the line naming the columns (for a missing column).
    """
    def where(name, i):
        if lines is None:
            return {"field": f"{prefix}{name}[{i}]"}
        return {"line": lines[name][i], "field": name}

    for name in REQUIRED:
        if name not in columns:
            raise InputError(f"the sounding has no {name} column (needed: "
                             f"{', '.join(REQUIRED)})", file=source or None, line=header_line,
                             field=prefix + name)
    if ("DRCT" in columns) != ("SKNT" in columns):
        missing = "SKNT" if "DRCT" in columns else "DRCT"
        raise InputError(f"wind needs both DRCT and SKNT; {missing} is missing",
                         file=source or None, line=header_line, field=prefix + missing)
    n = len(columns["HGHT"])
    for name, values in columns.items():
        if len(values) != n:
            raise InputError(f"column {name} has {len(values)} values, HGHT has {n}",
                             file=source or None, field=name)
    cols = {k: np.asarray(v, dtype=float) for k, v in columns.items()}
    for name, values in cols.items():
        low, high = PLAUSIBLE[name]
        for i, v in enumerate(values):
            if name in REQUIRED and not math.isfinite(v):
                raise InputError(f"{name} is missing on this level", file=source or None,
                                 **where(name, i))
            if math.isfinite(v) and not low <= v <= high:
                raise InputError(f"implausible {name} {v:g} (expected {low:g} to {high:g})",
                                 file=source or None, **where(name, i))
    if n < 2:
        raise InputError("a sounding needs at least two levels", file=source or None)
    h, p = cols["HGHT"], cols["PRES"]
    for i in range(1, n):
        if not h[i] > h[i - 1]:
            raise InputError(f"heights out of order: {h[i]:g} m after {h[i - 1]:g} m "
                             "(levels must go up)", file=source or None, **where("HGHT", i))
        if not p[i] < p[i - 1]:
            raise InputError(f"pressure {p[i]:g} hPa does not fall below the level under it "
                             f"({p[i - 1]:g} hPa)", file=source or None, **where("PRES", i))
    t_c = cols["TEMP"]
    w = None
    if "MIXR" in cols:
        w = _fill(cols["MIXR"] / 1000.0, h)
    if w is None and "DWPT" in cols:
        td = _fill(cols["DWPT"], h)
        if td is not None:
            w = mixing_ratio_from_vapour(saturation_vapour_pressure(td), p)
    if w is None and "RELH" in cols:
        rh = _fill(cols["RELH"], h)
        if rh is not None:
            w = mixing_ratio_from_vapour(rh / 100.0 * saturation_vapour_pressure(t_c), p)
    speed = direction = None
    if "SKNT" in cols:
        speed = _fill(cols["SKNT"] * KNOT, h)
        # Interpolate the direction as a vector so 350° and 10° meet at north.
        rad = np.radians(cols["DRCT"])
        s, c = _fill(np.sin(rad), h), _fill(np.cos(rad), h)
        if s is not None:
            direction = np.mod(np.arctan2(s, c), 2 * np.pi)
    zeros = np.zeros(n)
    return Sounding(h.copy(), p * 100.0, t_c + CELSIUS_ZERO, zeros if w is None else w,
                    zeros if speed is None else speed,
                    zeros if direction is None else direction, True, source)


def _number(cell: str, source: str, line: int, name: str) -> float:
    try:
        value = float(cell)
    except ValueError:
        raise InputError(f"{name} is not a number: {cell.strip()!r}", file=source,
                         line=line, field=name) from None
    if not math.isfinite(value):
        raise InputError(f"{name} is not a finite number: {cell.strip()!r}", file=source,
                         line=line, field=name)
    return value


def parse_wyoming(text: str, source: str = "<sounding>") -> Sounding:
    """Read the University of Wyoming text listing (fixed 7-character columns)."""
    lines = text.splitlines()
    header = next((i for i, ln in enumerate(lines) if ln.split()[:2] == ["PRES", "HGHT"]), None)
    if header is None:
        raise InputError("no 'PRES HGHT ...' header line: not a University of Wyoming sounding",
                         file=source)
    names = lines[header].split()
    start = header + 1
    while start < len(lines) and (not lines[start].strip() or lines[start].strip()[0] in "-h"
                                  or lines[start].split()[0] == "hPa"):
        start += 1
    columns = {n: [] for n in names if n in COLUMNS}
    where = {n: [] for n in columns}
    for k in range(start, len(lines)):
        row = lines[k]
        if not row.strip() or row.lstrip().startswith(("<", "Station")):
            break
        if row.strip().startswith("---"):
            continue
        cells = [row[7 * j:7 * j + 7] for j in range(len(names))]
        if len(row.rstrip()) > 7 * len(names):
            raise InputError("line longer than the header's columns", file=source, line=k + 1)
        by_name = dict(zip(names, cells))
        if not by_name.get("TEMP", "").strip():
            continue          # wind-only level or a mandatory level below the ground
        for name in columns:
            cell = by_name[name]
            columns[name].append(_number(cell, source, k + 1, name) if cell.strip() else math.nan)
            where[name].append(k + 1)
    return from_columns(columns, where, source, header_line=header + 1)


def parse_csv(text: str, source: str = "<sounding>") -> Sounding:
    """Read a CSV whose header names Wyoming columns (blank cell = no value)."""
    reader = csv.reader(io.StringIO(text))
    rows = [(i + 1, r) for i, r in enumerate(reader) if r and any(c.strip() for c in r)]
    if not rows:
        raise InputError("the sounding file is empty", file=source)
    head_line, head = rows[0]
    names = [c.strip().upper() for c in head]
    for name in names:
        if name not in COLUMNS:
            raise InputError(f"unknown column {name!r} (known: {', '.join(COLUMNS)})",
                             file=source, line=head_line, field=name)
    columns = {n: [] for n in names}
    where = {n: [] for n in names}
    for line, row in rows[1:]:
        if len(row) != len(names):
            raise InputError(f"{len(row)} cells, the header has {len(names)}", file=source,
                             line=line)
        for name, cell in zip(names, row):
            columns[name].append(_number(cell, source, line, name) if cell.strip() else math.nan)
            where[name].append(line)
    return from_columns(columns, where, source, header_line=head_line)


def parse_yaml(text: str, source: str = "<sounding>") -> Sounding:
    """Read YAML: a mapping of column name to a list of values (optionally under ``columns:``)."""
    root = compose_yaml(text, source)
    if isinstance(root, yaml.MappingNode):
        for key, value in root.value:
            if key.value == "columns":
                root = value
                break
    if not isinstance(root, yaml.MappingNode):
        raise InputError("expected a mapping of column names to lists of values", file=source)
    columns, where = {}, {}
    for key, value in root.value:
        name = str(key.value).upper()
        if name not in COLUMNS:
            raise InputError(f"unknown column {name!r} (known: {', '.join(COLUMNS)})",
                             file=source, line=key.start_mark.line + 1, field=name)
        if not isinstance(value, yaml.SequenceNode):
            raise InputError("expected a list of values", file=source,
                             line=value.start_mark.line + 1, field=name)
        columns[name], where[name] = [], []
        for item in value.value:
            line = item.start_mark.line + 1
            if not isinstance(item, yaml.ScalarNode):
                raise InputError("expected a number", file=source, line=line, field=name)
            blank = item.value in ("", "~", "null") and item.tag.endswith("null")
            columns[name].append(math.nan if blank else _number(item.value, source, line, name))
            where[name].append(line)
    return from_columns(columns, where, source, header_line=root.start_mark.line + 1)


def read_sounding(path: str | Path) -> Sounding:
    """Read a sounding file: ``.csv``, ``.yaml``/``.yml``, else the Wyoming text format."""
    path = Path(path)
    data = read_bounded(path, MAX_TEXT_BYTES, "sounding")
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as error:
        raise InputError(f"cannot read the sounding ({error})", file=path) from None
    suffix = path.suffix.lower()
    if suffix == ".csv":
        return parse_csv(text, str(path))
    if suffix in (".yaml", ".yml"):
        return parse_yaml(text, str(path))
    return parse_wyoming(text, str(path))
