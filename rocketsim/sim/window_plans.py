"""How each body flies a window's next segment (:mod:`rocketsim.sim.window`): a compiled run
of a vehicle, a run reading its program between its steps, a tumbling part's run, the
loop's batch, or one step at a time (:func:`plan`), and one body at most reading its
program inside a run (:func:`one_of_steps`).
"""

from __future__ import annotations

import math

from rocketsim.jit import compiling_elsewhere
from rocketsim.dynamics.derivative import radial_height
from rocketsim.dynamics.third_bodies import field_of
from rocketsim.flight.conditions import NO_CONDITION
from rocketsim.stepping import runs

# how a body flies a segment (see plan)
VEHICLE, STEPS, PART, BATCH = "vehicle", "steps", "part", "batch"


def _waiting(body) -> bool:
    runner = body.runner
    return runner is not None and not runner.finished and runner.waiting_on_predicate


def wake_step(world, body) -> float:
    """The step at which ``body``'s program wakes from its sleep (inf: it has none, has
    finished, or waits on a condition, which its compiled run tests)."""
    runner = body.runner
    if runner is None or runner.finished or runner.waiting_on_predicate:
        return math.inf
    return world.k + max(1, world.schedule.wake_steps(runner))


def plan(world, body, first: bool, seconds: float):
    """How ``body`` flies from the world's step (see :mod:`rocketsim.sim.window`): ``(VEHICLE, steering,
    condition)``, a compiled run of a vehicle with aerodynamics; ``(STEPS, steering,
    otherwise)``, one whose program waits on a condition read in Python or wakes at the next
    step (``fc.step()``), read between the steps of a run (:meth:`rocketsim.sim.window._Window._steps`;
    ``otherwise``: its plan where another body has that run, :func:`one_of_steps`: for a
    program woken at the next step the compiled run to it, else None); ``(PART,)``, a tumbling
    part's; ``(BATCH,)``, the loop's batch of a body none of whose steps has anything for
    Python; None: one step at a time (also while a second process compiles the run's
    kernel on a cold cache: the same bits, flown meanwhile). ``first``: the loop has run the
    autopilots of this step (a folded one left its step in ``body.steering``); ``seconds``:
    to the window's end."""
    checks, watch = body.checks, body.watch
    if body.vehicle is None:
        if (body.runner is not None and not body.runner.finished) or field_of(body.p) is not None:
            return None
        if body.drag is not None and radial_height(body.y, body.p) <= world.schedule.rails_floor(body):
            return None if compiling_elsewhere(runs.fly_part) else (PART,)
        return (BATCH,) if world.schedule.coasts_alone(body, seconds) else None
    if watch is None or checks is None or body.vehicle.parachutes or compiling_elsewhere(runs.fly_run):
        return None
    if not checks.every_step(body) or world.schedule.cruising(body):
        return None
    condition = NO_CONDITION
    if _waiting(body):
        condition = body.runner.condition
        if body.central != "earth":
            return None
    steering = None
    if body.attitude_command is not None:
        steering = body.steering if first else body.fc.folded()
        if steering is None:
            return None
    if not watch.max_q_done and (body.central != "earth" or not body.flies_in_days_air()):
        return None
    if condition is None:
        return STEPS, steering, None
    if condition is NO_CONDITION and body.central == "earth" and wake_step(world, body) == world.k + 1:
        return STEPS, steering, (VEHICLE, steering, condition)     # woken at every step, as by fc.step()
    return VEHICLE, steering, condition


def one_of_steps(plans: dict) -> dict:
    """``plans`` with a run reading its program between its steps (:meth:`rocketsim.sim.window._Window._steps`)
    for one body at most, the first; the others as their plans say otherwise (two bodies'
    programs read ahead of the window's queue would not be read in the loop's order)."""
    steps = sorted(i for i, plan in plans.items() if plan is not None and plan[0] == STEPS)
    return {i: plan[2] if i in steps[1:] else plan for i, plan in plans.items()}
