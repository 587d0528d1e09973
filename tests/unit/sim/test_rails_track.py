"""A sleeping vehicle holding an attitude in a turning frame rides sleep rails, mode TRACK.

The lunar orbiter (RCS quads handed to the autopilot) in a 300 km Earth orbit,
0.1 s headless step (as tests/unit/sim/test_rails_held.py, whose scenario it flies):

- holding prograde, it sleeps 150 s and then flies 60 s awake. Once the
  autopilot has settled (rates within 1e-4 rad/s of the frame's turn, the error
  within 0.01 deg of the law's steady lag) the world puts it on rails, where its
  nose is the velocity direction and its rates the direction's turn.
  References: the velocity of the same state for the nose (to 1e-12); for the
  rates, the turn of the velocity direction under point-mass + J2 gravity,
  ``Omega = v_hat x g / |v|`` (rocketsim.bodies.gravity, drag-free orbit);
  for the orbit and the waking, the same flight with the program awake every
  step (the autopilot steering with the RCS throughout, lagging the turn by its
  steady ``2 zeta Omega / omega_n`` = 0.12 deg): its thrusters are not pure
  couples, so the orbits differ by the trimming's small push (measured
  below), not to the bit.
- holding pitch 10 deg, heading 80 deg, roll 30 deg (fc.point), it sleeps 150 s
  on rails; reference: the readings' own Euler angles of each railed sample
  (rocketsim.flight.readings.StateView.euler, which fc.pitch/heading/roll read).
"""

import math

import numpy as np

from rocketsim.bodies.gravity import gravity
from rocketsim.layout import Q, R, V, W
from rocketsim.flight.readings import StateView
from rocketsim.frames.quaternion import quat_rotate
from tests.unit.sim.test_rails_held import _nose, _world


def _fly(write, program, seconds):
    """The body after the flight and ``(on rails, t, state)`` after each batch (on
    rails: the batch just flown was)."""
    world = _world(write, program)
    world.n_steps = round(seconds / world.h)
    body = world.bodies[0]
    log = []
    railed = [False]

    def progress(t):
        log.append((railed[0], body.t, body.y.copy()))
        railed[0] = world.schedule.on_rails(body)

    world.on_progress = progress
    world.run()
    assert body.t == seconds
    return body, log


def _lag(y):
    """Angle (rad) between the nose and the velocity."""
    v = y[V:V + 3] / np.linalg.norm(y[V:V + 3])
    return math.acos(min(1.0, float(_nose(y) @ v)))


def test_a_prograde_hold_sleeps_on_rails_in_its_turning_frame_and_wakes_seamlessly(write):
    start = "def main(fc):\n    fc.rcs(True)\n    fc.hold('prograde')\n"
    held, log = _fly(write, start + "    fc.sleep(150.0)\n    while True:\n        fc.step()\n", 210.0)
    awake, _ = _fly(write, start + "    while True:\n        fc.step()\n", 210.0)
    railed = [(t, y) for on, t, y in log if on]
    assert all(t <= 150.0 for t, _ in railed) and len(railed) > 0.9 * 150.0 / 0.1, len(railed)
    for t, y in railed:
        v = y[V:V + 3]
        assert np.max(np.abs(_nose(y) - v / np.linalg.norm(v))) < 1e-12, t
        turn = np.cross(v, gravity(y[R:R + 3])) / (v @ v)
        assert np.max(np.abs(quat_rotate(y[Q:Q + 4], y[W:W + 3]) - turn)) < 1e-9, t
    # awake again: the law's own lag builds up from zero, no transient beyond it
    steady = _lag(awake.y)
    woken = [_lag(y) for _, t, y in log if t > 150.0]
    assert max(woken) < 1.01 * steady and abs(woken[-1] - steady) < 1e-3 * steady, (max(woken), steady)
    dr = np.linalg.norm(held.y[R:R + 3] - awake.y[R:R + 3])
    dv = np.linalg.norm(held.y[V:V + 3] - awake.y[V:V + 3])
    print(f"prograde on rails vs awake after 210 s: {dr:.3e} m, {dv:.3e} m/s; lag {math.degrees(steady):.4f} deg")
    assert dr < 0.05 and dv < 2e-4


def test_a_pitch_heading_and_roll_hold_sleeps_on_rails_in_the_local_frame(write):
    command = (math.radians(10.0), math.radians(80.0), math.radians(30.0))
    _, log = _fly(write, "import math\ndef main(fc):\n    fc.rcs(True)\n"
                  f"    fc.point({command[0]!r}, {command[1]!r}, roll={command[2]!r})\n"
                  "    fc.sleep(1e9)\n", 150.0)
    railed = [(t, y) for on, t, y in log if on]
    assert len(railed) > 0.8 * 150.0 / 0.1 and log[-1][0], len(railed)
    for t, y in railed:
        assert np.max(np.abs(np.array(StateView.of_state(t, y).euler) - command)) < 1e-12, t
