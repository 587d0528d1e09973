"""Physical bounds of the figures of vehicle, site and scenario files.

Every number a file gives is finite and, as a quantity, within
:data:`~rocketsim.limits.MAX_QUANTITY` (:mod:`rocketsim.scenario.units`). A
vehicle's figures are held tighter, to what a vehicle can physically have, so
that a slip (a unit dropped, a value scaled by a thousand or a million) is
refused at its line, naming the bound, instead of flying a vehicle whose
dynamics go non-finite in the first steps (a zero inertia, a mass of 1e-300 kg,
a spring of 1e30 N/m). Each bound is generous, far beyond any vehicle flown or
designed, and says why it is where it is (``docs`` in :data:`BOUNDS`):

========================  ====================  ===========================================
figure                    bound                 why
========================  ====================  ===========================================
size of a part            1 mm .. 1 km          Starship, the largest vehicle flown, is 121 m
                                                long and 9 m wide
mass of a part or body    0.1 g .. 1e8 kg       Saturn V weighed 2.9e6 kg; the smallest
                                                model motors hold about 1 g of propellant
thrust of an engine       up to 1e8 N           the SLS booster, the largest flown, gives 16 MN
specific impulse          1 s .. 1e5 s          water rockets a few s, ion engines 1e4 s
propellant density        0.01 .. 1e5 kg/m3     a gas at low pressure .. osmium's 22 590
pressure                  up to 1e8 Pa          combustion chambers run at up to 30 MPa
identical parts           at most 1000          Super Heavy has 33 engines
engine response time      1 ms .. 1 h           spool-up and tail-off take tenths of a second
parachute drag area       up to 1e4 m2          Orion's mains, the largest flown, are about
                                                800 m2 each (C_D S), 2 400 m2 the cluster
========================  ====================  ===========================================

The rest (actuator rates, contact springs, friction, Mach tables, parachute
timing) are listed in :data:`BOUNDS` with their reasons. Two bounds relate figures
to the mass they act on, as the integrator needs (docs/physics.md#input-bounds):
a stage's dry mass under all its canopies descends at least
:data:`MIN_DESCENT_SPEED` in sea-level air (:func:`descent_speed`), and a contact
spring and damper on the lightest body they hold has no mode faster than
:data:`MAX_CONTACT_RATE` (:func:`contact_rate`). A bounded field's JSON schema description
names its bound (:func:`document_bounds`).
"""

from __future__ import annotations

import math
import typing
from dataclasses import dataclass

from pydantic_core import core_schema

from rocketsim.constants import G0, GAS_CONSTANT_USSA, MAX_DURATION, USSA_M0, USSA_P0, USSA_T0
from rocketsim.limits import MAX_QUANTITY

MIN_SIZE = 1e-3                 # m, the smallest positive size of a part (a millimetre)
MAX_SIZE = 1e3                  # m, the largest size, station or radius of a part
MIN_MASS = 1e-4                 # kg, the smallest positive mass of a part or a body (0.1 g)
MAX_MASS = 1e8                  # kg, the largest mass of a part or a body (100 000 t)
MAX_THRUST = 1e8                # N, of one engine, motor or thruster
MIN_ISP = 1.0                   # s
MAX_ISP = 1e5                   # s
MIN_DENSITY = 1e-2              # kg/m^3
MAX_DENSITY = 1e5               # kg/m^3
MAX_PRESSURE = 1e8              # Pa
MAX_COUNT = 1000                # identical parts on one ring or in one stack, restarts
MIN_RESPONSE = 1e-3             # s, shortest engine spool-up or tail-off
MAX_RESPONSE = 3600.0           # s, longest engine spool-up or tail-off, motor burn
MIN_IMPULSE = 1e-3              # N s, total impulse of a solid motor
MAX_SLEW = 100.0                # rad/s, of a gimbal or a grid fin
MAX_THROTTLE_RATE = 1e3         # fraction of full thrust per second
MAX_SEPARATION_SPEED = 100.0    # m/s, of a jettisoned fairing's halves
MAX_STIFFNESS = 1e12            # N/m, of a leg or the body's contact spring
MAX_DAMPING = 1e10              # N s/m
MAX_CONTACT_RATE = 500.0        # 1/s, |lambda| of a contact's fastest mode: 2.5 per 5 ms sub-step
MAX_FRICTION = 10.0             # Coulomb friction coefficient
MIN_FRICTION_SPEED = 1e-3       # m/s
MAX_FRICTION_SPEED = 100.0      # m/s
MAX_MACH = 100.0                # of an axial-force table
MAX_COEFFICIENT = 100.0         # an aerodynamic coefficient (C_A)
MIN_SPECIFIC_HEAT = 10.0        # J/(kg K)
MAX_SPECIFIC_HEAT = 1e5         # J/(kg K)
MAX_TEMPERATURE = 1e4           # K, of a heat shield at the start
MAX_Q_ALPHA = 1e12              # Pa deg, a structural limit
MAX_AXIAL_LOAD = 1e7            # m/s^2, a structural limit (about 1e6 g)
MAX_DRAG_AREA = 1e4             # m^2, C_D S of one parachute
MIN_DESCENT_SPEED = 1.0         # m/s, of a stage's dry mass under all its canopies, sea-level air
MAX_DEPLOY_HEIGHT = 100_000.0   # m, a parachute's deployment height above the ground
# kg/m^3, the US Standard Atmosphere 1976's sea-level density, p0 M0 / (R* T0): 1.2250
SEA_LEVEL_DENSITY = USSA_P0 * USSA_M0 / (GAS_CONSTANT_USSA * USSA_T0)
MIN_SITE_HEIGHT = -12_000.0     # m, the deepest ocean trench is 11 km below sea level
MAX_SITE_HEIGHT = 100_000.0     # m, the Karman line: above it a flight starts from orbit
MAX_PROGRAM_CPU = 3600.0        # s of CPU a program may be given for one step
MAX_PROGRAM_WAIT = 3600.0       # s of wall time a program may be given for one wake-up
RIGHT_ANGLE = math.pi / 2.0     # rad

