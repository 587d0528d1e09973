"""A staged vehicle coasting with its engines off goes on sleep rails.

Reference: the same vehicle flown awake (its program stepping every step, so
the world integrates the full derivative with the vehicle's mass properties
and engine model at every RK4 stage). With the engines off nothing but
gravity acts, and the rails' position and velocity must follow the awake
path (the same RK4 arithmetic: to the bit here); the engine clocks run on.
"""

from pathlib import Path

import numpy as np

from rocketsim.scenario.load import load
from rocketsim.sim.build import build_world

ROOT = Path(__file__).resolve().parents[3]


def test_a_coasting_stage_on_rails_follows_the_awake_path(write):
    finals = []
    for program, asleep in (("def main(fc):\n    fc.sleep(1e9)\n", True),
                            ("def main(fc):\n    while True:\n        fc.step()\n", False)):
        write("program.py", program)
        write("mission.yaml", """\
            epoch: 2026-11-26T12:00:00Z
            start:
              orbit: {altitude: 300 km, inclination: 28.5 deg}
            duration: 200 s
            """)
        path = write("scenario.yaml", f"""\
            name: coast
            vehicle: {ROOT / 'vehicles' / 'lunar-orbiter.yaml'}
            mission: mission.yaml
            program: program.py
            """)
        world = build_world(load(path))
        body = world.bodies[0]
        railed = []
        world.on_progress = lambda t: railed.append(world.schedule.on_rails(body))
        world.run()
        assert body.t == 200.0
        assert all(railed[5:]) if asleep else not any(railed)   # asleep: once the engine clocks pass the 0.25 s tail-off
        finals.append(body.y.copy())
    clocks = build_world(load(path)).bodies[0].vehicle.clocks
    np.testing.assert_array_equal(finals[0][:6], finals[1][:6])
    np.testing.assert_allclose(finals[0][clocks], finals[1][clocks], rtol=0, atol=1e-9)
    np.testing.assert_array_equal(finals[0][13:clocks.start], finals[1][13:clocks.start])    # tanks
