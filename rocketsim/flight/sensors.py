"""Sensor errors: a wandering bias (first-order Gauss-Markov) plus white noise.

docs/physics.md#sensors. The discrete bias process (the exact discretisation of a
first-order Gauss-Markov process; Brown & Hwang, *Introduction to Random Signals and
Applied Kalman Filtering*, 4th ed., sec. 2.9)::

    b[k+1] = exp(-dt/tau) b[k] + sigma_b sqrt(1 - exp(-2 dt/tau)) n[k],   n ~ N(0, 1)

Every measured quantity (and every axis of a vector) has its own random
stream, spawned from the run's seed by a stable key (the quantity's name), so
adding a sensor never changes another's numbers. Streams are drawn in blocks
for speed; a block is a deterministic function of the seed, the key and the
block's index, so the numbers do not depend on how they are consumed.

The error budget (1 sigma; ``hard`` triples every figure). The bias figures
are those of docs/physics.md#sensors; the correlation times within its
30-60 s and the white-noise parts are this project's choices:

=================  =============================  =========  ==================
quantity           bias sigma                     tau (s)    white sigma
=================  =============================  =========  ==================
position (3 axes)  2 m                            30/45/60   0.5 m
velocity (3 axes)  0.01 m/s                       30/45/60   0.003 m/s
attitude (3 axes)  0.03 deg                       60         0.005 deg
body rates         0.0005 deg/s                   60         0.01 deg/s
radar altitude     --                             --         0.2 % + 0.05 m
q, rho, p          1 % (of the value)             60         0.2 %
airspeed, Mach     0.5 %                          60         0.1 %
angle of attack    0.2 deg                        60         0.05 deg
accelerometers     0.1 % (of the value)           60         0.02 %
propellant gauge   0.2 % of what is left          60         0.05 %
=================  =============================  =========  ==================
"""

from __future__ import annotations

import math
import zlib
from dataclasses import dataclass

import numpy as np

from rocketsim.jit import njit
from rocketsim.constants import DEG

BLOCK = 4096            # samples drawn at a time per stream

LEVELS = {"truth": 0.0, "realistic": 1.0, "hard": 3.0}

# the navigation estimate's quantities, three axes each (rocketsim.flight.navigation), and
# the first column of each in a compiled run's errors (Sensors.run_errors); the tanks'
# propellant gauges follow them
ESTIMATE = ("position", "velocity", "attitude", "rates")
E_POSITION, E_VELOCITY, E_ATTITUDE, E_RATES, E_GAUGES = 0, 3, 6, 9, 12
NO_ERRORS = np.zeros((0, 0, 3))     # the errors of the truth: none


@dataclass(frozen=True)
class ErrorSpec:
    """One quantity's error: bias sigma and correlation time, white sigma.

    ``relative`` errors scale with the measured value; ``floor`` is an
    absolute white-noise part added in quadrature-free sum (radar: 0.2 % + 5 cm).
    """

    bias: float
    tau: float
    white: float
    relative: bool = False
    floor: float = 0.0


ERRORS: dict[str, ErrorSpec] = {
    "position.x": ErrorSpec(2.0, 30.0, 0.5),
    "position.y": ErrorSpec(2.0, 45.0, 0.5),
    "position.z": ErrorSpec(2.0, 60.0, 0.5),
    "velocity.x": ErrorSpec(0.01, 30.0, 0.003),
    "velocity.y": ErrorSpec(0.01, 45.0, 0.003),
    "velocity.z": ErrorSpec(0.01, 60.0, 0.003),
    "attitude.x": ErrorSpec(0.03 * DEG, 60.0, 0.005 * DEG),
    "attitude.y": ErrorSpec(0.03 * DEG, 60.0, 0.005 * DEG),
    "attitude.z": ErrorSpec(0.03 * DEG, 60.0, 0.005 * DEG),
    "rates.x": ErrorSpec(0.0005 * DEG, 60.0, 0.01 * DEG),
    "rates.y": ErrorSpec(0.0005 * DEG, 60.0, 0.01 * DEG),
    "rates.z": ErrorSpec(0.0005 * DEG, 60.0, 0.01 * DEG),
    "radar_altitude": ErrorSpec(0.0, 1.0, 0.002, relative=True, floor=0.05),
    "dynamic_pressure": ErrorSpec(0.01, 60.0, 0.002, relative=True),
    "air_density": ErrorSpec(0.01, 60.0, 0.002, relative=True),
    "air_pressure": ErrorSpec(0.01, 60.0, 0.002, relative=True),
    "airspeed": ErrorSpec(0.005, 60.0, 0.001, relative=True),
    "mach": ErrorSpec(0.005, 60.0, 0.001, relative=True),
    "angle_of_attack": ErrorSpec(0.2 * DEG, 60.0, 0.05 * DEG),
    "acceleration": ErrorSpec(0.001, 60.0, 0.0002, relative=True),
    "propellant": ErrorSpec(0.002, 60.0, 0.0005, relative=True),
}


