"""The telemetry sample of one body: its state message, every number of it from one compiled call.

:func:`rocketsim.stepping.sample_figures.figures` computes, for one body at its
time, the state and everything derived from it (geodetic position, speed, orbit
elements, mass, accelerations, air data; for a staged vehicle the engines,
propellant and heating) into one flat float64 array; :func:`values` returns that array with
the function that lays it out as the state message (keys in the order of
:data:`rocketsim.telemetry.schemas.BODY_STATE`), one per message shape, with a
layout worked out once per vehicle model. The flight writes the array as it
is (:meth:`rocketsim.telemetry.writer.TelemetryWriter.sample` splices its
numbers into a byte template of the message): a sample costs one compiled call
for its numbers and one for its bytes, no dictionary; :func:`message` builds
the dictionary for those who read it.

The fields and their units are those of :mod:`rocketsim.stepping.sample_figures`.

A missing value is nan in the figures, None in :func:`message`'s dictionary, and
left out of the file's message (:meth:`rocketsim.telemetry.writer.TelemetryWriter.sample`),
so that every field written has its schema's type.

Names with characters other than letters, digits, ``-`` and ``_`` have them
replaced by ``_``, so Foxglove's message paths (``/<body>/state.group_thrust.booster_Merlin_1D_ring``)
and CSV columns can name them.
"""

from __future__ import annotations

import math
import weakref
from functools import lru_cache
from typing import NamedTuple

import numpy as np

from rocketsim.jit import entry_point
from rocketsim.constants import DEG
from rocketsim.dynamics.central import air_about
from rocketsim.dynamics.nbody import FIELD_JD0, FIELD_ROT
from rocketsim.dynamics.soi import frame_rotation
from rocketsim.dynamics.third_bodies import P_BUCKET, field_of, hold_field, nbody_flag
from rocketsim.layout import P_RADIUS
from rocketsim.stepping.sample_figures import (FLIGHT_KEYS, ORBIT_KEYS, SAMPLE_ALPHA, SAMPLE_GROUPS, SAMPLE_HEADING,
                                               SAMPLE_HEIGHT, SAMPLE_HEIGHT_AGL, SAMPLE_LAT, SAMPLE_LON, SAMPLE_MASS,
                                               SAMPLE_ORBIT, SAMPLE_PITCH, SAMPLE_SPEED, SAMPLE_SURFACE_SPEED,
                                               SAMPLE_VEHICLE, figures, orbit_figures)
from rocketsim.telemetry.frames import CentralFrame, central_frame
from rocketsim.vehicle.heating import sutton_graves_constant


_NO_GROUPS = np.zeros(0, dtype=np.int64)


def values(body, gmst0: float, where) -> tuple[np.ndarray, "Shape"]:
    """Every number of the state message of ``body`` (a :class:`rocketsim.sim.world.Body`)
    at its time, in the layout of :func:`figures`, and the function that lays them out
    as the message: ``fields(values, integer)`` (``integer``: how a count is written,
    ``int`` for a message of numbers), one object per message shape.

    ``gmst0`` (rad): the Earth's sidereal angle at the epoch (the RAAN's origin about
    Earth); ``where(body)``: its (latitude rad, longitude rad, height m) away from Earth."""
    plan = _plan(body, gmst0)
    _, entry, fixed, shape, shield, earth = plan
    y, p = body.y, _held(body)
    args = (body.t, y, p) + _with_shield(body, fixed, shield)
    if not (y.flags.c_contiguous and p.flags.c_contiguous):
        v = figures(*args)
    else:
        if entry is None:
            entry = plan[1] = _entry(body.vehicle, args)
        v = entry(*args)
    if not earth:
        ground = v[SAMPLE_HEIGHT] - v[SAMPLE_HEIGHT_AGL]
        lat, lon, v[SAMPLE_HEIGHT] = where(body)
        v[SAMPLE_LAT], v[SAMPLE_LON], v[SAMPLE_HEIGHT_AGL] = lat / DEG, lon / DEG, v[SAMPLE_HEIGHT] - ground
    return v, shape


