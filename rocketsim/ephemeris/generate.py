"""Generate the truncated VSOP87D and ELP2000-82B coefficient tables.

Run from the repository root::

    python -m rocketsim.ephemeris.generate [DATA_DIR]

``DATA_DIR`` defaults to ``../shared/data`` relative to the repository root
and must hold ``vsop87d/earth.txt``, ``vsop87d/mars.txt`` and
``elp2000-82b/main_{longitude,latitude,distance}.txt`` (the full series, see
that folder's README). The full files are never copied into the project: this
script reads them, truncates them and writes ``_tables.py`` beside itself,
which the library imports (no data file is read at run time).

Truncation rule
---------------
For each coordinate (VSOP87D ``L``, ``B``, ``R``; ELP ``longitude``,
``latitude``, ``distance``) the terms are sorted by their *weight* and the
smallest are dropped for as long as the sum of the dropped weights stays at
or below a bound:

* VSOP87D: a term ``A t^alpha cos(B + C t)`` weighs ``|A| * T_SPAN^alpha``,
  ``T_SPAN = 0.1`` Julian millennium (the largest ``|t|`` of the validity
  span 1950-2100 is 2100, t = +0.1), which bounds its contribution over the
  span. Bound: ``VSOP_BOUND`` = 4e-6 in each coordinate's own unit (radians
  for ``L`` and ``B``, au for ``R``; 4e-6 au is 598 km): the dropped terms
  can move ``L``, ``B`` or ``R`` by at most that much over the span. The
  actual error is smaller because the dropped terms do not all peak
  together: at most 265 km for the Earth and 252 km for Mars over 1950-2100
  (sampled every 10 days; ``tests/unit/ephemeris/test_ephemeris_vsop87.py`` checks < 300 km).
* ELP2000-82B: the amplitudes are constants (the eccentricity factor ``E`` is
  within 0.04 % of 1 over the span), so a term weighs ``|A|``. Bounds:
  ``ELP_BOUND_ARCSEC`` = 0.5 arcsec in longitude and latitude and
  ``ELP_BOUND_KM`` = 1 km in distance; measured errors over 1950-2100
  (every 10 days): 0.15", 0.15" and 0.31 km.

These bounds keep 204 terms for the Earth, 793 for Mars and 239/202/156 for
the Moon (near the seed description's 198, 787 and 235/198/154; see
docs/physics.md#ephemerides); the counts are printed and written into the
generated module.
"""

from __future__ import annotations

import sys
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from rocketsim.ephemeris.layouts import prepare_elp, prepare_vsop

T_SPAN = 0.1                 # Julian millennia from J2000: 2100.0, the span's far end
VSOP_BOUND = 4.0e-6          # bound on the dropped amplitudes: rad (L, B), au (R)
ELP_BOUND_ARCSEC = 0.5       # bound on the dropped amplitudes, longitude and latitude
ELP_BOUND_KM = 1.0           # bound on the dropped amplitudes, distance

REPO_ROOT = Path(__file__).resolve().parents[2]
DEFAULT_DATA = REPO_ROOT.parent / "shared" / "data"
OUTPUT = Path(__file__).resolve().parent / "_tables.py"

VSOP_COORDS = "LBR"
ELP_FILES = ("main_longitude.txt", "main_latitude.txt", "main_distance.txt")


@dataclass(frozen=True)
class VsopSeries:
    """Flat VSOP87D series: term k is ``A[k] t^power[k] cos(B[k] + C[k] t)``
    added to coordinate ``coord[k]`` (0 = L rad, 1 = B rad, 2 = R au)."""

    coord: np.ndarray
    power: np.ndarray
    A: np.ndarray
    B: np.ndarray
    C: np.ndarray


@dataclass(frozen=True)
class ElpSeries:
    """Flat ELP2000-82B main problem: term k adds ``A[k] * trig(arg)`` to
    coordinate ``coord[k]`` (0 = longitude arcsec, sine; 1 = latitude arcsec,
    sine; 2 = distance km, cosine), ``arg = i[k] . (D, l', l, F)``."""

    coord: np.ndarray
    mult: np.ndarray     # (n, 4) integers multiplying D, l', l, F
    A: np.ndarray


