"""What can be read off one body's state at one instant, truth or estimate.

A :class:`StateView` takes a state (position, velocity, attitude, rates in the
ECI of the mission epoch, at mission time ``t``) and derives, lazily and once
(at the first read, then kept: a view is of one instant), everything a flight
program or the telemetry reads: the geodetic position, surface and orbital
velocities, local directions, attitude angles and gravity together, in one
compiled call into one buffer (:func:`step_readings`: a reading is then an
element of it; where the place's readings, the height, the climb rate, the
ground speed, the local axes, are read first, those alone:
:func:`place_readings`), the air and the orbit each at its own first read.
The same class serves the truth (telemetry) and the navigation estimate (a
program with realistic sensors), so every derived quantity inherits the
estimate's errors. A view :meth:`~StateView.following` a state its owner
rewrites at each step (a compiled run's hand-over buffer) is one object for
the whole run, moved to each step with :meth:`~StateView.at`, its readings
written again into one array of its own.

Conventions: body ``x`` is the nose. ``pitch`` is the nose's elevation above
the local horizon, ``heading`` its azimuth from north towards east, ``roll``
the turn about the nose from the reference attitude whose body ``z`` lies in
the vertical plane through the nose on the ground side of the horizon
(``z = sin(pitch) h - cos(pitch) up``, ``h`` the horizontal heading): a
vehicle flying level with its belly down has roll 0. With the nose within
0.01 deg of vertical the heading is that of body ``z`` and roll is 0.
"""

from __future__ import annotations

import math

import numpy as np

from rocketsim.jit import entry_point, njit
from rocketsim.atmosphere.table import air_at, wind_earth_fixed
from rocketsim.bodies.gravity import point_mass_j2
from rocketsim.constants import EARTH_J2, EARTH_MU, EARTH_OMEGA, EARTH_RADIUS_EQ, EARTH_RADIUS_POLAR
from rocketsim.layout import N_STATE, P_J2, P_MU, P_POLAR_RADIUS, P_RADIUS, P_SPIN, Q, R, V, W, make_params
from rocketsim.frames.elements import Elements, state_to_elements, time_to_apoapsis
from rocketsim.frames.local import VERTICAL, air_velocity, turned, where_into
from rocketsim.frames.quaternion import quat_to_matrix

# the central body of a view given no parameters: Earth (gravity and rotation)
_EARTH_P = make_params(1.0, (1.0, 1.0, 1.0), EARTH_MU, EARTH_RADIUS_EQ, EARTH_J2, EARTH_RADIUS_POLAR)


class _once:
    """A property computed at most once per view: the value then sits in the
    instance's ``__dict__`` and later reads are plain attribute look-ups (no lock,
    unlike :func:`functools.cached_property` before Python 3.12)."""

    def __init__(self, function):
        self.function = function
        self.name = function.__name__
        self.__doc__ = function.__doc__

    def __get__(self, view, owner=None):
        if view is None:
            return self
        value = view.__dict__[self.name] = self.function(view)
        return value


@njit
def air_here(h0, dh, density, pressure, temperature, speed_of_sound, wind_east, wind_north,
             lat, lon, h, t, r, v, spin=EARTH_OMEGA):
    """The day's air at geodetic ``lat``, ``lon`` (rad), height ``h`` (m) and mission time
    ``t`` (s) for a body at ECI ``r`` (m) moving at ``v`` (m/s): ``(density kg/m^3,
    pressure Pa, temperature K, speed of sound m/s, wind (ECI, m/s), air-relative
    velocity (ECI, m/s))``, the air turning at ``spin`` (rad/s, the central body's;
    Earth's by default). The table's arrays come first (:meth:`AtmosphereTable.arrays`)."""
    rho, p, temperature_k, sound, east, north = air_at(h0, dh, density, pressure, temperature,
                                                       speed_of_sound, wind_east, wind_north, h)
    fixed = wind_earth_fixed(east, north, lat, lon)
    wind = np.empty(3)
    wind[0], wind[1] = turned(fixed[0], fixed[1], -(0.0 + EARTH_OMEGA * t))
    wind[2] = fixed[2]
    return rho, p, temperature_k, sound, wind, air_velocity(r, v, wind, spin)


