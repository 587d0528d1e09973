"""How large a flight's telemetry file will be, before it flies.

:func:`estimate` counts the state samples of the body a scenario starts with -- one
every ``1 / rate`` seconds of the mission's duration, plus the first -- and prices each
at the bytes a sample takes in a zstd-chunked MCAP file with the messages drawn from
it (transform, location, the Earth's turn):

* :data:`RIGID_SAMPLE` for a rigid body (measured: the 6U CubeSat of
  ``scenarios/iss-coast.yaml``, 10 minutes at 10 Hz: 2.48 MB for 6 001 samples, 413
  bytes each);
* :data:`VEHICLE_SAMPLE` plus :data:`PER_GROUP` per engine group and tank for a staged
  vehicle (measured: ``scenarios/hobby-rocket.yaml``, one motor and no tank, 458 bytes
  a sample over its 1 715; the Falcon 9 of ``scenarios/falcon9-leo.yaml``, 8 engine
  groups and tanks, 605 bytes a sample over its first 100 s).

Where coasts are thinned (``telemetry.coast_rate``) a rigid body that starts in orbit
coasts the whole flight (it has no engine, and the air above 200 km holds no 1 Pa of
dynamic pressure) and is priced at the coast rate. Bodies a flight makes (a separated
stage, a fairing's halves) add samples of their own, and a flight that ends early
(a landing) writes fewer: the estimate is the size to expect within a factor of two
(tests/unit/api/test_fly_size.py), not a bound.
"""

from __future__ import annotations

from dataclasses import dataclass

from rocketsim.scenario.models import check_duration, time_argument
from rocketsim.scenario.load import LoadedScenario

RIGID_SAMPLE = 410.0        # bytes per sample of a rigid body (see the module)
VEHICLE_SAMPLE = 460.0      # bytes per sample of a staged vehicle without engine groups or tanks
PER_GROUP = 20.0            # bytes per sample per engine group and per tank
LARGE = 2e9                 # bytes: above this ``rocketsim fly`` asks before writing


@dataclass(frozen=True)
class SizeEstimate:
    """``bytes`` of ``samples`` of the starting body ``body`` at ``rate`` (Hz) over
    ``duration`` (s)."""

    bytes: float
    samples: int
    rate: float
    duration: float
    body: str

    @property
    def large(self) -> bool:
        """Above :data:`LARGE`: the command line asks before writing it."""
        return self.bytes > LARGE

    def __str__(self) -> str:
        return (f"about {_size(self.bytes)} ({self.samples:,} samples of {self.body} at {self.rate:g} Hz "
                f"over {_span(self.duration)})")


def estimate(loaded: LoadedScenario, duration: float | None = None) -> SizeEstimate:
    """The telemetry file's size :func:`rocketsim.api.fly_to_file` will write for ``loaded``
    flown ``duration`` seconds (default: the mission's); see the module."""
    scenario = loaded.scenario
    duration = scenario.mission.duration if duration is None else time_argument(duration, "duration", check_duration)
    telemetry, vehicle = scenario.telemetry, scenario.vehicle
    rate = telemetry.rate
    if vehicle.stages:
        groups = sum(len(stage.engines) + len(stage.tanks) for stage in vehicle.stages)
        per_sample = VEHICLE_SAMPLE + PER_GROUP * groups
    else:
        per_sample = RIGID_SAMPLE
        if telemetry.coast_rate is not None and scenario.mission.start.orbit is not None:
            rate = telemetry.coast_rate
    samples = int(duration * rate) + 1
    return SizeEstimate(samples * per_sample, samples, rate, duration, vehicle.name)


def _size(n: float) -> str:
    for unit, scale in (("GB", 1e9), ("MB", 1e6), ("kB", 1e3)):
        if n >= scale:
            return f"{n / scale:.3g} {unit}"
    return f"{n:.0f} bytes"


def _span(seconds: float) -> str:
    for unit, scale in (("d", 86400.0), ("h", 3600.0), ("min", 60.0)):
        if seconds >= scale:
            return f"{seconds / scale:.3g} {unit}"
    return f"{seconds:g} s"