def arguments(body, gmst0: float) -> tuple[tuple, "Shape"]:
    """``(the arguments of figures() after the state and parameters, shape)`` of
    ``body``'s state message at its time (see :func:`values`), for a compiled caller
    that computes figures itself (:mod:`rocketsim.sim.coast_runs`)."""
    _, _, fixed, shape, shield, _ = _plan(body, gmst0)
    return _with_shield(body, fixed, shield), shape


def _with_shield(body, fixed: tuple, shield: bool) -> tuple:
    """``fixed`` and the shield's temperature (K; nan: none), figures' last argument."""
    return fixed + ((float(body.checks.temperature) if shield else math.nan),)


def run_sampler(body, gmst0: float) -> tuple[tuple, "Shape", int, bool]:
    """``(arguments, shape, length, whole)`` for a compiled run of the staged vehicle
    ``body`` to compute its samples in (:func:`rocketsim.stepping.runs.fly_run`): ``figures(t,
    y, body.p, *arguments, shield_temperature)`` is what :func:`values` computes for
    the body in state ``y`` at time ``t`` (s), ``shape`` its ``fields``, ``length`` the
    number of its figures; ``whole``: they are the whole message (about Earth; elsewhere
    :func:`values` places the body in Python)."""
    _, _, fixed, shape, _, earth = _plan(body, gmst0)
    n_groups = len(_layout(body.vehicle)[1])
    return fixed, shape, SAMPLE_GROUPS + 2 * n_groups + body.vehicle.arrays.tank_bottom.shape[0] + 2, earth


# id(body) -> [weak reference to the body, what values() works out once for it while its
# parameters, vehicle model and checks, the air it flies in and the epoch's sidereal
# angle stay the same objects]
_PLANS: dict[int, list] = {}


def _plan(body, gmst0: float) -> tuple:
    """``[what it was worked out for, figures' entry (None until :func:`values` binds it), the
    arguments after the state and parameters but for the shield's temperature, shape, has a
    shield, flies about Earth]``
    of ``body``
    (see :data:`_PLANS`): the frame, the shape, the layout and the air looked up once,
    not at every sample."""
    earth = body.central == "earth"
    table = air_about(body.central, body.atmosphere() if earth else None)
    model = body.vehicle
    key = (body.p, model, None if model is None else model.arrays, body.checks, table, gmst0)
    found = _PLANS.get(id(body))
    if found is not None and found[0]() is body and all(a is b for a, b in zip(found[1][0], key)):
        return found[1]
    frame = _frame_of(body, gmst0)
    head = _head(body, gmst0, table)
    if model is None:
        fixed = _rigid(head, body.p, body.drag)
        shape, shield = _shape(frame, None, None, False), None
    else:
        group, groups, tanks = _layout(model)
        shield = body.checks.shield if body.checks is not None else None
        fixed = head + (model.arrays, group, len(groups), shield.nose_radius if shield is not None else 0.0,
                        sutton_graves_constant(body.mu), 0.0, 0.0, nbody_flag(body.p))
        shape = _shape(frame, groups, tanks, shield is not None)
    plan = [key, None, fixed, shape, shield is not None, earth]     # figures' entry bound by values()
    for gone in [k for k, (ref, _) in _PLANS.items() if ref() is None]:
        del _PLANS[gone]            # bodies gone with their runs
    _PLANS[id(body)] = [weakref.ref(body), plan]
    return plan


def _head(body, gmst0: float, table) -> tuple:
    """figures' arguments after the state and parameters that every body has: its
    central body's gravity, the sidereal angle (about Earth), the air ``table``."""
    earth = body.central == "earth"
    return (body.mu, gmst0 if earth else 0.0, earth, *table.arrays())