# slots of a state's readings (step_readings): scalars, then vectors and matrices (ECI axes,
# row by row)
LATITUDE, LONGITUDE, HEIGHT, CLIMB, GROUND_SPEED, PITCH, HEADING, ROLL, GRAVITY = range(9)
ENU, SURFACE, RADIAL, PROGRADE, NORMAL, SURFACE_PROGRADE, AXES = 9, 18, 21, 24, 27, 30, 33
ACROSS = AXES + 9           # 3 slots where the readings are computed, no reading
N_READINGS = ACROSS + 3


@njit
def _unit(x, y, z):
    """``(x, y, z)`` over its length, and the length (``sqrt(v @ v)``, as :func:`_norm`)."""
    u = np.empty(3)
    u[0], u[1], u[2] = x, y, z
    length = math.sqrt(u @ u)
    return u / length, length


@njit
def place_readings_into(out, t, r, v, p):
    """The readings of the place of a state into the slots of ``out`` (:data:`N_READINGS`)
    that :func:`step_readings` gives them, ``r``, ``v``, ``t`` and ``p`` as its: latitude,
    longitude, height, the climb rate, the speed over the ground, the local east, north,
    up and the surface velocity (:func:`~rocketsim.frames.local.where_into`), as
    :func:`step_readings` computes them (the horizontal part of the surface velocity
    goes through the slots :data:`ACROSS`). Returns ``(enu, surface velocity)``, views
    of ``out``."""
    lat, lon, height = where_into(out, ENU, r, v, t, p[P_SPIN], p[P_RADIUS], p[P_POLAR_RADIUS])
    up, surface = out[ENU + 6:ENU + 9], out[SURFACE:SURFACE + 3]
    climb = surface @ up
    across = out[ACROSS:ACROSS + 3]
    for i in range(3):
        across[i] = surface[i] - climb * up[i]
    out[LATITUDE], out[LONGITUDE], out[HEIGHT] = lat, lon, height
    out[CLIMB], out[GROUND_SPEED] = climb, math.sqrt(across @ across)
    return out[ENU:ENU + 9].reshape((3, 3)), surface


@njit
def place_readings(out, t, s, p):
    """:func:`place_readings_into` ``out`` (its other slots left as they are) for the
    position and velocity of ``s`` (a state's first :data:`~rocketsim.layout.N_STATE`
    numbers); returns nothing (a call from Python boxes no array)."""
    place_readings_into(out, t, s[R:R + 3], s[V:V + 3], p)


@njit
def state_readings(out, t, s, p):
    """:func:`step_readings_into` ``out`` for the position, velocity and attitude of ``s``
    (as :func:`place_readings`)."""
    step_readings_into(out, t, s[R:R + 3], s[V:V + 3], s[Q:Q + 4], p)


@njit
def step_readings(t, r, v, q, p):
    """:func:`step_readings_into` a new array."""
    out = np.empty(N_READINGS)
    step_readings_into(out, t, r, v, q, p)
    return out


