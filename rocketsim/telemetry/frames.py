"""The frame tree of a run's telemetry: where each frame the Foxglove 3-D panel draws hangs.

Frames (``foxglove.FrameTransform``: a child frame's pose in its parent):

* ``eci`` and ``ecef``: Earth's inertial frame (the ECI of the mission epoch)
  and its Earth-fixed frame, ``eci`` turned about ``z`` by the Earth rotation
  angle (:func:`rocketsim.frames.earth_fixed.earth_rotation_angle`);
* ``moon_inertial``, ``mars_inertial``: the frame a state about the Moon or
  Mars is in (the body's IAU pole as ``z``, the node of its equator on the
  J2000 equator as ``x``, fixed at the sphere-of-influence handover), and
  ``moon_fixed``, ``mars_fixed``: it turned about ``z`` by the body's IAU
  prime-meridian angle ``W`` (:func:`rocketsim.bodies.orientation.pole_and_meridian`),
  the axes planetocentric longitudes are read in
  (:func:`rocketsim.sim.central.planetocentric`); ``sun_inertial``: J2000
  equatorial axes at the Sun (no fixed frame);
* the *root*: the inertial frame of the first state written. Every other
  central body's inertial frame hangs under it, at that body's place relative
  to the root's centre (the n-body field's ephemeris,
  :func:`rocketsim.dynamics.third_bodies.bodies_at`) and turned by the change
  of axes. Two bodies handed over to Mars at different dates are in slightly
  different Mars frames (the pole moves): the second is ``mars_inertial_2``
  (and ``mars_fixed_2``);
* ``<body>``: the body's axes at its centre of mass, under the inertial frame
  its state is expressed in: the root's, or, about another centre, the frame
  ``<body>/<inertial frame>`` (``lunar-orbiter/moon_inertial``). A frame has
  one parent for the whole file (the app and its checks relate frames through
  one tree), so at a handover the body goes on in the frame of its new
  centre;
* ``mission``: the centre of mass of the lead body (the first one, the
  stack) with the root's axes, under the root for the whole file, so it
  follows the stack across handovers (from Earth to Mars). Followed in the
  3-D panel, it keeps what is looked at near the origin: the app composes
  transforms in 64-bit floats but draws in 32-bit ones, about 0.5 m steps at
  Earth's radius from the origin, a millionth of that a metre away.

A central body's frames are published on ``/<body>/transform`` (``/earth/transform``...)
when its frame is first used and then once a second of mission time: Foxglove
interpolates between transforms, and the fastest of them, Earth's turn, is
0.004 deg in a second.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from rocketsim.bodies.orientation import pole_and_meridian
from rocketsim.constants import SECONDS_PER_DAY
from rocketsim.dynamics.nbody import make_field
from rocketsim.dynamics.third_bodies import bodies_at
from rocketsim.ephemeris.solar_system import BODIES
from rocketsim.frames.earth_fixed import earth_rotation_angle
from rocketsim.frames.quaternion import quat_from_matrix
from rocketsim.telemetry import foxglove

MISSION_FRAME = "mission"
_NAMES = {"earth": ("eci", "ecef")}


class CentralFrame(NamedTuple):
    """The inertial frame a state is expressed in: its centre (``"earth"``...), the
    rotation matrix taking its axes to J2000 equatorial ones (9 floats, row by row),
    and the TT Julian date of mission time 0 (nan when unknown: an Earth flight without
    the n-body field, whose only frames are Earth's)."""

    center: str
    rotation: tuple
    jd0_tt: float


def central_frame(center: str, rotation, jd0_tt: float) -> CentralFrame:
    return CentralFrame(center, tuple(float(x) for x in np.asarray(rotation).reshape(9)), float(jd0_tt))


def frame_names(center: str, k: int = 1) -> tuple[str, str | None]:
    """``(inertial, fixed)`` frame names of ``center``'s ``k``-th frame (fixed: None for the Sun)."""
    inertial, fixed = _NAMES.get(center, (f"{center}_inertial", f"{center}_fixed"))
    if center == "sun":
        fixed = None
    if k > 1:
        inertial, fixed = f"{inertial}_{k}", None if fixed is None else f"{fixed}_{k}"
    return inertial, fixed


def _turn_about_z(angle: float) -> tuple:
    half = 0.5 * angle
    return (math.cos(half), 0.0, 0.0, math.sin(half))


class FrameTree:
    """The central bodies' frames of one file (see the module), as they come into use."""

    def __init__(self):
        self._frames: dict[CentralFrame, tuple[str, str | None]] = {}
        self._root: CentralFrame | None = None
        self._root_field = None
        self._at: dict[CentralFrame, int] = {}     # frame -> the second of its last transforms
        self._second = None                         # the second of the last call of due

    @property
    def root(self) -> str | None:
        """The root frame's name (None before the first frame)."""
        return None if self._root is None else self._frames[self._root][0]

    def body_frame(self, body: str, frame: CentralFrame) -> tuple[str, str]:
        """``(parent, child)`` of ``body``'s transform when its state is in ``frame``."""
        parent = self.inertial(frame)
        return parent, body if frame == self._root else f"{body}/{parent}"

    def is_root(self, frame: CentralFrame) -> bool:
        return frame == self._root

    def in_root(self, frame: CentralFrame, r, t: float) -> np.ndarray:
        """Position ``r`` (m, in ``frame``) in the root frame at mission time ``t`` (s)."""
        place, turn = self._placement(frame, t)
        return place + turn @ np.asarray(r, dtype=float)

    def inertial(self, frame: CentralFrame) -> str:
        """The name of ``frame``, a new frame of the tree if it is not one yet."""
        names = self._frames.get(frame)
        if names is None:
            if self._root is None:
                self._root = frame
            elif math.isnan(self._root.jd0_tt):
                raise ValueError(f"a state about {frame.center} in a run whose frame is Earth's "
                                 "without the n-body field's ephemeris")
            k = 1 + sum(1 for other in self._frames if other.center == frame.center)
            names = self._frames[frame] = frame_names(frame.center, k)
        return names[0]

    def due(self, t: float, stamp: int) -> list[tuple[str, dict]]:
        """``(central body, FrameTransform)`` to write at mission time ``t`` (s), log time
        ``stamp`` (ns): the transforms of each frame new since the last call or not
        written in this second of mission time."""
        second = math.floor(t)
        if second == self._second and len(self._at) == len(self._frames):
            return []               # all written in this second
        self._second = second
        out = []
        for frame, (inertial, fixed) in self._frames.items():
            if self._at.get(frame) == second:
                continue
            self._at[frame] = second
            time = foxglove.timestamp(stamp)
            if frame != self._root:
                out.append((frame.center, self._in_root(frame, inertial, t, time)))
            if fixed is not None:
                out.append((frame.center, foxglove.frame_transform(
                    time, inertial, fixed, (0.0, 0.0, 0.0), _turn_about_z(self._turn(frame, t)))))
        return out

    @staticmethod
    def _turn(frame: CentralFrame, t: float) -> float:
        """Angle (rad) about ``z`` from the inertial frame's ``x`` to the body-fixed frame's."""
        if frame.center == "earth":
            return earth_rotation_angle(t)
        return float(pole_and_meridian(frame.center, frame.jd0_tt + t / SECONDS_PER_DAY)[2])

    def _placement(self, frame: CentralFrame, t: float) -> tuple[np.ndarray, np.ndarray]:
        """``frame``'s centre in the root frame at ``t`` (m: where the ephemeris has it) and
        the matrix turning its components into the root's."""
        root = self._root
        if self._root_field is None:
            self._root_field = make_field(root.center, root.jd0_tt, rotation=np.reshape(root.rotation, (3, 3)))
        place = bodies_at(self._root_field, t)[0][BODIES.index(frame.center)]
        return place, np.reshape(root.rotation, (3, 3)).T @ np.reshape(frame.rotation, (3, 3))

    def _in_root(self, frame: CentralFrame, name: str, t: float, time: dict) -> dict:
        """``frame`` in the root: its centre where the ephemeris has it, its axes turned."""
        place, turn = self._placement(frame, t)
        return foxglove.frame_transform(time, self.root, name, place.tolist(), quat_from_matrix(turn).tolist())
