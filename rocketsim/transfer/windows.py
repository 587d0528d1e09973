"""Launch windows: the optima of a porkchop plot of Lambert arcs, refined.

Over a departure x arrival grid of transfer arcs (:func:`rocketsim.transfer.arcs.arcs`:
Lambert solutions between the bodies' positions, their burns priced, the targets'
set-ups) the local minima of the chosen objective (total Δv or C3), within the
limits on C3, arrival v∞ and time of flight, are refined by a local minimiser
(``scipy.optimize.minimize``, Nelder-Mead on the two dates) and returned as
:class:`Window` objects. An optimum the refinement carries onto a bound of the
search (the first or last departure date, the earliest or latest arrival date, the
shortest or longest time of flight) is the best the search range holds, not a
minimum of the problem: its window's ``edge`` names the bound. :func:`parking_plane`
gives the plane of the parking orbit a window departs from.

Dates are Julian dates in TT (``jd_tt``); times of flight in days. The ephemeris is
a parameter, as :mod:`rocketsim.transfer.arcs` takes it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Callable

import numpy as np

from rocketsim.errors import InputError
from rocketsim.transfer.arcs import (Arcs, Orbits, Target, arcs, body_states, check_dates,
                                     default_ephemeris, target)


@dataclass(frozen=True)
class Window:
    """One launch window: the optimum of a basin of the porkchop plot."""

    departure_jd_tt: float
    arrival_jd_tt: float
    tof_days: float
    c3: float                       # m^2/s^2
    vinf_departure: tuple[float, float, float]   # m/s, J2000 equatorial
    vinf_arrival: float             # m/s
    rla: float                      # rad
    dla: float                      # rad
    dv_departure: float             # m/s
    dv_arrival: float               # m/s
    dv_total: float                 # m/s
    edge: str | None = None         # the search bound the optimum sits on (None: inside)


@dataclass
class Search:
    """What :func:`search` found: the windows, best first, and the grid."""

    target: Target
    windows: list[Window]
    grid: Arcs
    objective: str
    limits: dict = field(default_factory=dict)


def parking_plane(window: Window, target_name: str, inclination: float | None = None,
                  ephemeris: Callable | None = None) -> tuple[float, float]:
    """``(inclination, RAAN)`` (rad, J2000 mean equator and equinox) of the circular
    parking orbit ``window`` departs from.

    To Mars: a plane holding the departure asymptote (right ascension ``a``,
    declination ``d``) at ``inclination`` (default the smallest, ``|d|``), crossing
    it northbound for ``d > 0``: ``sin(a - RAAN) = tan d / tan i`` (Vallado,
    *Fundamentals of Astrodynamics and Applications*, 4th ed., sec. 12.4: a launch
    azimuth's plane through a given direction). To the Moon: the Moon's orbital
    plane at arrival (its geocentric angular momentum), which the search assumes the
    parking orbit lies in; ``inclination`` is then refused."""
    if target(target_name).name == "moon":
        if inclination is not None:
            raise InputError("a lunar window departs in the Moon's orbital plane: no parking inclination "
                             "to choose", field="parking inclination")
        eph = ephemeris or default_ephemeris
        r, v = eph("moon", np.array([window.arrival_jd_tt]), "earth")
        h = np.cross(np.asarray(r, dtype=float).reshape(3), np.asarray(v, dtype=float).reshape(3))
        return (math.acos(h[2] / float(np.linalg.norm(h))),
                math.atan2(h[0], -h[1]) % (2.0 * math.pi))
    declination = window.dla
    smallest = abs(declination)
    i = smallest if inclination is None else inclination
    if not smallest <= i <= math.pi - smallest:
        raise InputError(f"a parking orbit inclined {math.degrees(i):.2f} deg cannot hold the departure "
                         f"asymptote at declination {math.degrees(declination):.2f} deg: give at least "
                         f"{math.degrees(smallest):.2f} deg", field="parking inclination")
    ratio = math.tan(declination) / math.tan(i) if math.tan(i) != 0.0 else 0.0
    return i, (window.rla - math.asin(max(-1.0, min(1.0, ratio)))) % (2.0 * math.pi)


def _objective_values(grid: Arcs, objective: str, limits: dict) -> np.ndarray:
    values = grid.dv_total if objective == "dv" else grid.c3
    values = np.where(grid.valid, values, np.inf)
    ok = np.isfinite(values)
    if limits.get("max_c3") is not None:
        ok &= grid.c3 <= limits["max_c3"]
    if limits.get("max_vinf_arrival") is not None:
        ok &= grid.vinf_arrival <= limits["max_vinf_arrival"]
    if limits.get("tof_days") is not None:
        lo, hi = limits["tof_days"]
        ok &= (grid.tof_days >= lo) & (grid.tof_days <= hi)
    return np.where(ok, values, np.inf)


def _local_minima(values: np.ndarray) -> list[tuple[int, int]]:
    """Grid cells not larger than any of their 8 neighbours, all of them finite.

    A cell on the edge of the grid or of the region within the limits is not
    a minimum of the problem but of the box drawn around it, so it is skipped.
    """
    padded = np.pad(values, 1, constant_values=np.inf)
    centre = padded[1:-1, 1:-1]
    is_min = np.isfinite(centre)
    n, m = values.shape
    for di in (-1, 0, 1):
        for dj in (-1, 0, 1):
            if di == 0 and dj == 0:
                continue
            neighbour = padded[1 + di:1 + di + n, 1 + dj:1 + dj + m]
            is_min &= np.isfinite(neighbour) & (centre <= neighbour)
    cells = list(zip(*np.nonzero(is_min)))
    cells.sort(key=lambda ij: values[ij])
    return [(int(i), int(j)) for i, j in cells]


def search(departure_jd, arrival_jd, *, target_name: str = "mars", objective: str = "dv",
           orbits: Orbits = Orbits(), max_c3: float | None = None,
           max_vinf_arrival: float | None = None, tof_days: tuple[float, float] | None = None,
           count: int = 3, ephemeris: Callable | None = None,
           progress: Callable[[int, int], None] | None = None) -> Search:
    """The best windows over a grid of departure x arrival dates (TT Julian dates).

    ``departure_jd`` (N,) and ``arrival_jd`` (M,) are the grid's axes.
    ``objective`` is ``"dv"`` (total Δv: escape plus capture) or ``"c3"``.
    Limits: ``max_c3`` (m^2/s^2), ``max_vinf_arrival`` (m/s), ``tof_days``
    (min, max; default: the target's range). Returns at most ``count``
    windows, best first, each refined by ``scipy.optimize.minimize`` from a
    local minimum of the grid and kept within the limits. ``progress(done,
    total)`` is called as rows of the grid are finished.
    """
    from scipy.optimize import minimize

    if objective not in ("dv", "c3"):
        raise InputError(f"objective must be 'dv' or 'c3', got {objective!r}", field="objective")
    tgt = target(target_name)
    eph = ephemeris or default_ephemeris
    dep = np.asarray(departure_jd, dtype=float).reshape(-1)
    arr = np.asarray(arrival_jd, dtype=float).reshape(-1)
    if dep.size == 0 or arr.size == 0:
        raise InputError("the search grid is empty", field="dates")
    if ephemeris is None:
        check_dates(dep, "departure date")
        check_dates(arr, "arrival date")
    limits = {"max_c3": max_c3, "max_vinf_arrival": max_vinf_arrival,
              "tof_days": tof_days if tof_days is not None else tgt.tof_days}

    dep_states = body_states(eph, "earth", dep, tgt.center)
    arr_states = body_states(eph, tgt.arrival_body, arr, tgt.center)
    # Row blocks so that progress can be reported on long searches.
    block = max(1, 20000 // max(1, arr.size))
    rows = []
    for start in range(0, dep.size, block):
        stop = min(dep.size, start + block)
        rows.append(arcs(dep[start:stop, None], arr[None, :], target_name=tgt.name,
                         orbits=orbits, ephemeris=eph,
                         departure_states=(dep_states[0][start:stop, None],
                                           dep_states[1][start:stop, None]),
                         arrival_states=(arr_states[0][None], arr_states[1][None])))
        if progress is not None:
            progress(stop, dep.size)
    grid = Arcs(*(np.concatenate([getattr(r, f) for r in rows], axis=0)
                  for f in Arcs.__dataclass_fields__))

    # Opportunities are the basins of the unconstrained objective inside the
    # grid; the limits then only accept or reject their optima. A minimum
    # made by a limit cutting the porkchop (say at the longest time of
    # flight allowed) is not an opportunity, unless no basin's optimum is
    # within the limits: then the constrained optimum is the one window.
    free = _objective_values(grid, objective, {})
    values = _objective_values(grid, objective, limits)
    step = max(float(np.median(np.diff(dep))) if dep.size > 1 else 1.0,
               float(np.median(np.diff(arr))) if arr.size > 1 else 1.0)
    lo_dep, hi_dep = dep[0], dep[-1]
    lo_arr, hi_arr = arr[0], arr[-1]

    def evaluate(point):
        d, a = float(point[0]), float(point[1])
        if not (lo_dep <= d <= hi_dep and lo_arr <= a <= hi_arr):
            return None
        return arcs(np.array([d]), np.array([a]), target_name=tgt.name, orbits=orbits,
                    ephemeris=eph)

    def refine(i, j, within):
        """Optimum from grid cell (i, j) of the objective under ``within``.

        Nelder-Mead in (departure, time of flight), both kept inside their
        bounds (the grid's dates, and the time-of-flight limit if it is in
        ``within``), so that an optimum on a time-of-flight limit is found
        along it; other limits count as infinite cost.
        """
        tof_lo, tof_hi = within.get("tof_days") or (-np.inf, np.inf)

        def cost(x):
            one = evaluate((x[0], x[0] + x[1]))
            return np.inf if one is None else float(_objective_values(one, objective, within)[0])
        start = np.array([dep[i], arr[j] - dep[i]])
        bounds = [(lo_dep, hi_dep), (max(tof_lo, lo_arr - hi_dep), min(tof_hi, hi_arr - lo_dep))]
        start = np.clip(start, [b[0] for b in bounds], [b[1] for b in bounds])
        simplex = np.array([start, start + [step, 0.0], start + [0.0, step]])
        simplex = np.clip(simplex, [b[0] for b in bounds], [b[1] for b in bounds])
        result = minimize(cost, start, method="Nelder-Mead", bounds=bounds,
                          options={"initial_simplex": simplex, "xatol": 1e-5,
                                   "fatol": 1e-9, "maxiter": 600})
        best = result.x if np.isfinite(result.fun) and result.fun <= cost(start) else start
        return np.array([best[0], best[0] + best[1]])

    tof_lo, tof_hi = limits["tof_days"] or (-np.inf, np.inf)
    bounds = (("the first departure date searched", 0, lo_dep), ("the last departure date searched", 0, hi_dep),
              ("the earliest arrival date searched", 1, lo_arr), ("the latest arrival date searched", 1, hi_arr),
              ("the shortest time of flight searched", 2, tof_lo), ("the longest time of flight searched", 2, tof_hi))

    def edge_of(point) -> str | None:
        """The bound the optimum ``point`` (departure, arrival) sits on, within a
        thousandth of the grid's step (the refinement stops on a bound it reaches)."""
        place = (point[0], point[1], point[1] - point[0])
        return next((name for name, axis, bound in bounds if abs(place[axis] - bound) <= 1e-3 * step), None)

    def window_at(point):
        one = evaluate(point)
        return Window(
            departure_jd_tt=float(point[0]), arrival_jd_tt=float(point[1]),
            tof_days=float(one.tof_days[0]), c3=float(one.c3[0]),
            vinf_departure=tuple(float(x) for x in one.vinf_departure[0]),
            vinf_arrival=float(one.vinf_arrival[0]), rla=float(one.rla[0]),
            dla=float(one.dla[0]), dv_departure=float(one.dv_departure[0]),
            dv_arrival=float(one.dv_arrival[0]), dv_total=float(one.dv_total[0]), edge=edge_of(point))

    windows: list[Window] = []
    for i, j in _local_minima(free):
        if len(windows) >= count:
            break
        best = refine(i, j, {})
        one = evaluate(best)
        if not np.isfinite(_objective_values(one, objective, limits)[0]):
            continue                                  # this basin's optimum breaks a limit
        if any(abs(best[0] - w.departure_jd_tt) < 2.0 * step
               and abs(best[1] - w.arrival_jd_tt) < 2.0 * step for w in windows):
            continue
        windows.append(window_at(best))
    if not windows and np.isfinite(values).any():
        i, j = np.unravel_index(int(np.argmin(values)), values.shape)
        windows.append(window_at(refine(int(i), int(j), limits)))
    key = (lambda w: w.dv_total) if objective == "dv" else (lambda w: w.c3)
    windows.sort(key=key)
    return Search(tgt, windows, grid, objective, limits)