@njit
def step_readings_into(out, t, r, v, q, p):
    """The readings of a state in one compiled call: position ``r`` (m), velocity ``v``
    (m/s), attitude ``q`` (body -> ECI) at mission time ``t`` (s) of a body with
    parameters ``p`` (:mod:`rocketsim.layout`: the central body's ellipsoid, rotation
    and gravity), into ``out``, a float64 array of :data:`N_READINGS` slots: latitude,
    longitude (rad), height (m) over the central body's ellipsoid
    (:func:`~rocketsim.frames.local.where_and_how_fast`), the climb rate and the speed
    over the ground (m/s), pitch, heading, roll (rad, the module's conventions), the
    gravity's magnitude (m/s^2, point mass + J2), then the local east, north, up (rows),
    the surface velocity (m/s), the radial, prograde, orbit-normal (``r x v``) and
    surface-prograde unit vectors, and the body -> ECI matrix (its columns body x, y, z;
    row by row). Each figure is computed with the operations, in the order, of numpy's
    on these float64 values (a dot product is ``@``, a norm ``sqrt(v @ v)``, a cross
    product that of ``np.cross``), so a reading has the bits it has when computed
    figure by figure; those of the place are :func:`place_readings_into`'s."""
    enu, surface = place_readings_into(out, t, r, v, p)
    east, north, up = enu[0].copy(), enu[1].copy(), enu[2].copy()
    # the attitude's angles (pitch, heading, roll: see the module)
    axes = quat_to_matrix(q)
    nose, z_body = axes[:, 0].copy(), axes[:, 2].copy()
    sin_pitch = nose @ up
    if sin_pitch < -1.0:
        sin_pitch = -1.0
    elif sin_pitch > 1.0:
        sin_pitch = 1.0
    pitch = math.asin(sin_pitch)
    if abs(sin_pitch) >= VERTICAL:
        # the reference z is the heading itself (nose up) or its opposite
        belly = math.copysign(1.0, sin_pitch) * z_body
        heading, roll = math.atan2(belly @ east, belly @ north), 0.0
    else:
        horizontal = nose - sin_pitch * up
        horizontal /= math.sqrt(horizontal @ horizontal)
        heading = math.atan2(horizontal @ east, horizontal @ north)
        z_ref = sin_pitch * horizontal - math.cos(pitch) * up
        right = np.empty(3)         # z_ref x z_body, as np.cross
        right[0] = z_ref[1] * z_body[2] - z_ref[2] * z_body[1]
        right[1] = z_ref[2] * z_body[0] - z_ref[0] * z_body[2]
        right[2] = z_ref[0] * z_body[1] - z_ref[1] * z_body[0]
        roll = math.atan2(nose @ right, z_ref @ z_body)
    out[PITCH], out[HEADING], out[ROLL] = pitch, heading % (2 * math.pi), roll
    g = np.empty(3)
    g[0], g[1], g[2] = point_mass_j2(r[0], r[1], r[2], p[P_MU], p[P_RADIUS], p[P_J2])
    out[GRAVITY] = math.sqrt(g @ g)
    # the directions
    radial, _ = _unit(r[0], r[1], r[2])
    prograde, _ = _unit(v[0], v[1], v[2])
    normal, _ = _unit(r[1] * v[2] - r[2] * v[1], r[2] * v[0] - r[0] * v[2], r[0] * v[1] - r[1] * v[0])
    speed = math.sqrt(surface @ surface)
    along = surface / speed if speed > 0 else up
    for i in range(3):
        for k in range(3):
            out[AXES + 3 * i + k] = axes[i, k]
        out[RADIAL + i], out[PROGRADE + i] = radial[i], prograde[i]
        out[NORMAL + i], out[SURFACE_PROGRADE + i] = normal[i], along[i]


_BOUND: dict = {}       # kernel -> its entry for a view's own state (_bound)


def _bound(kernel, out: np.ndarray, t: float, state: np.ndarray, p: np.ndarray):
    """``kernel``'s compiled entry for the types of a view's ``kernel(out, t, state, p)``,
    bound at the first call, not typed by numba's dispatcher at every call: a view of_state
    holds its state in a C-contiguous float64 copy of its own (one :meth:`~StateView.following`
    a state, in that C-contiguous float64 state), and is read so only with C-contiguous
    parameters (a body's) into a float64 array of its own."""
    entry = _BOUND.get(kernel)
    if entry is None:
        entry = _BOUND[kernel] = entry_point(kernel, out, t, state, p)
    return entry


def _norm(vector) -> float:
    """Euclidean length of a float64 vector: the bits of ``np.linalg.norm`` (the
    square root of ``v @ v``), at a fraction of its cost."""
    return math.sqrt(vector @ vector)