# why each bound is where it is, quoted in refusals and schema descriptions
BOUNDS = {
    "size": "a vehicle part's sizes and stations are within a kilometre, and a size that "
            "cannot be 0 is at least a millimetre (Starship, the largest vehicle flown, is 121 m "
            "long)",
    "mass": "a part or body weighs from 0.1 g to 1e8 kg (Saturn V weighed 2.9e6 kg)",
    "thrust": "no engine, motor or thruster gives more than 1e8 N (the SLS booster gives 16 MN)",
    "isp": "specific impulses run from a few s (water rockets) to 1e4 s (ion engines)",
    "density": "a propellant is no lighter than a thin gas and no denser than 1e5 kg/m3 "
               "(osmium: 22 590 kg/m3)",
    "pressure": "combustion chambers run at up to 30 MPa; a nozzle's exit is below that",
    "count": "identical parts come in hundreds at most (Super Heavy has 33 engines)",
    "response": "an engine spools up or tails off in tenths of a second, not under a "
                "millisecond nor over an hour",
    "burn": "a motor's curve starts at 0 s and lasts at most an hour",
    "impulse": "the smallest model motors deliver 0.3 N s",
    "angle": "a deflection or cone half-angle is at most 90 deg",
    "slew": "gimbals and fins slew at a few rad/s at most",
    "throttle rate": "an engine throttles through its range in no less than a millisecond",
    "separation": "a fairing's halves are pushed apart at a few m/s, not faster than 100 m/s",
    "stiffness": "a landing leg's spring is about 1e8 N/m; 1e12 N/m is steel a metre thick",
    "damping": "landing-leg dampers are about 1e6 N s/m",
    "contact rate": "RK4 holds a mode of |lambda| dt up to 2.6 (of a damped spring) or 2.8 "
                    "(undamped), 520 /s at the 5 ms ground sub-steps; landing legs' modes are "
                    "tens to hundreds of /s",
    "drag area": "the largest parachutes flown, Orion's mains, are 35 m across, about 800 m2 of "
                 "C_D S each and 2 400 m2 the cluster of three",
    "descent": "RK4 at the longest step, 0.1 s, holds a descent at its terminal speed v "
               "(a mode of 2 g / v) only above 0.7 m/s; an empty nylon canopy descends at 0.9 m/s",
    "opening": "a parachute's lines pay out and its canopy fills in tenths of a second to "
               "seconds, not under a millisecond nor over an hour",
    "deploy height": "a parachute opens in the air, below 100 km above the ground",
    "delay": "a parachute opens after its event within the longest mission, a century",
    "friction": "friction coefficients are below 2 for any pair of materials",
    "friction speed": "friction is regularised below a speed of 1 mm/s .. 100 m/s",
    "mach": "Mach numbers of a flight stay below 100 (entry from the Moon is Mach 36)",
    "coefficient": "axial-force coefficients are of order 1 (a flat plate's is 1.3)",
    "specific heat": "specific heats of solids run from 100 to 15 000 J/(kg K)",
    "temperature": "a heat shield starts below 10 000 K",
    "structural limit": "structures break below 1e12 Pa deg and 1e6 g",
    "site height": "a site is on the ground: from 12 km below sea level (the deepest trench is "
                   "11 km) to 100 km up (above that a flight starts from orbit)",
    "cpu": "a program is given at most an hour of CPU for one step",
    "wait": "a program is given at most an hour of wall time for one wake-up",
    "direction": "a direction's components are within 1e30, so that their squares stay finite",
    "elevation": "an elevation is from -90 deg (down) to 90 deg (up)",
    "latitude": "a latitude is from -90 deg to 90 deg",
}


