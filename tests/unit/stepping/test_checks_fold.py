"""One compiled call per step of a vehicle with aerodynamics (for speed): the
autopilot's step, the RK4 advance and the checks' figures folded into
:func:`rocketsim.stepping.checked_step.advance_checked`.

A pure speed refactor: the reference is the code before it, three calls
(:func:`rocketsim.flight.steering.steer_step`, :func:`rocketsim.dynamics.rk4.advance`,
:func:`rocketsim.stepping.checked_step.step_figures` on the arrays without contact
points), which these tests run side by side with the fold: same bits. The
breakup test's axial load is also checked against its closed form ``T / (m g0)``.
"""

import math
from pathlib import Path

import numpy as np
import pytest

from rocketsim.jit import Entries
from rocketsim.constants import G0
from rocketsim.dynamics import rk4
from rocketsim.dynamics.third_bodies import nbody_flag
from rocketsim.flight.fc import FlightComputer
from rocketsim.scenario.load import load
from rocketsim.sim import vehicle_checks, world as world_module
from rocketsim.sim.vehicle_checks import VehicleChecks
from rocketsim.stepping.checked_step import advance_checked
from rocketsim.sim.build import build_world
from tests.unit.vehicle.test_contact import _World
from tests.unit.vehicle.test_heating_limits import light_stage

MISSION = Path(__file__).resolve().parents[3] / "scenarios" / "falcon9-leo.yaml"


def test_a_16_g_burn_breaks_the_vehicle_through_the_folded_step():
    # the step's own figures fire the check, with the bits of the separate call and the
    # closed form T / (m g0) at the state after the step (the thrust is steady: spooled up)
    model, body = light_stage(100e3)
    body.kernels = Entries()
    checks, world = VehicleChecks(), _World()
    body.y, taken = checks.advance(body, 250, 0.02, 1)
    body.t = (250 + taken) * 0.02
    checks.after_step(world, body, 0.02)
    name, figures = world.events[0]
    assert name == "breakup" and figures["cause"] == "axial load" and not body.flying
    mass = model.mass_properties(body.y)[0]
    assert figures["axial_load_g"] == pytest.approx(100e3 / (mass * G0), rel=1e-12)
    separate = _World()
    body.flying = True
    VehicleChecks().after_step(separate, body, 0.02)        # no figures at hand: the separate call
    assert separate.events == world.events


def _fly(seconds, fold, monkeypatch, sensors="truth"):
    """The shipped mission's first ``seconds`` (on the pad, liftoff, the climb through the
    air) with ``sensors``: final states, events, the checks' inputs at every step and how
    many steps took the fold's figures (out of contact) and steered inside it."""
    seen = {"figures": [], "near": 0, "far": 0, "steered": 0}

    def recording_breakup(q, alpha, axial, *limits, original=vehicle_checks.breakup):
        seen["figures"].append((q, alpha, axial))
        return original(q, alpha, axial, *limits)

    monkeypatch.setattr(vehicle_checks, "breakup", recording_breakup)
    if fold:
        call = Entries.call

        def counting_call(entries, kernel, key, *args):
            out = call(entries, kernel, key, *args)
            if kernel is advance_checked:
                seen["near" if out[2] else "far"] += 1
                seen["steered"] += bool(args[6])
            return out

        monkeypatch.setattr(Entries, "call", counting_call)
    else:       # the code before the fold: the autopilot's own call, the plain advance, the figures' call
        autopilot = FlightComputer.autopilot
        monkeypatch.setattr(FlightComputer, "autopilot", lambda fc, fold=False: autopilot(fc))

        def unfolded(checks, body, k0, h, n, steering=None):
            assert steering is None
            return body.kernels.call(rk4.advance, body.vehicle.arrays, body.y, k0, h, n, body.p,
                                     body.vehicle.arrays, nbody_flag(body.p))

        monkeypatch.setattr(VehicleChecks, "advance", unfolded)
    # every step through the loop's one-step path (not the compiled runs of rocketsim.sim.window,
    # whose steps are those of the fold: tests/unit/stepping/test_runs.py)
    monkeypatch.setattr(world_module, "fly_window", lambda world, length: False)
    world = build_world(load(MISSION, {"sensors": sensors}), duration=seconds)
    summary = world.run()
    monkeypatch.undo()
    return [b.y.copy() for b in world.bodies], summary, seen


@pytest.mark.parametrize("sensors", ["truth", "realistic"])
def test_the_folded_step_flies_the_same_bits_as_three_calls(monkeypatch, sensors):
    # with realistic sensors the folded step steers on the navigation estimate it makes
    # itself (with the truth's ambient pressure for the engines), the three calls on the
    # flight computer's (rocketsim.flight.navigation) and the truth's air read in Python
    states, summary, seen = _fly(12.0, True, monkeypatch, sensors)
    states_before, summary_before, seen_before = _fly(12.0, False, monkeypatch, sensors)
    assert all(np.array_equal(a, b) for a, b in zip(states, states_before, strict=True))
    assert summary == summary_before
    assert seen["figures"] == seen_before["figures"] and len(seen["figures"]) == 600
    # both ways of the figures ran: on the pad (legs on the ground) and in the air
    assert seen["near"] > 0 and seen["far"] > 0 and seen["steered"] > 0


def test_after_a_staging_within_the_step_the_autopilot_runs_on_the_estimate_read_before_it():
    # the program read the estimate, then dropped the fairing in the same step: the body's
    # state is new, the estimate is the stack's; the autopilot steers on that estimate (as
    # before the fold) in its own call, not on the new state inside the step's
    world = build_world(load(MISSION))
    body = world.bodies[0]
    body.fc.point(math.radians(80.0), math.radians(90.0))
    assert body.fc.autopilot(fold=True) is not None         # nothing read yet: folded
    body.fc.position                                        # the program reads the estimate
    assert body.fc.autopilot(fold=True) is not None         # the truth's current view: folded
    world.jettison_fairing(body)
    assert body.fc.autopilot(fold=True) is None             # ran here, on the estimate read before
