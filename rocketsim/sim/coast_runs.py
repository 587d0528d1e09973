"""Runs of whole sample intervals: rigid bodies coasting with nothing for Python, sampled in one call.

A rigid body with no program, no drag, no n-body field, no event left to watch
and out of the ground's reach (:meth:`rocketsim.sim.schedule.Schedule.coasts_alone`)
is flown by the world's loop one telemetry interval at a time: the RK4 steps
(:func:`rocketsim.dynamics.rk4.advance`), then the finiteness test and the
sample, all in Python between intervals. While every flying body is such a body
(a spacecraft coasting in orbit), :func:`fly_coast` flies up to :data:`MAX_INTERVALS`
intervals in one compiled call per body (:func:`rocketsim.stepping.runs.coast_run`):
the same ``advance`` of each interval, the same test of the state, and each
interval's sample figures (:func:`rocketsim.stepping.sample_figures.figures`, the
arguments of the world's sampler) into rows the world then writes in the loop's order (by
interval, then body). The same steps and the same figures: the same file.

The run leaves the last interval's sample to the loop (its ``check_finite`` and
sampling at a sample step), so the loop's order after the run is its order after
any batch. A state that is no longer finite ends the run at that interval: the
rows before it are written and the loop's test raises its error there.
"""

from __future__ import annotations

import numpy as np

from rocketsim.jit import compile_beside, compiling_elsewhere
from rocketsim.dynamics.third_bodies import nbody_flag
from rocketsim.sim import sampling
from rocketsim.stepping.runs import coast_run
from rocketsim.stepping.sample_figures import N_SAMPLE_RIGID

MAX_INTERVALS = 128     # sample intervals in one run (12.8 s at 10 Hz): the rows waiting to be written


def fly_coast(world) -> bool:
    """Fly the world's bodies whole sample intervals from its step ``k`` (a sample
    step) in :func:`coast_run`\\ s, writing every interval's samples but the last, and
    leave the world's step count at the last interval's end; False (nothing done)
    unless every flying body coasts alone (see the module) for at least two intervals,
    or while a second process compiles :func:`coast_run` (the loop flies the same steps)."""
    every = world.sample_every
    m = min(MAX_INTERVALS, (world.n_steps - world.k) // every)
    flying = [body for body in world.bodies if body.flying]
    if m < 2 or compiling_elsewhere(coast_run) or not all(_coasts(world, body, m * every * world.h)
                                                          for body in flying):
        return False
    k0, h = world.k, world.h
    runs = []
    for body in flying:
        fixed, shape = sampling.arguments(body, world.gmst0)
        if world.telemetry is None:
            shape = None                    # no samples: the same call, no rows
        rows = np.empty((m - 1 if shape is not None else 0, N_SAMPLE_RIGID))
        y, flown = coast_run(*_coast_arguments(body, k0, h, every, m, rows, fixed))
        runs.append((body, y, flown, rows, shape))
    flown = min(run[2] for run in runs)     # a state no longer finite: nothing written from it on
    if len(runs) == 1:                      # one body's samples: one block
        body, _, _, rows, shape = runs[0]
        if shape is not None:
            world.telemetry.sample_rows(body.name, rows[:flown - 1], shape)
    else:                                   # the bodies' samples interleaved, sample by sample
        for j in range(flown - 1):
            for body, _, _, rows, shape in runs:
                if shape is not None:
                    world.telemetry.sample(body.name, rows[j], shape)
    for body, y, _, _, _ in runs:
        body.y, body.t = y, (k0 + flown * every) * h
    world.k = k0 + flown * every
    return True


def _coast_arguments(body, k0: int, h: float, every: int, m: int, rows: np.ndarray, fixed: tuple) -> tuple:
    """The arguments of :func:`coast_run` for ``body`` (see there)."""
    return body.y, k0, h, every, m, body.p, nbody_flag(body.p), rows, fixed


def compile_coasts_beside(world) -> None:
    """On a cold cache, queue :func:`coast_run`'s kernel for each rigid body coasting about
    Earth for a second process to compile (:func:`rocketsim.jit.compile_beside`) while
    this one compiles the first sample's."""
    for body in world.bodies:
        if body.vehicle is None and body.central == "earth":
            fixed, _ = sampling.arguments(body, world.gmst0)
            compile_beside(coast_run, _coast_arguments(body, 0, world.h, world.sample_every, 2,
                                                       np.empty((1, N_SAMPLE_RIGID)), fixed))


def _coasts(world, body, seconds: float) -> bool:
    """Whether ``body`` coasts alone for ``seconds`` (s) on the world's RK4 path about
    Earth: no attitude command, not cruising, not on sleep rails."""
    schedule = world.schedule
    return (body.vehicle is None and body.central == "earth" and body.attitude_command is None
            and not schedule.cruising(body) and schedule.coasts_alone(body, seconds)
            and not schedule.on_rails(body))