def stream_key(name: str) -> int:
    """A stable integer key of a quantity's name (CRC-32; the same on every machine)."""
    return zlib.crc32(name.encode("utf-8"))


@njit
def _gauss_markov(series, phi, drive, initial):
    """The bias recursion ``b[k] = phi b[k-1] + drive n[k]`` over a block, with
    ``phi b[-1]`` given as ``initial`` (the first-order Gauss-Markov process): the
    normals ``n`` of ``series`` replaced by the biases, in place."""
    previous = initial
    for k in range(series.shape[0]):
        previous = drive * series[k] + previous
        series[k] = previous
        previous = phi * previous


class ErrorStream:
    """The bias and white noise of one quantity, sample by sample (one per step).

    The bias starts from its stationary distribution (``N(0, sigma_b^2)``),
    so statistics hold from the first step. Levels scale every sigma. Sample
    ``k`` is column ``k mod BLOCK`` of block ``k // BLOCK`` (:meth:`block`); the
    two latest blocks drawn are kept, for the readings and for the compiled runs
    (:meth:`Sensors.run_errors`) alike.
    """

    def __init__(self, seed: int, name: str, spec: ErrorSpec, dt: float, level: float):
        self.spec = spec
        self._seed = seed
        self._key = stream_key(name)
        self._phi = math.exp(-dt / spec.tau)
        self._sigma = spec.bias * level
        self._drive = self._sigma * math.sqrt(1.0 - self._phi ** 2)
        self._white = spec.white * level
        self._floor = spec.floor * level
        self._drawn = 0             # blocks drawn
        self._last = 0.0            # the last bias of the last block drawn
        self._blocks: dict[int, np.ndarray] = {}
        self.index = 0              # step index of the next sample

    def _draw(self) -> None:
        """Draw the next block: biases, white noise, absolute white noise."""
        b = self._drawn
        sequence = np.random.SeedSequence(entropy=self._seed, spawn_key=(self._key, b))
        rows = np.random.Generator(np.random.PCG64(sequence)).standard_normal((3, BLOCK))
        if b == 0:
            initial = (self._sigma - self._drive) * rows[0, 0]      # b[0] = sigma_b n[0]
        else:
            initial = self._phi * self._last
        _gauss_markov(rows[0], self._phi, self._drive, initial)     # the draws, scaled in place
        rows[1] *= self._white
        rows[2] *= self._floor
        self._last = float(rows[0, -1])
        self._blocks[b] = rows
        self._blocks.pop(b - 2, None)
        self._drawn = b + 1

    def block(self, b: int) -> np.ndarray:
        """Rows (bias, white, absolute white) of the samples of steps ``b BLOCK`` to
        ``(b + 1) BLOCK - 1``, shape (3, BLOCK); blocks are drawn in order and the two
        latest kept (``ValueError`` for one passed over)."""
        while self._drawn <= b:
            self._draw()
        rows = self._blocks.get(b)
        if rows is None:
            raise ValueError(f"sensor block {b} was passed over (the latest is {self._drawn - 1})")
        return rows

    def sample(self) -> tuple[float, float, float]:
        """The next ``(bias, white, absolute white)``."""
        return self.at(self.index)

    def at(self, k: int) -> tuple[float, float, float]:
        """The error of step ``k`` (steps are read in increasing order; the
        samples of steps nobody read are passed over, so step k's error is the
        same whoever reads when)."""
        if k < self.index:
            raise ValueError(f"sensor step {k} was already read (next is {self.index})")
        rows = self.block(k // BLOCK)
        j = k % BLOCK
        self.index = k + 1
        return float(rows[0, j]), float(rows[1, j]), float(rows[2, j])

    def series(self, n: int) -> np.ndarray:
        """The next ``n`` samples as rows (bias, white, absolute white), shape (3, n).

        The same numbers :meth:`sample` would give one at a time (for studies
        of the error statistics over long holds).
        """
        parts = []
        while n > 0:
            j = self.index % BLOCK
            take = min(n, BLOCK - j)
            parts.append(self.block(self.index // BLOCK)[:, j:j + take])
            self.index += take
            n -= take
        return np.hstack(parts)

    def measure(self, truth: float, k: int | None = None) -> float:
        """``truth`` with the error of step ``k`` (default: the next sample)."""
        bias, white, floor = self.sample() if k is None else self.at(k)
        if self.spec.relative:
            return truth * (1.0 + bias + white) + floor
        return truth + bias + white + floor


class Sensors:
    """All of one body's error streams, at a level (``truth``, ``realistic``, ``hard``)."""

    def __init__(self, seed: int, body: str, level: str, dt: float):
        if level not in LEVELS:
            raise ValueError(f"unknown sensor level {level!r}; use one of {', '.join(LEVELS)}")
        self.level = level
        self.perfect = level == "truth"     # the truth's readings: no errors
        self._seed, self._body, self._dt, self._scale = seed, body, dt, LEVELS[level]
        self.streams: dict[str, ErrorStream] = {}
        self._run = None            # ((block, tanks), errors) of run_errors

    def stream(self, name: str) -> ErrorStream:
        """The stream of quantity ``name``; ``kind/detail`` names (``propellant/stage/tank``)
        take the error of ``kind`` and a stream of their own."""
        if name not in self.streams:
            spec = ERRORS[name.split("/", 1)[0]]
            self.streams[name] = ErrorStream(self._seed, f"{self._body}/{name}", spec, self._dt,
                                             self._scale)
        return self.streams[name]

    def vector(self, name: str, truth, k: int | None = None) -> np.ndarray:
        """A 3-vector measured axis by axis (``name.x``, ``.y``, ``.z``) at step ``k``."""
        return np.array([self.stream(f"{name}.{axis}").measure(value, k)
                         for axis, value in zip("xyz", truth)])

    def scalar(self, name: str, truth: float, k: int | None = None) -> float:
        """One quantity measured at step ``k``."""
        return self.stream(name).measure(truth, k)

    def run_errors(self, k: int, tanks: tuple[str, ...]) -> tuple[np.ndarray, int]:
        """``(errors, first)``: the errors of the estimate's quantities and of the tanks'
        propellant gauges (``propellant/<tank>`` of each name of ``tanks``) at the steps
        ``first`` to ``first + 2 BLOCK - 1``, ``first`` the start of step ``k``'s block:
        ``errors[k - first, c]`` is ``(bias, white, absolute white)`` of column ``c``
        (:data:`E_POSITION`... the axes x, y, z of each of :data:`ESTIMATE`, then from
        :data:`E_GAUGES` the tanks in order), the numbers :meth:`vector` and
        :meth:`scalar` read, for compiled code (:func:`measured`, :func:`gauged`); kept
        until the block or the tanks change. :data:`NO_ERRORS` for the truth."""
        if self.perfect:
            return NO_ERRORS, k
        b = k // BLOCK
        key = (b, tuple(tanks))
        last = self._run
        if last is None or last[0] != key:
            names = [f"{quantity}.{axis}" for quantity in ESTIMATE for axis in "xyz"]
            names += [f"propellant/{tank}" for tank in tanks]
            streams = [self.stream(name) for name in names]
            errors = np.empty((2 * BLOCK, len(names), 3))
            if last is not None and last[0] == (b - 1, key[1]):
                errors[:BLOCK] = last[1][BLOCK:]        # the block before's second half
            else:
                np.copyto(errors[:BLOCK], np.stack([stream.block(b) for stream in streams]).transpose(2, 0, 1))
            np.copyto(errors[BLOCK:], np.stack([stream.block(b + 1) for stream in streams]).transpose(2, 0, 1))
            self._run = (key, errors)
        return self._run[1], b * BLOCK


@njit(inline="always")     # a few operations: typed in its callers, no kernel of its own
def measured(truth, errors, j, c):
    """``truth`` with the error of column ``c`` of row ``j`` of a run's errors
    (:meth:`Sensors.run_errors`), as :meth:`ErrorStream.measure` adds an absolute one."""
    return truth + errors[j, c, 0] + errors[j, c, 1] + errors[j, c, 2]


@njit(inline="always")     # a few operations: typed in its callers, no kernel of its own
def gauged(truth, errors, j, c):
    """``truth`` with the relative error of column ``c`` of row ``j`` of a run's errors,
    as :meth:`ErrorStream.measure` applies one (a propellant gauge's)."""
    return truth * (1.0 + errors[j, c, 0] + errors[j, c, 1]) + errors[j, c, 2]
