"""The events of a flight that nobody commands: liftoff, max-Q, burn-out, orbit.

One :class:`FlightEvents` watches one body; the world calls
:meth:`FlightEvents.after_step` after every (batch of) step(s). Definitions:

* ``liftoff`` — a body that started on a site has risen 1 m above its
  starting height (figures: mass).
* ``max_q`` — the peak of the dynamic pressure on a staged vehicle,
  reported once ``q`` has fallen 5 % below a peak of at least 1 kPa (figures
  at the peak: q, Mach, altitude).
* ``stage_dry`` — a stage's usable propellant is gone (the engine model
  flags the instant); named ``MECO`` for the vehicle's first stage and
  ``SECO`` for its second when that is how the burn ends.
* ``orbit`` — the first time a body that did not start in orbit coasts (no
  thrust) with a periapsis above 100 km (the Karman line): the elements as
  figures.

Commanded events (``ignition``, ``shutdown``, ``separation``) are recorded by
the flight computer and the world where the command is given.
"""

from __future__ import annotations

import math

from rocketsim.atmosphere.table import TOP
from rocketsim.constants import DEG, EARTH_RADIUS_EQ
from rocketsim.vehicle.engines import C_ON, E_STAGE, E_TAIL, S_DRY, S_DRY_AT

LIFTOFF_HEIGHT = 1.0          # m above the starting height
MAX_Q_MIN = 1000.0            # Pa, a peak smaller than this is not "max-Q"
MAX_Q_DROP = 0.95             # reported once q < 95 % of the peak
ORBIT_PERIAPSIS = 100e3       # m above the equatorial radius
# the cheap bound below which no orbit is possible (1 ppm under the test's radius: rounding)
ORBIT_PERIAPSIS_BOUND = (EARTH_RADIUS_EQ + ORBIT_PERIAPSIS) * (1.0 - 1e-6)


class FlightEvents:
    """The uncommanded events of one body (see the module)."""

    def __init__(self, world, body, on_ground: bool, stage_names: list[str]):
        self.world = world
        self.body = body
        self.start_height = body.view().geodetic[2] if on_ground else None
        self.lifted = not on_ground
        self.peak = None                          # (q, t, mach, altitude)
        self.max_q_done = False
        self.dry_seen: set[str] = set()
        self.stage_names = stage_names            # the whole vehicle's, for MECO/SECO
        self.in_orbit = in_orbit(body.view().orbit)   # starting in orbit is not achieving it

    def after_step(self) -> None:
        """Watch the body's new state. The view (and its kernels) is built only while
        liftoff or max-Q is pending, or the orbit test has passed its cheap bound
        (:func:`periapsis_bound`): a few microseconds per step otherwise."""
        body = self.body
        if not self.lifted and body.view().geodetic[2] > self.start_height + LIFTOFF_HEIGHT:
            self.lifted = True
            self.world.event(body, "liftoff", {"mass_kg": body.mass})
        if body.vehicle is not None:        # a rigid body feels no air: no max-Q to watch
            if not self.max_q_done:
                self._max_q(body.view())
            self._stages_dry()
        if not self.in_orbit and self.lifted and periapsis_bound(body.y, body.mu) > ORBIT_PERIAPSIS_BOUND:
            self._orbit(body.view())

    def _max_q(self, view) -> None:
        if body_has_no_air(view):
            return
        q = view.dynamic_pressure
        if self.peak is None or q > self.peak[0]:
            self.peak = (q, self.body.t, view.mach, view.geodetic[2])
        elif self.peak[0] >= MAX_Q_MIN and q < MAX_Q_DROP * self.peak[0]:
            self.max_q_done = True
            q_peak, t_peak, mach, altitude = self.peak
            self.world.event(self.body, "max_q", {"q_Pa": q_peak, "mach": mach, "altitude_m": altitude,
                                                  "at_s": t_peak})

    def _stages_dry(self) -> None:
        model = self.body.vehicle
        stage = model.arrays.stage
        for s, name in enumerate(model.stage_names):
            if stage[s, S_DRY] > 0.5 and name not in self.dry_seen:
                self.dry_seen.add(name)
                index = self.stage_names.index(name) if name in self.stage_names else -1
                label = {0: "MECO", 1: "SECO"}.get(index, "stage_dry")
                self.world.event(self.body, label, {"stage": name, "burnout_s": float(stage[s, S_DRY_AT])})

    def _orbit(self, view) -> None:
        orbit = view.orbit
        if not in_orbit(orbit):         # tested first: cheaper than the engines' states
            return
        if self.body.vehicle is None or coasting(self.body.vehicle, self.body.y, self.body.t):
            self.in_orbit = True
            self.world.event(self.body, "orbit", {
                "periapsis_altitude_m": orbit.periapsis - EARTH_RADIUS_EQ,
                "apoapsis_altitude_m": orbit.apoapsis - EARTH_RADIUS_EQ,
                "inclination_deg": orbit.i / DEG, "eccentricity": orbit.e})


def periapsis_bound(y, mu: float) -> float:
    """An upper bound (m) of the periapsis radius of state ``y`` (ECI position and
    velocity first, m and m/s) about ``mu`` (m^3/s^2): the semi-latus rectum
    ``|r x v|^2 / mu`` (the periapsis is ``p / (1 + e)``), in plain floats (~1 us).
    Below :data:`ORBIT_PERIAPSIS_BOUND` the body cannot be in orbit and the elements
    are not computed."""
    x, y_, z, u, v, w = y[:6].tolist()
    hx, hy, hz = y_ * w - z * v, z * u - x * w, x * v - y_ * u
    return (hx * hx + hy * hy + hz * hz) / mu


def in_orbit(orbit) -> bool:
    """An ellipse whose periapsis clears 100 km above the equatorial radius."""
    return orbit.e < 1.0 and orbit.periapsis - EARTH_RADIUS_EQ > ORBIT_PERIAPSIS


def coasting(model, y, t: float) -> bool:
    """True when no engine of ``model`` thrusts: each is commanded off or its stage has
    run dry, and its tail-off is over."""
    eng, cmd, stage = model.arrays.eng, model.arrays.cmd, model.arrays.stage
    clocks = y[model.clocks]
    for e in range(model.n_engines):
        s = int(eng[e, E_STAGE])
        if stage[s, S_DRY] > 0.5:
            if t - stage[s, S_DRY_AT] < eng[e, E_TAIL]:
                return False
        elif cmd[e, C_ON] > 0.5 or clocks[e] < eng[e, E_TAIL]:
            return False
    return True


def body_has_no_air(view) -> bool:
    """True above the flight model's air (600 km): no dynamic pressure to watch."""
    return view.geodetic[2] > TOP or math.isnan(view.geodetic[2])