def _rigid(head: tuple, p: np.ndarray, drag: tuple | None) -> tuple:
    """A rigid body's arguments of figures after ``head`` (:func:`_head`), but for the
    shield's temperature: ``drag`` is a tumbling part's ``(area over mass m^2/kg, length m)``
    (None: a body the air does not act on)."""
    area_mass, length = (0.0, 0.0) if drag is None else drag
    return head + (None, _NO_GROUPS, 0, 0.0, 0.0, float(area_mass), float(length), nbody_flag(p))


def part_arguments(body, gmst0: float) -> tuple:
    """The arguments of figures (as :func:`arguments`) of a rigid body that separates
    from the vehicle ``body`` about Earth (a fairing's half: the same central body,
    air and epoch), for a compiled caller to be typed before the body exists."""
    # a drag area and length of the types of a part's (its own are given at its samples)
    return _rigid(_head(body, gmst0, air_about(body.central, body.atmosphere())), body.p, (1.0, 1.0)) \
        + (math.nan,)


def message(body, gmst0: float, where) -> dict:
    """The state message of ``body`` at its time (see :func:`values`), as a dictionary."""
    v, fields = values(body, gmst0, where)
    return fields(v.tolist(), int)


def _held(body) -> np.ndarray:
    """``body.p``, with the other bodies' positions held for the body's time if it carries
    an n-body field that no step has held them in yet (its first sample, the sample after
    a handover): the positions the step's derivative reads
    (:func:`rocketsim.dynamics.third_bodies.hold_field`), so its accelerations are defined."""
    p = body.p
    if len(p) > P_BUCKET and p[P_BUCKET] != p[P_BUCKET]:
        p = p.copy()
        hold_field(p, body.t)
    return p


def _entry(model, args):
    """The compiled entry of ``figures(*args)``, bound once per vehicle model and n-body
    switch (and once per switch for every rigid body): :meth:`rocketsim.jit.Entries.call`
    without its look at every argument, to call with contiguous state and parameters (a
    view is called through the dispatcher). The switch (``args[-2]``, True or None) is a
    type of the entry: a body with an n-body field and one without need two."""
    nbody = args[-2]
    if model is None:
        if nbody not in _RIGID:
            _RIGID[nbody] = entry_point(figures, *args)
        return _RIGID[nbody]
    record = _model(model)
    if record[2] is None or record[2][0] is not model.arrays or record[2][1] is not nbody:
        record[2] = (model.arrays, nbody, entry_point(figures, *args))
    return record[2][2]


_RIGID: dict = {}       # the n-body switch -> the rigid bodies' entry


class Shape(NamedTuple):
    """The ``fields`` of :func:`values`: the state message of one shape from its numbers
    (``fields(values, integer)``), and the inertial frame it is expressed in."""

    frame: CentralFrame
    groups: tuple | None
    tanks: tuple | None
    shield: bool

    def __call__(self, v, integer) -> dict:
        return _fields(v, integer, self.frame.center, self.groups, self.tanks, self.shield)


@lru_cache(maxsize=64)
def _shape(frame: CentralFrame, groups, tanks, shield: bool) -> Shape:
    """The ``fields`` of :func:`values` for one message shape, the same object each time."""
    return Shape(frame, groups, tanks, shield)


def _frame_of(body, gmst0: float) -> CentralFrame:
    """The inertial frame of ``body``'s state: its field's (centre, axes, epoch), else
    Earth's ECI of the mission epoch (``gmst0``, rad)."""
    fp = field_of(body.p)
    if fp is None:
        return _earth_frame(gmst0)
    return central_frame(body.central, fp[FIELD_ROT:FIELD_ROT + 9], fp[FIELD_JD0])


@lru_cache(maxsize=4)
def _earth_frame(gmst0: float) -> CentralFrame:
    return central_frame("earth", frame_rotation("earth", 0.0, gmst0), math.nan)


