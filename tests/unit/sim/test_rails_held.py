"""A sleeping vehicle holding an inertial direction goes on sleep rails, mode HELD.

The lunar orbiter (RCS quads handed to the autopilot) turns 2 deg onto an ECI
direction given by fc.point_at and sleeps 300 s in a 300 km orbit. Once the
autopilot has settled (nose within 0.01 deg, rates below 1e-4 rad/s:
rocketsim.sim.world.HOLD_SETTLED_ERROR / HOLD_SETTLED_RATE) the world puts it on
rails: its nose is set on the commanded direction and stays there.

References: the command itself for the attitude (the nose must be the commanded
unit vector to 1e-12, the rates exactly zero); for the orbit, the same flight
with the program awake every step (the full derivative, the autopilot steering
with the RCS throughout). The awake body keeps trimming within its settle band
with thrusters that are not pure couples, so the two orbits differ by the
trimming's small push, not to the bit (tolerance stated below).
Commands in turning frames: tests/unit/sim/test_rails_track.py.
Both flights take the 0.1 s headless step (the awake reference flown at 20 ms
costs about 1.7 ms a step with its RCS solve: 0.1 s steps and 300 s keep the
file near 4 s; rails and awake share the step either way).
"""

from pathlib import Path

import numpy as np

from rocketsim.layout import Q, R, V, W
from rocketsim.frames.quaternion import quat_rotate
from rocketsim.scenario.load import load
from rocketsim.sim.build import build_world

ROOT = Path(__file__).resolve().parents[3]
SECONDS = 300.0


def _world(write, program):
    write("program.py", program)
    write("mission.yaml", f"""\
        epoch: 2026-11-26T12:00:00Z
        start:
          orbit: {{altitude: 300 km, inclination: 28.5 deg}}
        duration: {SECONDS} s
        """)
    path = write("scenario.yaml", f"""\
        name: hold
        vehicle: {ROOT / 'vehicles' / 'lunar-orbiter.yaml'}
        mission: mission.yaml
        program: program.py
        step: 0.1 s
        """)
    return build_world(load(path))


def _nose(y):
    return quat_rotate(y[Q:Q + 4], np.array((1.0, 0.0, 0.0)))


def _direction(write):
    """An ECI direction 2 deg from the start attitude's nose (about body z)."""
    y = _world(write, "def main(fc):\n    pass\n").bodies[0].y
    z = quat_rotate(y[Q:Q + 4], np.array((0.0, 0.0, 1.0)))
    nose = _nose(y)
    a = np.radians(2.0)
    return np.cos(a) * nose + np.sin(a) * np.cross(z, nose)


def _fly(write, program):
    world = _world(write, program)
    body = world.bodies[0]
    railed = []
    steps = []
    start = [world.k]

    def progress(t):
        steps.append(world.k - start[0])
        railed.append(world.schedule.on_rails(body))
        start[0] = world.k

    world.on_progress = progress
    world.run()
    assert body.t == SECONDS
    return body, railed, steps, world.h


def test_a_settled_inertial_hold_sleeps_on_rails_with_its_nose_on_the_command(write):
    d = _direction(write)
    command = f"    fc.rcs(True)\n    fc.point_at([{float(d[0])!r}, {float(d[1])!r}, {float(d[2])!r}])\n"
    held, railed, steps, held_h = _fly(write, f"def main(fc):\n{command}    fc.sleep(1e9)\n")
    awake, _, _, _ = _fly(write, f"def main(fc):\n{command}    while True:\n        fc.step()\n")
    # on rails for most of the sleep: the slew settles, then long batches on rails
    on_rails = sum(n for n, r in zip(steps, railed) if r)
    assert on_rails > 0.8 * SECONDS / held_h, (on_rails, len(steps))
    assert railed[-1]
    # reference: the command itself
    assert np.max(np.abs(_nose(held.y) - d)) < 1e-12
    assert np.all(held.y[W:W + 3] == 0.0)
    assert not np.any(held.vehicle.arrays.aero.rcs_cmd)
    # the awake hold wobbles within its settle band
    assert np.degrees(np.arccos(min(1.0, float(_nose(awake.y) @ d)))) < 0.01
    # orbit: the awake flight to 1 m and 1 mm/s after 300 s (its trimming's push)
    dr = np.linalg.norm(held.y[R:R + 3] - awake.y[R:R + 3])
    dv = np.linalg.norm(held.y[V:V + 3] - awake.y[V:V + 3])
    print(f"held vs awake after {SECONDS} s: {dr:.3e} m, {dv:.3e} m/s")
    assert dr < 1.0 and dv < 1e-3