@dataclass(frozen=True)
class Within:
    """Pydantic metadata: a number from ``low`` to ``high`` (either None: unbounded on that
    side; ``low`` itself excluded when ``above``), in SI ``unit``; a value outside is refused
    naming the range and the reason ``BOUNDS[why]``."""

    low: float | None
    high: float | None
    why: str
    unit: str = ""
    above: bool = False

    def __get_pydantic_core_schema__(self, source, handler):
        return core_schema.no_info_after_validator_function(self.check, handler(source))

    def text(self) -> str:
        """The range in words: "above 0 m and at most 1000 m"."""
        unit = f" {self.unit}" if self.unit else ""
        parts = []
        if self.low is not None:
            parts.append(f"{'above' if self.above else 'at least'} {self.low:g}{unit}")
        if self.high is not None:
            parts.append(f"at most {self.high:g}{unit}")
        return " and ".join(parts)

    def check(self, value):
        if value is None:
            return value
        low_ok = self.low is None or (value > self.low if self.above else value >= self.low)
        if not (low_ok and (self.high is None or value <= self.high)):
            raise ValueError(f"must be {self.text()}: {BOUNDS[self.why]}")
        return value


def within(low: float | None, high: float | None, why: str, unit: str = "",
           above: bool = False) -> Within:
    """The :class:`Within` bound; ``why`` a key of :data:`BOUNDS`."""
    if why not in BOUNDS:
        raise KeyError(why)
    return Within(low, high, why, unit, above)


# the bounds of the usual kinds of figure
SIZE = within(MIN_SIZE, MAX_SIZE, "size", "m")                  # a positive size
EXTENT = within(0.0, MAX_SIZE, "size", "m")                     # a size or station, 0 allowed
STATION = within(-MAX_SIZE, MAX_SIZE, "size", "m")              # a station either side of 0
AREA = within(0.0, MAX_SIZE ** 2, "size", "m2", above=True)
PART_MASS = within(0.0, MAX_MASS, "mass", "kg")                 # 0 allowed
BODY_MASS = within(MIN_MASS, MAX_MASS, "mass", "kg")            # positive
THRUST = within(0.0, MAX_THRUST, "thrust", "N", above=True)
ISP = within(MIN_ISP, MAX_ISP, "isp", "s")
COUNT = within(1, MAX_COUNT, "count")
ANGLE = within(0.0, RIGHT_ANGLE, "angle", "rad")
SLEW = within(0.0, MAX_SLEW, "slew", "rad/s")
RESPONSE = within(MIN_RESPONSE, MAX_RESPONSE, "response", "s")
DIRECTION = within(-MAX_QUANTITY, MAX_QUANTITY, "direction")
BURN_TIME = within(0.0, MAX_RESPONSE, "burn", "s")             # a time of a thrust curve
CURVE_THRUST = within(0.0, MAX_THRUST, "thrust", "N")           # a thrust of a thrust curve


DRAG_AREA = within(0.0, MAX_DRAG_AREA, "drag area", "m2", above=True)
OPENING_LAG = within(0.0, MAX_RESPONSE, "opening", "s")
INFLATION = within(MIN_RESPONSE, MAX_RESPONSE, "opening", "s")
DEPLOY_HEIGHT = within(0.0, MAX_DEPLOY_HEIGHT, "deploy height", "m")
DEPLOY_DELAY = within(0.0, MAX_DURATION, "delay", "s")


def descent_speed(mass: float, drag_area: float) -> float:
    """m/s, the terminal speed ``sqrt(2 m g0 / (rho0 C_D S))`` of ``mass`` (kg) under the
    drag area ``drag_area`` (m^2) in sea-level air (:data:`SEA_LEVEL_DENSITY`)."""
    return math.sqrt(2.0 * mass * G0 / (SEA_LEVEL_DENSITY * drag_area))


def contact_rate(mass: float, stiffness: float, damping: float) -> float:
    """1/s, the largest |lambda| of the modes of ``mass`` (kg) on a spring ``stiffness``
    (N/m) and damper ``damping`` (N s/m): the roots of m s^2 + c s + k = 0, ``sqrt(k/m)``
    underdamped, ``(c + sqrt(c^2 - 4 m k)) / (2 m)`` overdamped."""
    disc = damping * damping - 4.0 * mass * stiffness
    if disc < 0.0:
        return math.sqrt(stiffness / mass)
    return (damping + math.sqrt(disc)) / (2.0 * mass)


def _bounds_in(annotation) -> list[Within]:
    """The :class:`Within` bounds inside an annotation (through Annotated, Optional, tuple)."""
    found = []
    for meta in getattr(annotation, "__metadata__", ()):
        if isinstance(meta, Within):
            found.append(meta)
    for arg in typing.get_args(annotation):
        if not isinstance(arg, Within):
            found.extend(b for b in _bounds_in(arg) if b not in found)
    return found


def document_bounds(schema: dict, model) -> None:
    """``json_schema_extra`` of the scenario models: each bounded field's description
    ends with its bound and the reason for it."""
    for name, info in model.model_fields.items():
        bounds = [b for meta in info.metadata if isinstance(meta, Within) for b in [meta]]
        bounds += [b for b in _bounds_in(info.annotation) if b not in bounds]
        prop = schema.get("properties", {}).get(name)
        if not bounds or prop is None:
            continue
        words = "; ".join(f"{b.text()}: {BOUNDS[b.why]}" for b in bounds)
        prop["description"] = (prop.get("description", "") + f" [bounds: {words}]").strip()