def _fields(v, integer, central: str, groups, tanks, shield: bool) -> dict:
    """The state message (keys in the order of :data:`rocketsim.telemetry.schemas.BODY_STATE`)
    from the numbers ``v`` of :func:`figures` (a list, or slots standing for them)."""
    out = {"t": v[-2], "position": v[0:3], "velocity": v[3:6], "attitude": v[6:10],
           "body_rates": v[10:13], "latitude_deg": v[SAMPLE_LAT], "longitude_deg": v[SAMPLE_LON],
           "altitude": v[SAMPLE_HEIGHT], "height_agl": v[SAMPLE_HEIGHT_AGL], "inertial_speed": v[SAMPLE_SPEED],
           "surface_speed": v[SAMPLE_SURFACE_SPEED], "pitch_deg": v[SAMPLE_PITCH], "heading_deg": v[SAMPLE_HEADING],
           "orbit": _orbit(v[SAMPLE_ORBIT:SAMPLE_MASS]), "central_body": central}
    out.update(zip(FLIGHT_KEYS, v[SAMPLE_MASS:SAMPLE_VEHICLE]))
    alpha = v[SAMPLE_ALPHA]
    out["angle_of_attack_deg"] = alpha if alpha == alpha else None
    if groups is not None:
        n = len(groups)
        throttle = v[SAMPLE_VEHICLE]
        out["throttle"] = throttle if throttle == throttle else None
        out["group_throttle"] = {g: x if x == x else None
                                 for g, x in zip(groups, v[SAMPLE_GROUPS:SAMPLE_GROUPS + n])}
        out["thrust"] = v[SAMPLE_VEHICLE + 1]
        out["group_thrust"] = dict(zip(groups, v[SAMPLE_GROUPS + n:SAMPLE_GROUPS + 2 * n]))
        out["mass_flow"] = v[SAMPLE_VEHICLE + 2]
        out["engines_running"] = integer(v[SAMPLE_VEHICLE + 3])
        out["propellant"] = v[SAMPLE_VEHICLE + 4]
        out["propellant_tanks"] = dict(zip(tanks, v[SAMPLE_GROUPS + 2 * n:-2]))
        if shield:
            out["heat_flux"] = v[SAMPLE_VEHICLE + 5]
            out["shield_temperature"] = v[-1]
    return out


def orbit(body, gmst0: float) -> dict:
    """The ``orbit`` field of ``body``'s state message (see :func:`message`)."""
    return _orbit(orbit_figures(body.position, body.velocity, body.mu, body.p[P_RADIUS],
                                gmst0 if body.central == "earth" else 0.0).tolist())


def _orbit(values: list) -> dict:
    """The orbit's fields from its figures, null for an apoapsis and period not elliptic."""
    out = dict(zip(ORBIT_KEYS, values))
    if values[7] != values[7]:
        out["apoapsis_altitude"] = None
    if values[8] != values[8]:
        out["period"] = None
    return out


@lru_cache(maxsize=64)
def _keys(names: tuple[str, ...]) -> tuple[str, ...]:
    """Field names of tanks or engine groups (``stage/name`` -> ``stage_name``)."""
    return tuple("".join(c if c.isalnum() or c in "-_" else "_" for c in n) for n in names)


# id(model) -> [weak reference to the model, its layout, (its arrays, figures' entry) or None]
_MODELS: dict[int, list] = {}


def _layout(model) -> tuple:
    """``(engine group index of each engine, group keys, tank keys)`` of ``model``,
    worked out once per model (a staging builds new ones)."""
    return _model(model)[1]


def _model(model) -> list:
    """What is worked out once per vehicle model (see :data:`_MODELS`)."""
    found = _MODELS.get(id(model))
    if found is not None and found[0]() is model:
        return found
    keys = _keys(tuple(model.engine_groups))
    groups = tuple(dict.fromkeys(keys))
    layout = (np.array([groups.index(k) for k in keys], dtype=np.int64), groups,
              _keys(tuple(model.tank_names)))
    for key in [k for k, (ref, _, _) in _MODELS.items() if ref() is None]:
        del _MODELS[key]            # models gone with their runs
    found = _MODELS[id(model)] = [weakref.ref(model), layout, None]
    return found