def read_vsop(path: Path) -> VsopSeries:
    """Parse a full VSOP87D file of ``../shared/data/vsop87d``."""
    coord, power, a, b, c = [], [], [], [], []
    for number, line in enumerate(Path(path).read_text().splitlines(), 1):
        if not line.strip() or line.startswith("#"):
            continue
        name, *values = line.split()
        if len(name) != 2 or name[0] not in VSOP_COORDS or len(values) != 3:
            raise ValueError(f"{path}:{number}: not a VSOP87D term: {line!r}")
        coord.append(VSOP_COORDS.index(name[0]))
        power.append(int(name[1]))
        a.append(float(values[0]))
        b.append(float(values[1]))
        c.append(float(values[2]))
    return VsopSeries(np.array(coord, np.int64), np.array(power, np.int64),
                      np.array(a), np.array(b), np.array(c))


def read_elp(folder: Path) -> ElpSeries:
    """Parse the three ELP2000-82B main-problem files of ``folder``."""
    coord, mult, a = [], [], []
    for index, name in enumerate(ELP_FILES):
        path = Path(folder) / name
        for number, line in enumerate(path.read_text().splitlines(), 1):
            if not line.strip() or line.startswith("#"):
                continue
            fields = line.split()
            if len(fields) < 5:
                raise ValueError(f"{path}:{number}: not an ELP term: {line!r}")
            coord.append(index)
            mult.append([int(f) for f in fields[:4]])
            a.append(float(fields[4]))
    return ElpSeries(np.array(coord, np.int64), np.array(mult, np.int64).reshape(-1, 4),
                     np.array(a))


def _keep_mask(coord: np.ndarray, weight: np.ndarray, bounds) -> np.ndarray:
    """Per coordinate, drop the smallest weights while their sum <= bound."""
    keep = np.ones(len(weight), bool)
    for c, bound in enumerate(bounds):
        index = np.flatnonzero(coord == c)
        order = index[np.argsort(weight[index], kind="stable")]
        dropped = np.searchsorted(np.cumsum(weight[order]), bound, side="right")
        keep[order[:dropped]] = False
    return keep


def truncate_vsop(series: VsopSeries, bound: float = VSOP_BOUND) -> VsopSeries:
    """The VSOP87D truncation rule of this module's docstring."""
    weight = np.abs(series.A) * T_SPAN ** series.power
    keep = _keep_mask(series.coord, weight, (bound,) * 3)
    return VsopSeries(*(getattr(series, f)[keep] for f in ("coord", "power", "A", "B", "C")))


def truncate_elp(series: ElpSeries, bound_arcsec: float = ELP_BOUND_ARCSEC,
                 bound_km: float = ELP_BOUND_KM) -> ElpSeries:
    """The ELP2000-82B truncation rule of this module's docstring."""
    keep = _keep_mask(series.coord, np.abs(series.A), (bound_arcsec, bound_arcsec, bound_km))
    return ElpSeries(series.coord[keep], series.mult[keep], series.A[keep])


def _array(values, dtype="float") -> str:
    if dtype == "int":
        body = ", ".join(str(int(v)) for v in values)
        return f"np.array([{body}], dtype=np.int64)"
    body = ",\n    ".join(repr(float(v)) for v in values)
    return f"np.array([\n    {body},\n])"


def _recipe(layout) -> str:
    """Source of a series' :func:`~rocketsim.ephemeris.sincos.sum_recipe` (the last four
    fields of its ``layouts.VsopLayout``/``ElpLayout``): a tuple of four int64 arrays."""
    return "(\n" + "".join(f"    {_array(a, 'int')},\n" for a in layout[-4:]) + ")"


