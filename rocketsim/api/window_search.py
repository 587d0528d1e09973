"""Launch windows to Mars or the Moon over UTC dates: what ``rocketsim windows`` lists,
plots and writes as a mission fragment.

:func:`window_grid` lays a grid of departure and arrival dates (TT Julian dates, with
the UTC clock they were made from); :func:`launch_windows` searches it
(:func:`rocketsim.transfer.windows.search`: Izzo's Lambert arcs between the bodies'
centres on the project's ephemerides, refined to the optima, priced as escape from a
circular parking orbit plus capture at the target, patched conics) and gives the
:class:`LaunchWindows`: its windows as rows in UTC, a window as a mission-file
fragment, the grid for :func:`rocketsim.plots.porkchop`.
"""

from __future__ import annotations

import datetime as dt
import math
from dataclasses import dataclass
from typing import Callable

import numpy as np

from rocketsim.constants import SECONDS_PER_DAY
from rocketsim.scenario.units import parse_quantity
from rocketsim.timescales import Epoch
from rocketsim.transfer import arcs as transfer_arcs, windows as transfer_windows


def window_targets() -> list[str]:
    """Where a window search can go: ``mars``, ``moon``."""
    return sorted(transfer_arcs.TARGETS)


def days(value) -> float:
    """A duration in days: a number (days), or a text with its time unit (``"200 h"``)."""
    try:
        return float(value)
    except ValueError:
        return parse_quantity(value, "time") / SECONDS_PER_DAY


class UtcClock:
    """TT Julian dates <-> UTC, anchored at ``start`` (Delta T held at its value there)."""

    def __init__(self, start: dt.datetime):
        self.epoch = Epoch.from_utc(start)
        self.jd_tt0 = self.epoch.jd_tt()

    def jd_tt(self, moment: dt.datetime) -> float:
        return self.jd_tt0 + (moment - self.epoch.utc).total_seconds() / SECONDS_PER_DAY

    def utc(self, jd_tt: float) -> dt.datetime:
        return self.epoch.utc_at((jd_tt - self.jd_tt0) * SECONDS_PER_DAY)


@dataclass
class WindowGrid:
    """The dates a search tries: ``departure_jd`` (N,) and ``arrival_jd`` (M,), TT Julian
    dates ``step_days`` apart, arrivals from the first departure plus the shortest time of
    flight to the last plus the longest (``tof_days``); ``clock`` turns them into UTC."""

    target: str
    clock: UtcClock
    departure_jd: np.ndarray
    arrival_jd: np.ndarray
    tof_days: tuple[float, float]

    @property
    def cells(self) -> int:
        return self.departure_jd.size * self.arrival_jd.size


def window_grid(target: str, first: dt.datetime, last: dt.datetime, step: float,
                tof_days: tuple[float, float] | None = None) -> WindowGrid:
    """The :class:`WindowGrid` to ``target`` of departures from the UTC instant ``first`` to
    ``last``, ``step`` seconds apart, with times of flight ``tof_days`` (min, max; default
    the target's range)."""
    lo, hi = tof_days or transfer_arcs.target(target).tof_days
    clock = UtcClock(first)
    step_days = step / SECONDS_PER_DAY
    jd_first, jd_last = clock.jd_tt(first), clock.jd_tt(last)
    departure = jd_first + step_days * np.arange(math.floor((jd_last - jd_first) / step_days + 1e-9) + 1)
    arrival_first = departure[0] + lo
    arrival = arrival_first + step_days * np.arange(
        math.floor((departure[-1] + hi - arrival_first) / step_days + 1e-9) + 1)
    return WindowGrid(target, clock, departure, arrival, (lo, hi))