class StateView:
    """Derived readings of one state at mission time ``t`` (SI units, ECI vectors)."""

    def __init__(self, t: float, r, v, q, w, atmosphere=None, mu: float = EARTH_MU, p=None):
        """``atmosphere``: a function returning the day's AtmosphereTable (called
        only when the air is read); ``p``: the body's parameters, whose central
        body's gravity and rotation (``P_SPIN``) the readings use (None: Earth's)."""
        self.t = t
        self.position = np.asarray(r, dtype=float)
        self.velocity = np.asarray(v, dtype=float)
        self.attitude = np.asarray(q, dtype=float)
        self.body_rates = np.asarray(w, dtype=float)
        self._atmosphere = atmosphere
        self.mu = mu
        self._p = _EARTH_P if p is None else p

    @classmethod
    def of_state(cls, t: float, y: np.ndarray, atmosphere=None, mu: float = EARTH_MU,
                 p=None) -> "StateView":
        """The view of a state vector ``y`` (position, velocity, attitude, rates first;
        :mod:`rocketsim.layout`), copied so later steps do not change it;
        ``p`` as for the constructor."""
        view = cls.__new__(cls)
        view.t, view._state = float(t), y[:N_STATE].copy()
        view._atmosphere, view.mu, view._p = atmosphere, mu, _EARTH_P if p is None else p
        return view

    def following(self, state: np.ndarray, readings: np.ndarray | None = None) -> "StateView":
        """A view of the same body as this one (its air, ``mu`` and parameters) over
        ``state`` itself (position, velocity, attitude, rates: a C-contiguous float64
        array of :data:`~rocketsim.layout.N_STATE` numbers), not a copy: for a state
        its owner rewrites in place from step to step, the view then moved to the
        step's time with :meth:`at`. Its readings go to one array of its own, written
        again at each instant: what it returns of them (and of the state) is read
        within the instant, or copied. ``readings``: that array, where the owner writes
        the place's readings with the state (:func:`place_readings_into`: a compiled
        run's), else a new one, where :meth:`at` computes them."""
        out, p = np.empty(N_READINGS) if readings is None else readings, self._p
        fixed = dict(t=self.t, _state=state, _atmosphere=self._atmosphere, mu=self.mu, _p=p,
                     position=state[R:R + 3], velocity=state[V:V + 3], attitude=state[Q:Q + 4],
                     body_rates=state[W:W + 3], _out=out,
                     _places=None if readings is not None else _bound(place_readings, out, self.t, state, p))
        fixed["_fixed"] = fixed         # what at() keeps; the view's own dict a copy of it
        view = StateView.__new__(StateView)
        view.__dict__ = fixed.copy()
        return view

    def at(self, t: float) -> None:
        """A view :meth:`following` a state, moved to mission time ``t`` (s), its state
        rewritten by its owner: everything derived is read again, the place's readings
        at once (a view is moved to a step to be read there)."""
        fixed = self._fixed
        now = self.__dict__
        if len(now) != len(fixed) + 1:      # more read than the place: forgotten
            self.__dict__ = now = fixed.copy()
            now["_place"] = fixed["_out"]
        now["t"] = t
        if fixed["_places"] is not None:
            fixed["_places"](fixed["_out"], t, fixed["_state"], fixed["_p"])

    # --- the state, sliced at the first read (a view of_state) ---------------------
    @_once
    def position(self) -> np.ndarray:
        return self._state[R:R + 3]

    @_once
    def velocity(self) -> np.ndarray:
        return self._state[V:V + 3]

    @_once
    def attitude(self) -> np.ndarray:
        return self._state[Q:Q + 4]

    @_once
    def body_rates(self) -> np.ndarray:
        return self._state[W:W + 3]

    # --- the step's readings: the place's, or all, in one compiled call -----------
    @_once
    def _place(self) -> np.ndarray:
        """The readings of the place (:func:`place_readings`: its slots alone set), or all of
        them if read already."""
        found = self.__dict__.get("_buffer")
        if found is not None:
            return found
        out = self._out
        if out is None:
            return self._buffer
        _bound(place_readings, out, self.t, self._state, self._p)(out, self.t, self._state, self._p)
        return out

    @_once
    def _buffer(self) -> np.ndarray:
        out = self._out
        if out is None:
            return step_readings(self.t, self.position, self.velocity, self.attitude, self._p)
        _bound(state_readings, out, self.t, self._state, self._p)(out, self.t, self._state, self._p)
        return out

    @_once
    def _out(self) -> np.ndarray | None:
        """The array the readings go to through the bound kernels (:func:`_bound`), or None
        for a view they cannot be bound for (given its vectors, or parameters not
        C-contiguous): :func:`step_readings` then."""
        if "_state" not in self.__dict__ or not self._p.flags.c_contiguous:
            return None
        return np.empty(N_READINGS)

    # --- where ------------------------------------------------------------
    @_once
    def geodetic(self) -> tuple[float, float, float]:
        """(latitude rad, longitude rad, height above WGS84 m)."""
        return tuple(self._place[LATITUDE:HEIGHT + 1].tolist())

    @property
    def height(self) -> float:
        """Height above the central body's ellipsoid (WGS84 about Earth), m."""
        return self._place.item(HEIGHT)

    @property
    def enu(self) -> np.ndarray:
        """Rows: local east, north, up unit vectors in ECI axes."""
        return self._place[ENU:ENU + 9].reshape(3, 3)

    # --- motion -----------------------------------------------------------
    @property
    def surface_velocity(self) -> np.ndarray:
        """Velocity relative to the central body's turning ground, ECI axes (m/s)."""
        return self._place[SURFACE:SURFACE + 3]

    @property
    def vertical_speed(self) -> float:
        return self._place.item(CLIMB)

    @property
    def horizontal_speed(self) -> float:
        return self._place.item(GROUND_SPEED)

    @property
    def radial(self) -> np.ndarray:
        return self._buffer[RADIAL:RADIAL + 3]

    @property
    def prograde(self) -> np.ndarray:
        return self._buffer[PROGRADE:PROGRADE + 3]

    @property
    def normal(self) -> np.ndarray:
        return self._buffer[NORMAL:NORMAL + 3]

    @property
    def surface_prograde(self) -> np.ndarray:
        return self._buffer[SURFACE_PROGRADE:SURFACE_PROGRADE + 3]

    # --- attitude -----------------------------------------------------------
    @property
    def axes(self) -> np.ndarray:
        """Body x (nose), y, z as the columns of the body -> ECI matrix."""
        return self._buffer[AXES:AXES + 9].reshape(3, 3)

    @_once
    def euler(self) -> tuple[float, float, float]:
        """(pitch, heading, roll) in radians (see the module's conventions)."""
        return tuple(self._buffer[PITCH:ROLL + 1].tolist())

    # --- air --------------------------------------------------------------
    @_once
    def air(self) -> tuple:
        """(density, pressure, temperature, speed of sound, wind ECI, air velocity ECI)."""
        lat, lon, height = self.geodetic
        return air_here(*self._atmosphere().arrays(), lat, lon, height, self.t, self.position,
                        self.velocity, self._p[P_SPIN])

    @_once
    def airspeed(self) -> float:
        return _norm(self.air[5])

    @_once
    def mach(self) -> float:
        return self.airspeed / self.air[3]

    @_once
    def dynamic_pressure(self) -> float:
        return 0.5 * self.air[0] * self.airspeed ** 2

    @_once
    def angle_of_attack(self) -> float:
        """Angle between the nose and the air-relative velocity (rad, 0 in still air)."""
        v_air = self.air[5]
        speed = np.linalg.norm(v_air)
        if speed == 0.0:
            return 0.0
        return math.acos(float(np.clip(self.axes[:, 0] @ v_air / speed, -1.0, 1.0)))

    # --- gravity and orbit ------------------------------------------------
    @property
    def gravity(self) -> float:
        """Magnitude of the local gravitational acceleration of the central body (point
        mass + J2), m/s^2."""
        return self._buffer.item(GRAVITY)

    @_once
    def effective_gravity(self) -> float:
        """``|g| - v_h^2 / r``, ``v_h`` the inertial horizontal speed
        (docs/physics.md#effective-gravity)."""
        r = _norm(self.position)
        v = self.velocity
        v_radial = v @ self.position / r
        v_h2 = max(float(v @ v - v_radial ** 2), 0.0)
        return self.gravity - v_h2 / r

    @_once
    def orbit(self) -> Elements:
        return state_to_elements(self.position, self.velocity, self.mu)

    @_once
    def time_to_apoapsis(self) -> float:
        return time_to_apoapsis(self.position, self.velocity, self.mu)
