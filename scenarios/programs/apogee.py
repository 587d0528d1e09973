"""Watch a ballistic flight: log the release, mark the apogee, then sleep.

A flight program is a plain script: main(fc) runs once, and every fc.step(),
fc.sleep() or fc.wait_until() hands control back to the simulator.
"""


def main(fc):
    fc.log(f"released at {fc.altitude:.0f} m, speed {sum(v * v for v in fc.velocity) ** 0.5:.0f} m/s")
    highest = fc.altitude
    while True:
        fc.step()
        if fc.altitude < highest:
            fc.event("apogee", altitude_m=highest)
            break
        highest = fc.altitude
    fc.wait_until(fc.below("altitude", 10_000))
    fc.log("below 10 km")