@dataclass
class LaunchWindows:
    """What a search of ``grid`` found (``search``: the windows, best first, and the arcs
    over the grid), for the parking and capture ``orbits``."""

    grid: WindowGrid
    search: transfer_windows.Search
    orbits: transfer_arcs.Orbits

    @property
    def windows(self) -> list[transfer_windows.Window]:
        return self.search.windows

    def rows(self) -> list[dict]:
        """Each window as a row: UTC dates, days, C3 (km²/s²), the departure asymptote's
        declination and right ascension (deg), arrival v-infinity and Delta-v (km/s), and
        ``edge``: the bound of the search its optimum sits on (None: inside the range)."""
        utc = self.grid.clock.utc
        return [{
            "departure_utc": f"{utc(w.departure_jd_tt):%Y-%m-%dT%H:%M:%SZ}",
            "arrival_utc": f"{utc(w.arrival_jd_tt):%Y-%m-%dT%H:%M:%SZ}",
            "tof_days": round(w.tof_days, 3),
            "c3_km2_s2": round(w.c3 / 1e6, 4),
            "dla_deg": round(math.degrees(w.dla), 3),
            "rla_deg": round(math.degrees(w.rla), 3),
            "vinf_arrival_km_s": round(w.vinf_arrival / 1e3, 4),
            "dv_departure_km_s": round(w.dv_departure / 1e3, 4),
            "dv_arrival_km_s": round(w.dv_arrival / 1e3, 4),
            "dv_total_km_s": round(w.dv_total / 1e3, 4),
            "edge": w.edge,
        } for w in self.windows]

    def fragment(self, index: int = 0, parking_inclination: float | None = None) -> str:
        """The window ``index`` (0: the best) as a mission file (YAML) a scenario names as
        its ``mission:``: the departure epoch, a start in the circular parking orbit the
        window departs from (:func:`rocketsim.transfer.windows.parking_plane`: a plane
        holding the departure asymptote inclined ``parking_inclination`` rad, by default
        the least that does; to the Moon the Moon's orbital plane), a duration to the
        arrival and a day beyond, ``gravity: n-body``; the window's figures (C3, the
        asymptote, v-infinity, Delta-v, the arrival) in the comments above it."""
        import yaml

        window, target, orbits = self.windows[index], self.grid.target, self.orbits
        departure = self.grid.clock.utc(window.departure_jd_tt)
        arrival = self.grid.clock.utc(window.arrival_jd_tt)
        inclination, raan = transfer_windows.parking_plane(window, target, parking_inclination)
        capture = orbits.capture_apoapsis_altitude
        capture = orbits.capture_periapsis_altitude if capture is None else capture
        name = f"earth-{target}-{departure:%Y-%m-%d}"
        mission = {
            "name": name,
            "epoch": f"{departure:%Y-%m-%dT%H:%M:%SZ}",
            "start": {"orbit": {"altitude": f"{orbits.parking_altitude / 1e3:g} km",
                                "inclination": f"{math.degrees(inclination):.4f} deg",
                                "raan": f"{math.degrees(raan):.4f} deg"}},
            "duration": f"{math.ceil(window.tof_days) + 1:g} d",
            "gravity": "n-body",
        }
        burn = ("departure burn " + ", ".join(f"{c / 1e3:+.6f}" for c in window.vinf_departure)
                + " km/s (J2000)") if target == "moon" else (
            f"v-infinity {', '.join(f'{c / 1e3:+.6f}' for c in window.vinf_departure)} km/s (J2000)")
        lines = [
            f"Launch window #{index + 1} to {target} from `rocketsim windows` (patched conics: Izzo's Lambert",
            "solver between the bodies' centres on the project's VSOP87D/ELP2000 ephemerides).",
            f"departure {departure:%Y-%m-%dT%H:%M:%SZ} from a {orbits.parking_altitude / 1e3:g} km circular "
            f"parking orbit: C3 {window.c3 / 1e6:.4f} km2/s2,",
            f"  asymptote RA {math.degrees(window.rla):.4f} deg, declination {math.degrees(window.dla):.4f} deg; "
            f"{burn};",
            f"  departure delta-v {window.dv_departure / 1e3:.4f} km/s",
            f"arrival {arrival:%Y-%m-%dT%H:%M:%SZ} after {window.tof_days:.4f} d: v-infinity "
            f"{window.vinf_arrival / 1e3:.4f} km/s,",
            f"  capture into {orbits.capture_periapsis_altitude / 1e3:g} x {capture / 1e3:g} km: delta-v "
            f"{window.dv_arrival / 1e3:.4f} km/s (total {window.dv_total / 1e3:.4f} km/s)",
        ]
        if window.edge:
            lines.append(f"AT THE EDGE of the search: on {window.edge}; the optimum may lie beyond it")
        lines += ["The parking orbit's plane " + ("is the Moon's orbital plane at arrival."
                                                  if target == "moon" else "holds the departure asymptote."),
                  "A scenario flies this mission with `mission: <this file>`, its vehicle and a program."]
        return "".join(f"# {line}\n" for line in lines) + yaml.safe_dump(mission, sort_keys=False)


def launch_windows(grid: WindowGrid, *, objective: str = "dv", parking_altitude: float = 200e3,
                   capture_periapsis_altitude: float = 400e3,
                   capture_apoapsis_altitude: float | None = None, max_c3: float | None = None,
                   max_vinf_arrival: float | None = None, count: int = 3,
                   progress: Callable[[int, int], None] | None = None) -> LaunchWindows:
    """The best ``count`` windows over ``grid`` by ``objective`` (``"dv"``: total Delta-v,
    or ``"c3"``), from a circular parking orbit at ``parking_altitude`` (m) to a capture
    orbit of periapsis and apoapsis altitudes (m; no apoapsis: circular), within
    ``max_c3`` (m²/s²) and ``max_vinf_arrival`` (m/s) and the grid's times of flight;
    ``progress(rows done, rows)`` as the grid's rows are finished."""
    orbits = transfer_arcs.Orbits(parking_altitude=parking_altitude,
                                     capture_periapsis_altitude=capture_periapsis_altitude,
                                     capture_apoapsis_altitude=capture_apoapsis_altitude)
    found = transfer_windows.search(grid.departure_jd, grid.arrival_jd, target_name=grid.target,
                                    objective=objective, orbits=orbits, max_c3=max_c3,
                                    max_vinf_arrival=max_vinf_arrival, tof_days=grid.tof_days,
                                    count=count, progress=progress)
    return LaunchWindows(grid, found, orbits)
