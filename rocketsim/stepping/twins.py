"""Every decision of the Python side after a step, and its twin in each compiled run.

After a step the world's Python side may record an event (liftoff, max-Q, a
touchdown...), end a body's flight or stop the flight. A compiled run
(:mod:`rocketsim.stepping.runs`) flies on past a step only where it is sure that
the Python side would do none of that there: a decision it does not test for
would be flown past in silence. :data:`TWINS` is the map of them: for each
decision of the Python side (an event, by the name it is recorded with; a stop
with no event of its own, or an event whose name its caller gives, by the
function that makes it), the function of :mod:`rocketsim.sim` that makes it and,
for each compiled run, the kernel that hands such a step back to Python (a test
of :mod:`rocketsim.stepping.quiet`, or the run's own) or, as a sentence, why
that run needs none.

``tests/house/test_twins.py`` reads the events and stops of :mod:`rocketsim.sim` from
its source and fails on any that is missing here, or here but gone from there,
on a twin whose docstring does not name the Python function it mirrors, on a
test of :mod:`rocketsim.stepping.quiet` that is nobody's twin and on a compiled
run with no column here.
"""

from typing import NamedTuple

from rocketsim.stepping import quiet, runs


class Twin(NamedTuple):
    """A decision of the Python side and, for each compiled run, the kernel that tests
    for it or why the run needs none (a sentence)."""

    python: str         # the function that makes the decision (dotted)
    fly_run: object
    fly_part: object
    coast_run: object


# why a run needs no twin of a decision
RIGID = ("it flies a rigid body: the flight events watch a staged vehicle's engines, air and parachutes, "
         "its checks its loads and contacts")
PARACHUTES = "a vehicle with parachutes is flown one step at a time (rocketsim.sim.window_plans.plan)"
NO_FIELD = ("a part with an n-body field is flown one step at a time (rocketsim.sim.window_plans.plan); "
            "without one, nothing is handed over")
COASTS_ALONE = ("it flies only bodies that coast alone (rocketsim.sim.schedule.Schedule.coasts_alone): no "
                "event left to watch, no n-body field, no program running, the ground out of reach")
COMMANDED = ("a program's command: a program runs only in Python, and every run returns at the step its "
             "program wakes, its compiled condition holds or, resumed between the run's steps, it acts")
SPLIT = "made at a split, a program's command (" + COMMANDED + ")"
CRUISING = "cruise rails are flown by the world's loop (rocketsim.sim.world.World._cruise), never in a run"

_EVENTS = "rocketsim.sim.flight_events.FlightEvents."
_CHECKS = "rocketsim.sim.vehicle_checks.VehicleChecks."


def _python_only(python: str, why: str) -> Twin:
    """A decision no run meets: each run's reason ``why``."""
    return Twin(python, why, why, why)


TWINS = {
    # the flight events (rocketsim.sim.flight_events)
    "liftoff": Twin(_EVENTS + "after_step", quiet.below_liftoff, quiet.below_liftoff, COASTS_ALONE),
    "max_q": Twin(_EVENTS + "_max_q", quiet.max_q_quiet, RIGID, RIGID),
    "MECO": Twin(_EVENTS + "_stages_dry", quiet.events_quiet, RIGID, RIGID),
    "SECO": Twin(_EVENTS + "_stages_dry", quiet.events_quiet, RIGID, RIGID),
    "stage_dry": Twin(_EVENTS + "_stages_dry", quiet.events_quiet, RIGID, RIGID),
    "burnout": Twin(_EVENTS + "_burnouts", quiet.events_quiet, RIGID, RIGID),
    "off_rail": Twin(_EVENTS + "_off_rail", quiet.events_quiet, RIGID, RIGID),
    "apogee": Twin(_EVENTS + "_parachutes", PARACHUTES, RIGID, RIGID),
    "parachute_inflated": Twin(_EVENTS + "_parachutes", PARACHUTES, RIGID, RIGID),
    "parachute_released": Twin(_EVENTS + "_parachutes", PARACHUTES, RIGID, RIGID),
    "parachute_deployed": Twin(_EVENTS + "deploy", PARACHUTES, RIGID, RIGID),
    "orbit": Twin(_EVENTS + "_orbit", quiet.orbit_and_soi_quiet, quiet.orbit_and_soi_quiet, COASTS_ALONE),
    # a vehicle's checks (rocketsim.sim.vehicle_checks)
    "breakup": Twin(_CHECKS + "after_step", quiet.checks_quiet, RIGID, RIGID),
    "touchdown": Twin(_CHECKS + "after_step", quiet.checks_quiet, RIGID, RIGID),
    "tip-over": Twin(_CHECKS + "after_step", quiet.checks_quiet, RIGID, RIGID),
    "heat shield failure": Twin(_CHECKS + "_heat", quiet.checks_quiet, RIGID, RIGID),
    # the world's (rocketsim.sim.world, rocketsim.sim.handover)
    "impact": Twin("rocketsim.sim.world.World.after_advance", runs.fly_run, runs.fly_part, COASTS_ALONE),
    "soi_handover": Twin("rocketsim.sim.handover.hand_over", quiet.orbit_and_soi_quiet, NO_FIELD, COASTS_ALONE),
    "cruise_end": _python_only("rocketsim.sim.world.World._cruise", CRUISING),
    "world.World.check_finite": Twin("rocketsim.sim.world.World.check_finite", quiet.surely_finite,
                                     quiet.surely_finite, runs.coast_run),
    # commanded: by a program, through the flight computer (rocketsim.sim.staging, rocketsim.sim.craft)
    "fairing jettison": _python_only("rocketsim.sim.staging.jettison_fairing", COMMANDED),
    "payload deploy": _python_only("rocketsim.sim.staging.deploy_payload", COMMANDED),
    "separation": _python_only("rocketsim.sim.staging.separate", COMMANDED),
    "not followed": _python_only("rocketsim.sim.staging.leave_unfollowed", SPLIT),
    "craft.BodyCraft.event": _python_only("rocketsim.sim.craft.BodyCraft.event", COMMANDED),
}
