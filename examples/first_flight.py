"""Fly a scenario from Python, read its tables, change it and compare two runs.

Run from the repository's root (``python examples/first_flight.py``); it flies
30 s of the sounding payload's ballistic arc twice, in memory, and draws the
first run to ``first_flight.png`` in the current folder (or in the folder
given as the first argument).
"""

import sys
from pathlib import Path

import rocketsim

SCENARIO = Path(__file__).resolve().parent.parent / "scenarios" / "spaceport-ballistic.yaml"
out = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(".")

# fly 30 s of mission time; nothing is written to disk
run = rocketsim.fly(SCENARIO, duration=30)
print(run)

# a body's samples as a pandas DataFrame indexed by mission time (s)
payload = run.bodies["sounding-payload"]
table = payload.table()
print(table[["altitude_m", "height_agl_m", "surface_speed_m_s"]].tail(3))

# the same scenario released 100 m/s slower upwards: an override by path (the release
# velocity is east, north, up; [2] its third item), validated as the file is
slower = rocketsim.load(SCENARIO, overrides={"mission.start.site.velocity[2]": "1095.4 m/s"})
other = rocketsim.fly(slower, duration=30)
lower = other.bodies["sounding-payload"].table()

# compare the two runs sample by sample
difference = (table["altitude_m"] - lower["altitude_m"]).iloc[-1]
print(f"at T+30 s the faster release is {difference:.0f} m higher")
assert difference > 0

print("plot:", run.plot(out / "first_flight.png"))
