"""Draw a run from its telemetry: one PNG, its panels chosen for the flight.

Every panel has mission time across (s, min, h or days by the flight's length) and
a line per body (one colour per body throughout, named in the figure's legend):

* height: above the ground in m for a flight that stays under 10 km, else the
  altitude above the ellipsoid in km (log-scaled, about each central body in turn,
  for a flight that leaves Earth);
* speed: over the ground (solid; below 2 000 km of altitude), through the air
  (dashed), inertial (dotted: a body that reaches orbit or leaves Earth), in m/s,
  or km/s above 3 km/s;
* dynamic pressure q (Pa or kPa) and Mach: only where the flight meets the air;
* sensed acceleration in g (standard gravities) in flight (a coast under 0.05 g has
  none to show): from a body's landing on
  (a touchdown's contact spike, a landed body's weight) it is not drawn, its largest
  value named where it is beyond the flight's scale;
* propulsion: the throttle flown with the propellant on board (kg, or t above 10 t),
  or for solid motors the thrust (N or kN) with the propellant;
* attitude: the nose's pitch above the horizon and the angle of attack (deg; left),
  its heading from north (deg, dotted; right), of the bodies with engines or motors
  where there are some (a fairing's tumbling halves would hide them); the angle of
  attack and the heading up to the body's landing;
* orbit: periapsis and apoapsis altitudes (km) of the bodies while in orbit;
* the ground track: east and north of the start (m or km) for a flight within
  500 km of it, else latitude and longitude over the coastlines
  (:mod:`rocketsim.telemetry.land`), about Earth;
* the events, numbered in time order on the height panel (events too close to
  be told apart share a label, ``3-5``) and every one of them listed below.

A quantity no body has (throttle of a rigid body, q in vacuum) gets no panel. The
labels are laid out so that none overlaps another (tests/unit/plots/test_run_plots.py checks
every shipped scenario's picture). Reads a run's file only (nothing it carries is
executed), or a run in memory.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from rocketsim.campaigns.landing import east_north
from rocketsim.constants import G0
from rocketsim.errors import InputError
from rocketsim.plots.canvas import Picture, pyplot, save
from rocketsim.plots.event_marks import event_labels, event_lines, event_list, list_columns
from rocketsim.telemetry.land import draw_coastline
from rocketsim.telemetry.reader import read_run
from rocketsim.telemetry.tables import table

SMALL_HEIGHT = 10e3          # m: a flight below this has its height above the ground in m
LOCAL_TRACK = 500e3          # m: a track within this of its start is drawn east/north of it
LANDINGS = ("touchdown", "impact", "tip-over")
LOAD = 0.05                  # g: a flight whose sensed acceleration stays under it has no load panel
# m: low Earth orbit's upper bound (IADC Space Debris Mitigation Guidelines, 2007): above it the
# speed over the turning ground is mostly the ground's turn (28 km/s at the Moon's distance)
GROUND_SPEED_CEILING = 2000e3
_STYLE = {"surface": "-", "air": "--", "inertial": ":"}


def run(run, out: str | Path | None = None) -> Path | Picture:
    """Draw ``run``: a :class:`~rocketsim.api.run.Run` (what :func:`rocketsim.fly` and
    :func:`rocketsim.open_run` return) or the path of a run's MCAP file, read without
    executing anything. To the PNG ``out``, returning its path; without ``out``, a
    :class:`~rocketsim.plots.canvas.Picture`."""
    return save(figure(run), out, dpi=80, format="png")


def figure(run):
    """The open matplotlib figure :func:`run` writes, for ``run`` as there."""
    if isinstance(run, (str, Path)):
        file = read_run(run)
        return compose(file, {body: table(run, body) for body in file.bodies}, Path(run).stem)
    tables = {name: body.samples.columns() for name, body in run.bodies.items()}
    return compose(run.file, tables, run.path.stem if run.path else "run")


def _arrays(columns: dict) -> dict[str, np.ndarray]:
    """A body's columns (lists with None, or arrays) as float arrays (NaN where missing);
    text columns (the central body) as object arrays."""
    out = {}
    for key, values in columns.items():
        values = np.asarray(values, dtype=object if key == "central_body" else None)
        if values.dtype == object and key != "central_body":
            values = np.array([np.nan if v is None else v for v in values], dtype=float)
        out[key] = values
    return out


def _has(columns: dict, key: str) -> bool:
    values = columns.get(key)
    return values is not None and values.dtype.kind == "f" and bool(np.isfinite(values).any())


class _Time:
    """Mission time in the unit the flight's length reads best in."""

    def __init__(self, span: float):
        self.unit, self.scale = next(((u, s) for u, s, limit in
                                      (("s", 1.0, 1200.0), ("min", 60.0, 3 * 3600.0), ("h", 3600.0, 3 * 86400.0))
                                      if span <= limit), ("d", 86400.0))

    def __call__(self, t):
        return np.asarray(t, dtype=float) / self.scale

    def text(self, t: float) -> str:
        return f"T+{t / self.scale:.2f} {self.unit}" if self.unit != "s" else f"T+{t:.2f} s"