def render(vsop: dict[str, VsopSeries], elp: ElpSeries, full_counts: dict) -> str:
    """Source text of the generated tables module."""
    out = [
        '"""Truncated VSOP87D and ELP2000-82B coefficient tables. GENERATED FILE.',
        "",
        "Written by ``python -m rocketsim.ephemeris.generate`` from the full series",
        "(Bretagnon & Francou 1988, IMCCE VSOP87D.ear/.mar; Chapront-Touze &",
        "Chapront, ELP2000-82B files ELP01-ELP03) by the truncation rule stated in",
        "``rocketsim/ephemeris/generate.py``. Do not edit by hand.",
        '"""',
        "",
        "import numpy as np",
        "",
        f"T_SPAN = {T_SPAN!r}  # Julian millennia",
        f"VSOP_BOUND = {VSOP_BOUND!r}",
        f"ELP_BOUND_ARCSEC = {ELP_BOUND_ARCSEC!r}",
        f"ELP_BOUND_KM = {ELP_BOUND_KM!r}",
        f"FULL_COUNTS = {full_counts!r}",
        "",
    ]
    for body, s in vsop.items():
        name = body.upper()
        counts = [int(np.sum(s.coord == c)) for c in range(3)]
        out.append(f"# {name}: {len(s.A)} terms kept (L, B, R: {counts})")
        out.append(f"{name}_COORD = {_array(s.coord, 'int')}")
        out.append(f"{name}_POWER = {_array(s.power, 'int')}")
        for field in ("A", "B", "C"):
            out.append(f"{name}_{field} = {_array(getattr(s, field))}")
        out.append("")
    counts = [int(np.sum(elp.coord == c)) for c in range(3)]
    out.append(f"# MOON: {len(elp.A)} terms kept (longitude, latitude, distance: {counts})")
    out.append(f"MOON_COORD = {_array(elp.coord, 'int')}")
    out.append(f"MOON_MULT = {_array(elp.mult.ravel(), 'int')}.reshape(-1, 4)")
    out.append(f"MOON_A = {_array(elp.A)}")
    out.append("")
    out.append("# Each series' sum_recipe (direct, derived, pair_a, pair_b) for its layout")
    out.append("# (rocketsim.ephemeris.layouts): worked out here, not at every import.")
    for body, s in vsop.items():
        out.append(f"{body.upper()}_RECIPE = {_recipe(prepare_vsop(s.coord, s.power, s.A, s.B, s.C))}")
    out.append(f"MOON_RECIPE = {_recipe(prepare_elp(elp.coord, elp.mult, elp.A))}")
    out.append("")
    return "\n".join(out)


def load_full(data: Path = DEFAULT_DATA) -> tuple[dict[str, VsopSeries], ElpSeries]:
    """The full series from ``data`` (for the generator, tests and benchmark)."""
    data = Path(data)
    vsop = {body: read_vsop(data / "vsop87d" / f"{body}.txt") for body in ("earth", "mars")}
    return vsop, read_elp(data / "elp2000-82b")


def prepared_full(data: Path = DEFAULT_DATA):
    """The full series laid out for ``solar_system.heliocentric_states``:
    ``(earth, mars, moon)``. For the tests and the benchmark, which measure
    the truncation against them."""
    full_vsop, full_elp = load_full(data)
    earth, mars = (prepare_vsop(s.coord, s.power, s.A, s.B, s.C)
                   for s in (full_vsop["earth"], full_vsop["mars"]))
    return earth, mars, prepare_elp(full_elp.coord, full_elp.mult, full_elp.A)


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    if len(argv) > 1 or (argv and argv[0] in ("-h", "--help")):
        print(__doc__)
        return 0 if argv and argv[0] in ("-h", "--help") else 2
    data = Path(argv[0]) if argv else DEFAULT_DATA
    full_vsop, full_elp = load_full(data)
    vsop = {body: truncate_vsop(s) for body, s in full_vsop.items()}
    elp = truncate_elp(full_elp)
    full_counts = {body: len(s.A) for body, s in full_vsop.items()}
    full_counts["moon"] = [int(np.sum(full_elp.coord == c)) for c in range(3)]
    OUTPUT.write_text(render(vsop, elp, full_counts))
    for body, s in vsop.items():
        print(f"{body}: kept {len(s.A)} of {full_counts[body]} terms")
    print("moon: kept", [int(np.sum(elp.coord == c)) for c in range(3)],
          "of", full_counts["moon"], "terms (longitude, latitude, distance)")
    print(f"wrote {OUTPUT}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
