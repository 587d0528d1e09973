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
from rocketsim.transfer import windows as transfer_windows


def window_targets() -> list[str]:
    """Where a window search can go: ``mars``, ``moon``."""
    return sorted(transfer_windows.TARGETS)


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
    lo, hi = tof_days or transfer_windows.target(target).tof_days
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
    orbits: transfer_windows.Orbits

    @property
    def windows(self) -> list[transfer_windows.Window]:
        return self.search.windows

    def rows(self) -> list[dict]:
        """Each window as a row: UTC dates, days, C3 (km²/s²), the departure asymptote's
        declination and right ascension (deg), arrival v-infinity and Delta-v (km/s)."""
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
        } for w in self.windows]

    def fragment(self, index: int = 0) -> str:
        """The window ``index`` (0: the best) as a mission-file fragment (YAML): the
        mission's name and epoch, the departure burn's target, the arrival and capture."""
        import yaml

        window, target, orbits = self.windows[index], self.grid.target, self.orbits
        departure = self.grid.clock.utc(window.departure_jd_tt)
        arrival = self.grid.clock.utc(window.arrival_jd_tt)
        vector = [round(c / 1e3, 6) for c in window.vinf_departure]
        capture = {"periapsis_altitude": f"{orbits.capture_periapsis_altitude / 1e3:g} km",
                   "apoapsis_altitude": f"{(orbits.capture_apoapsis_altitude if orbits.capture_apoapsis_altitude is not None else orbits.capture_periapsis_altitude) / 1e3:g} km"}
        burn = {
            "epoch": f"{departure:%Y-%m-%dT%H:%M:%SZ}",
            "parking_orbit_altitude": f"{orbits.parking_altitude / 1e3:g} km",
            "c3_km2_s2": round(window.c3 / 1e6, 4),
            ("v_infinity_km_s" if target == "mars" else "burn_vector_km_s"): vector,
            "rla_deg": round(math.degrees(window.rla), 4),
            "dla_deg": round(math.degrees(window.dla), 4),
            "dv": f"{window.dv_departure / 1e3:.4f} km/s",
        }
        data = {
            "mission": {"name": f"earth-{target}-{departure:%Y-%m-%d}",
                        "epoch": f"{departure:%Y-%m-%dT%H:%M:%SZ}"},
            "departure_burn": burn,
            "arrival": {"body": target, "epoch": f"{arrival:%Y-%m-%dT%H:%M:%SZ}",
                        "tof": f"{window.tof_days:.4f} d",
                        "v_infinity": f"{window.vinf_arrival / 1e3:.4f} km/s",
                        "capture_orbit": capture,
                        "dv": f"{window.dv_arrival / 1e3:.4f} km/s"},
        }
        note = (f"# Launch window to {target} from `rocketsim windows` (patched conics: Izzo's\n"
                "# Lambert solver between the bodies' centres on the project's VSOP87D/ELP2000\n"
                "# ephemerides). `mission` goes into a scenario's mission; `departure_burn` is\n"
                "# the target of the departure burn (J2000 mean equatorial frame; for the Moon\n"
                "# the burn vector itself, from a parking orbit in the Moon's plane).\n")
        return note + yaml.safe_dump(data, sort_keys=False)


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
    orbits = transfer_windows.Orbits(parking_altitude=parking_altitude,
                                     capture_periapsis_altitude=capture_periapsis_altitude,
                                     capture_apoapsis_altitude=capture_apoapsis_altitude)
    found = transfer_windows.search(grid.departure_jd, grid.arrival_jd, target_name=grid.target,
                                    objective=objective, orbits=orbits, max_c3=max_c3,
                                    max_vinf_arrival=max_vinf_arrival, tof_days=grid.tof_days,
                                    count=count, progress=progress)
    return LaunchWindows(grid, found, orbits)