def draw(run, tables: dict, out, title: str) -> Path | Picture:
    """Draw ``run`` (a :class:`~rocketsim.telemetry.reader.RunFile`: its events, logs,
    metadata) with each body's columns ``tables[body]`` (:func:`rocketsim.telemetry.tables.table`'s,
    lists or arrays) to the PNG ``out`` (:func:`rocketsim.plots.canvas.save`); ``title``
    names a run whose metadata does not."""
    return save(compose(run, tables, title), out, dpi=80, format="png")


def compose(run, tables: dict, title: str):
    """The matplotlib figure :func:`draw` writes (see there), laid out and open."""
    plt = pyplot()
    bodies = {name: _arrays(columns) for name, columns in tables.items()}
    bodies = {name: c for name, c in bodies.items() if _has(c, "t")}
    colours = {name: f"C{k % 10}" for k, name in enumerate(tables)}
    landed = {}
    for event in run.events:
        if event["name"] in LANDINGS:
            landed.setdefault(event["body"], event["t"])
    times = [c["t"] for c in bodies.values()] or [np.zeros(1)]
    start, end = min(float(np.nanmin(t)) for t in times), max(float(np.nanmax(t)) for t in times)
    clock = _Time(max(end - start, 1e-9))
    panels = [p for p in (_height, _speed, _air, _acceleration, _propulsion, _attitude, _orbit, _track)
              if p(None, bodies, clock, landed)]
    if not panels:
        raise InputError(f"{title}: nothing to plot (no body has a state sample)", field="--plot")
    events = run.events
    ncols = 3
    nrows = math.ceil(len(panels) / ncols)
    lines = event_lines(events, clock, run.problem)
    list_height = 0.4 + 0.15 * math.ceil(len(lines) / list_columns(lines)) if events else 0.0
    height = 3.4 * nrows + list_height + 1.3
    figure = plt.figure(figsize=(16, height), dpi=80)
    grid = figure.add_gridspec(nrows + (1 if events else 0), ncols,
                               height_ratios=[3.4] * nrows + ([list_height] if events else []),
                               left=0.06, right=0.94, bottom=0.03 + 0.3 / height, top=1 - 1.05 / height,
                               hspace=0.45, wspace=0.42)
    axes = []
    for k, panel in enumerate(panels):
        ax = figure.add_subplot(grid[k // ncols, k % ncols])
        panel(ax, bodies, clock, landed, colours=colours)
        axes.append(ax)
        if panel is not _track:
            ax.set_xlabel(f"mission time, {clock.unit}")
            ax.grid(True, lw=0.4)
            for event in events:
                ax.axvline(clock(event["t"]), color="0.6", lw=0.5, ls=":", zorder=0)
    if axes and panels[0] is _height:
        event_labels(figure, axes[0], events, clock)
    if events:
        event_list(figure.add_subplot(grid[nrows, :]), events, clock, run.problem)
    handles = [plt.Line2D([], [], color=colours[name], lw=2) for name in bodies]
    figure.legend(handles, list(bodies), loc="upper left", ncol=min(len(bodies), 6), fontsize=9,
                  frameon=False, bbox_to_anchor=(0.06, 1 - 0.45 / height))
    info = run.metadata.get("rocketsim", {})
    outcome = run.metadata.get("outcome", {}).get("status", "")
    figure.suptitle(f"{info.get('scenario', title)}  (epoch {info.get('epoch_utc', '?')}"
                    + (f", {outcome}" if outcome and outcome != "ok" else "") + ")",
                    x=0.06, ha="left", y=1 - 0.25 / height)
    return figure


# --- the panels: each called with ax None answers whether it has anything to draw -----
def _line(ax, clock, columns, key, colour, scale=1.0, **style):
    t, y = columns["t"], columns[key]
    ax.plot(clock(t), y * scale, color=colour, **{"lw": 1.1, **style})


def _height(ax, bodies, clock, landed, colours=None):
    if ax is None:
        return any(_has(c, "altitude") for c in bodies.values())
    agl = all(_has(c, "height_agl") and np.nanmax(c["height_agl"]) < SMALL_HEIGHT for c in bodies.values())
    far = not all(_near_earth(c) for c in bodies.values())
    for name, c in bodies.items():
        if agl:
            _line(ax, clock, c, "height_agl", colours[name])
        else:
            _line(ax, clock, c, "altitude", colours[name], 1e-3)
    if agl:
        ax.set_ylabel("height above the ground, m")
    elif far:
        ax.set_yscale("log", nonpositive="mask")
        ax.set_ylabel("altitude above the central body, km")
    else:
        ax.set_ylabel("altitude above the ellipsoid, km")
    ax.set_title("height", fontsize=9)
    return True


def _over_the_ground(columns) -> np.ndarray:
    """``surface_speed`` where the body is below :data:`GROUND_SPEED_CEILING`, else nan."""
    low = columns["altitude"] < GROUND_SPEED_CEILING if _has(columns, "altitude") else True
    return np.where(low, columns["surface_speed"], np.nan)


def _speed(ax, bodies, clock, landed, colours=None):
    if ax is None:
        return any(_has(c, "inertial_speed") for c in bodies.values())
    speeds = {name: {"surface": _over_the_ground(c) if _has(c, "surface_speed") else None,
                     "air": c["airspeed"] if _has(c, "airspeed") and _in_air(c) else None,
                     "inertial": c["inertial_speed"] if _has(c, "inertial_speed") else None}
              for name, c in bodies.items()}
    top = max((np.nanmax(v) for kinds in speeds.values() for v in kinds.values()
               if v is not None and np.isfinite(v).any()), default=0.0)
    fast = top > 3000.0
    scale, unit = (1e-3, "km/s") if fast else (1.0, "m/s")
    inertial = fast or any(_has(c, "altitude") and np.nanmax(c["altitude"]) > 100e3 for c in bodies.values())
    drawn = set()
    for name, c in bodies.items():
        for kind, values in speeds[name].items():
            if values is not None and (kind != "inertial" or inertial) and np.isfinite(values).any():
                ax.plot(clock(c["t"]), values * scale, color=colours[name], lw=1.1, ls=_STYLE[kind])
                drawn.add(kind)
    ax.set_ylabel(f"speed, {unit}")
    ax.set_title("speed", fontsize=9)
    names = {"surface": "over the ground", "air": "through the air", "inertial": "inertial"}
    plt = pyplot()
    handles = [plt.Line2D([], [], color="k", lw=1, ls=_STYLE[k]) for k in names if k in drawn]
    if len(handles) > 1:
        ax.legend(handles, [names[k] for k in names if k in drawn], fontsize=7, loc="best")
    return True


def _in_air(columns) -> bool:
    return _has(columns, "dynamic_pressure") and np.nanmax(columns["dynamic_pressure"]) > 1.0


def _air(ax, bodies, clock, landed, colours=None):
    if ax is None:
        return any(_in_air(c) for c in bodies.values())
    top = max(np.nanmax(c["dynamic_pressure"]) for c in bodies.values() if _in_air(c))
    scale, unit = (1e-3, "kPa") if top >= 1000.0 else (1.0, "Pa")
    mach = ax.twinx()
    for name, c in bodies.items():
        if _in_air(c):
            _line(ax, clock, c, "dynamic_pressure", colours[name], scale)
            if _has(c, "mach"):
                _line(mach, clock, c, "mach", colours[name], ls="--", lw=0.9)
    ax.set_ylabel(f"dynamic pressure q, {unit}")
    mach.set_ylabel("Mach (dashed)")
    mach.set_ylim(bottom=0.0)
    ax.set_title("air: q and Mach", fontsize=9)
    return True


def _acceleration(ax, bodies, clock, landed, colours=None):
    if ax is None:      # a coast feels no load worth a panel
        return any(_has(c, "sensed_acceleration") and np.nanmax(c["sensed_acceleration"]) > LOAD * G0
                   for c in bodies.values())
    flight_top, landings = 0.0, []
    for name, c in bodies.items():
        if not _has(c, "sensed_acceleration"):
            continue
        g = c["sensed_acceleration"] / G0
        in_flight = c["t"] < landed.get(name, math.inf)
        ax.plot(clock(c["t"][in_flight]), g[in_flight], color=colours[name], lw=1.1)
        if in_flight.any() and np.isfinite(g[in_flight]).any():
            flight_top = max(flight_top, float(np.nanmax(g[in_flight])))
        if (~in_flight).any() and np.isfinite(g[~in_flight]).any():
            landings.append((name, float(np.nanmax(g[~in_flight]))))
    top = 1.15 * flight_top if flight_top > 0 else 1.0
    ax.set_ylim(0.0, top)
    above = [f"{name} {peak:.0f} g" for name, peak in sorted(landings, key=lambda x: -x[1]) if peak > top]
    if above:
        ax.text(0.98, 0.96, "landing, not drawn:\n" + "\n".join(above[:3] + (["..."] if len(above) > 3 else [])),
                transform=ax.transAxes, ha="right", va="top", fontsize=7, color="0.3",
                bbox={"boxstyle": "round,pad=0.2", "fc": "white", "ec": "none", "alpha": 0.8})
    ax.set_ylabel("sensed acceleration, g")
    ax.set_title("load", fontsize=9)
    return True


def _propulsion(ax, bodies, clock, landed, colours=None):
    throttled = [n for n, c in bodies.items() if _has(c, "throttle")]
    thrusting = [n for n, c in bodies.items() if _has(c, "thrust") and np.nanmax(c["thrust"]) > 0.0]
    if ax is None:
        return bool(throttled or thrusting)
    heavy = max((np.nanmax(c["propellant"]) for c in bodies.values() if _has(c, "propellant")), default=0.0)
    p_scale, p_unit = (1e-3, "t") if heavy >= 1e4 else (1.0, "kg")
    if throttled:
        for name in throttled:
            _line(ax, clock, bodies[name], "throttle", colours[name])
        ax.set_ylim(0.0, 1.05)
        ax.set_ylabel("throttle")
        ax.set_title("propulsion: throttle and propellant", fontsize=9)
    else:
        top = max(np.nanmax(bodies[n]["thrust"]) for n in thrusting)
        t_scale, t_unit = (1e-6, "MN") if top >= 1e7 else (1e-3, "kN") if top >= 1e4 else (1.0, "N")
        for name in thrusting:
            _line(ax, clock, bodies[name], "thrust", colours[name], t_scale)
        ax.set_ylabel(f"thrust, {t_unit}")
        ax.set_title("propulsion: thrust and propellant", fontsize=9)
    if heavy > 0.0:
        right = ax.twinx()
        for name, c in bodies.items():
            if _has(c, "propellant"):
                _line(right, clock, c, "propellant", colours[name], p_scale, ls="--", lw=0.9)
        right.set_ylabel(f"propellant on board, {p_unit} (dashed)")
        right.set_ylim(bottom=0.0)
    return True


def _attitude(ax, bodies, clock, landed, colours=None):
    if ax is None:
        return any(_has(c, "pitch_deg") for c in bodies.values())
    heading = ax.twinx()
    powered = {n for n, c in bodies.items() if _has(c, "thrust")}       # the vehicles, if any: not
    for name, c in bodies.items():                                      # their parts' tumbling
        if not _has(c, "pitch_deg") or (powered and name not in powered):
            continue
        _line(ax, clock, c, "pitch_deg", colours[name])
        # landed: the angle to the breeze and the heading of an upright nose are noise
        flying = c["t"] <= landed.get(name, math.inf)
        if _in_air(c) and _has(c, "angle_of_attack_deg"):
            ax.plot(clock(c["t"]), np.where(flying, c["angle_of_attack_deg"], np.nan),
                    color=colours[name], ls="--", lw=0.9)
        wrapped = np.where(flying, c["heading_deg"], np.nan)
        wrapped[1:][np.abs(np.diff(wrapped)) > 180.0] = np.nan      # no line across north
        heading.plot(clock(c["t"]), wrapped, color=colours[name], ls=":", lw=0.9)
    ax.set_ylim(-95.0, 185.0)
    ax.set_yticks(range(-90, 181, 45))
    ax.set_ylabel("pitch (solid), angle of attack (dashed), deg")
    heading.set_ylim(-5.0, 365.0)
    heading.set_yticks(range(0, 361, 90))
    heading.set_ylabel("heading from north, deg (dotted)")
    ax.set_title("attitude of the nose", fontsize=9)
    return True


def _orbit(ax, bodies, clock, landed, colours=None):
    def orbiting(c):
        return _has(c, "orbit_periapsis_altitude") and np.nanmax(c["orbit_periapsis_altitude"]) > 100e3
    if ax is None:
        return any(orbiting(c) for c in bodies.values())
    for name, c in bodies.items():
        if orbiting(c):
            up = c["orbit_periapsis_altitude"] > 0.0
            t = clock(c["t"])
            ax.plot(t, np.where(up, c["orbit_periapsis_altitude"], np.nan) / 1e3, color=colours[name], lw=1.1)
            ax.plot(t, np.where(up, c["orbit_apoapsis_altitude"], np.nan) / 1e3, color=colours[name], lw=1.1,
                    ls="--")
    low, high = ax.dataLim.y0, ax.dataLim.y1
    if low > 0.0 and high > 1e3 * low:          # from a parking orbit to the Sun's: decades apart
        ax.set_yscale("log")
    ax.set_ylabel("periapsis (solid), apoapsis (dashed), km")
    ax.set_title("orbit, while above the ground", fontsize=9)
    return True


def _track(ax, bodies, clock, landed, colours=None):
    about = {n: c for n, c in bodies.items() if _has(c, "latitude_deg")}
    if ax is None:
        return bool(about)
    first = next(iter(about.values()))
    k = int(np.argmax(np.isfinite(first["latitude_deg"])))
    lat0, lon0 = float(first["latitude_deg"][k]), float(first["longitude_deg"][k])
    local = {n: east_north(c["latitude_deg"], c["longitude_deg"], lat0, lon0) for n, c in about.items()
             if _near_earth(c)}
    reach = max((float(np.nanmax(np.hypot(*en))) for en in local.values()), default=math.inf)
    if local and reach < LOCAL_TRACK and len(local) == len(about):
        scale, unit = (1e-3, "km") if reach > 5e3 else (1.0, "m")
        for name, (east, north) in local.items():
            ax.plot(east * scale, north * scale, color=colours[name], lw=1.1)
            ax.plot(east[-1:] * scale, north[-1:] * scale, "x", color=colours[name])
        ax.plot([0.0], [0.0], "k^", ms=7)
        ax.set_xlabel(f"east of the start, {unit}")
        ax.set_ylabel(f"north of the start, {unit}")
        ax.set_aspect("equal", adjustable="datalim")
        ax.ticklabel_format(useOffset=False, style="plain")
        ax.set_title("ground track (^ start, x end)", fontsize=9)
        ax.grid(True, lw=0.4)
        return True
    lats, lons = [], []
    for name, c in about.items():
        lat, lon = c["latitude_deg"].copy(), c["longitude_deg"].copy()
        lat[~_near_earth_mask(c)] = np.nan
        lon[1:][np.abs(np.diff(lon)) > 180.0] = np.nan       # no line across the antimeridian
        ax.plot(lon, lat, color=colours[name], lw=1.0)
        lats.append(lat)
        lons.append(lon)
    lat, lon = np.concatenate(lats), np.concatenate(lons)
    ok = np.isfinite(lat) & np.isfinite(lon)
    if ok.any() and np.ptp(lat[ok]) < 20 and np.ptp(lon[ok]) < 20:
        # a short track: zoomed on it, the box of the panel filled at one degree to one degree
        box = ax.get_position()
        width, height = figure_size(ax)
        ratio = (box.height * height) / (box.width * width)
        half = 0.6 * max(np.ptp(lat[ok]), np.ptp(lon[ok]), 0.1)
        half_lon, half_lat = (half, half * ratio) if ratio < 1.0 else (half / ratio, half)
        mid_lon, mid_lat = 0.5 * (lon[ok].min() + lon[ok].max()), 0.5 * (lat[ok].min() + lat[ok].max())
        ax.set_xlim(mid_lon - half_lon, mid_lon + half_lon)
        ax.set_ylim(mid_lat - half_lat, mid_lat + half_lat)
    else:
        ax.set_xlim(-180, 180)
        ax.set_ylim(-90, 90)
        ax.set_xticks(range(-180, 181, 60))
        ax.set_yticks(range(-90, 91, 30))
    ax.set_aspect("equal", adjustable="box")
    draw_coastline(ax, ax.get_xlim(), ax.get_ylim())
    ax.ticklabel_format(useOffset=False, style="plain")
    ax.set_xlabel("longitude, deg")
    ax.set_ylabel("latitude, deg")
    ax.set_title("ground track (about Earth)", fontsize=9)
    ax.grid(True, lw=0.4)
    return True


def figure_size(ax) -> tuple[float, float]:
    """The width and height (in) of the figure ``ax`` is drawn in."""
    return tuple(ax.figure.get_size_inches())


def _near_earth_mask(columns) -> np.ndarray:
    central = columns.get("central_body")
    if central is None:
        return np.ones(len(columns["t"]), dtype=bool)
    return np.array([c in (None, "earth") for c in central])


def _near_earth(columns) -> bool:
    return bool(_near_earth_mask(columns).all())
