"""The engines, propellant and heating of one body, as fields of its telemetry state message.

Read-only: nothing here changes the state, the engines' commands or the checks,
and no sensor is read (the figures are the truth, like the rest of the state
message). Called once per telemetry sample, with the compiled calls the
integrator uses (:func:`rocketsim.vehicle.engines.thrusts` and
:func:`~rocketsim.vehicle.engines.engine_state`), no derivative call.

Fields of a staged vehicle (SI units):

* ``throttle``: the throttle actually flown (after the slew limit and the
  flow-separation floor, 0-1 of vacuum thrust), averaged over the engines
  running; ``null`` when none runs. ``group_throttle`` is the same by engine
  group (``<stage>_<group>``, ``null`` for a group with no engine running);
* ``thrust`` (N) in total and ``group_thrust`` (N) by engine group, at the
  ambient pressure of the state message's air;
* ``mass_flow``: propellant drawn by all engines, kg/s;
* ``engines_running``: engines whose spool fraction is above zero on a stage
  with usable propellant left (spooling up, at thrust, or tailing off);
* ``propellant``: all propellant on board, kg (the unusable reserve
  included), and ``propellant_tanks`` by tank (``<stage>_<tank>``, kg).

Fields of a body with a heat shield:

* ``heat_flux``: cold-wall stagnation-point convective heat flux, W/m^2, by
  Sutton-Graves (:func:`rocketsim.vehicle.heating.sutton_graves`) on the
  shield's nose radius, in the air the shield's checks read (the vehicle's
  air table at the radial height; the air-relative speed of its aerodynamics);
* ``shield_temperature``: the lumped shield's temperature, K (as the checks
  integrate it after every step).

Names with characters other than letters, digits, ``-`` and ``_`` have them
replaced by ``_``, so Foxglove's message paths (``/<body>/state.group_thrust.booster_Merlin_1D_ring``)
and CSV columns can name them.
"""

from __future__ import annotations

import math
import weakref
from functools import lru_cache

from rocketsim.atmosphere.table import air_at
from rocketsim.constants import MARS_MU, SUTTON_GRAVES_EARTH, SUTTON_GRAVES_MARS
from rocketsim.dynamics.derivative import body_air_velocity, radial_height
from rocketsim.vehicle import engines as E
from rocketsim.vehicle.heating import sutton_graves


@lru_cache(maxsize=64)
def _keys(names: tuple[str, ...]) -> tuple[str, ...]:
    """Field names of tanks or engine groups (``stage/name`` -> ``stage_name``)."""
    return tuple("".join(c if c.isalnum() or c in "-_" else "_" for c in n) for n in names)


def vehicle_quantities(body) -> dict:
    """The engine, propellant and heating fields of ``body``'s state message at its time
    (see the module); empty for a rigid body without a heat shield."""
    out = {}
    model = body.vehicle
    if model is not None:
        out.update(_propulsion(body, model))
    checks = body.checks
    if model is not None and checks is not None and checks.shield is not None:
        out["heat_flux"] = _heat_flux(body, model.arrays, checks.shield.nose_radius)
        out["shield_temperature"] = checks.temperature
    return out


def _heat_flux(body, veh, nose_radius: float) -> float:
    """Sutton-Graves flux (W/m^2) in the air the shield's checks read: the vehicle's air
    table at the radial height, the air-relative speed of its aerodynamics (about Mars
    too, where the readings' air is a vacuum)."""
    y = body.y
    rho = air_at(veh.air_h0, veh.air_dh, veh.air_density, veh.air_pressure, veh.air_temperature,
                 veh.air_speed_of_sound, veh.air_wind_east, veh.air_wind_north,
                 radial_height(y, body.p))[0]
    u, v, w = body_air_velocity(y, veh.aero.wind)
    k = SUTTON_GRAVES_MARS if body.mu == MARS_MU else SUTTON_GRAVES_EARTH
    return sutton_graves(rho, math.sqrt(u * u + v * v + w * w), nose_radius, k)


def _propulsion(body, model) -> dict:
    a = model.arrays
    t, y, n = body.t, body.y, model.n_engines
    p_a = body.view().air[1]
    stage_of, group_of, groups, tanks = _layout(model)
    thrust = E.thrusts(t, y, a.first_clock, a.eng, a.cmd, a.stage, p_a).tolist()
    dry = a.stage[:, E.S_DRY].tolist()
    clocks = y[a.first_clock:a.first_clock + n].tolist()
    mdot_full = a.eng[:, E.E_MDOT].tolist()
    on, level = a.cmd[:, E.C_ON].tolist(), a.cmd[:, E.C_LEVEL].tolist()
    tail = a.eng[:, E.E_TAIL].tolist()
    group_thrust = dict.fromkeys(groups, 0.0)
    group_tau: dict[str, list] = {g: [] for g in groups}
    taus, flow = [], 0.0
    for e in range(n):
        if dry[stage_of[e]] > 0.5 or (on[e] < 0.5 and (level[e] <= 0.0 or clocks[e] >= tail[e])):
            continue            # dry, or shut down and its tail-off over: f = 0
        f, tau, _, _ = E.engine_state(t, e, clocks[e], a.eng, a.cmd, p_a)
        if f <= 0.0:
            continue
        taus.append(tau)
        group_tau[group_of[e]].append(tau)
        group_thrust[group_of[e]] += thrust[e]
        flow += f * tau * mdot_full[e]
    propellant = y[model.tanks]
    return {
        "throttle": sum(taus) / len(taus) if taus else None,
        "group_throttle": {g: sum(v) / len(v) if v else None for g, v in group_tau.items()},
        "thrust": sum(thrust),
        "group_thrust": group_thrust,
        "mass_flow": flow,
        "engines_running": len(taus),
        "propellant": float(propellant.sum()),
        "propellant_tanks": dict(zip(tanks, propellant.tolist())),
    }


_LAYOUTS: dict[int, tuple] = {}


def _layout(model) -> tuple:
    """``(stage of each engine, group key of each engine, group keys, tank keys)`` of
    ``model``, worked out once per model (a staging builds new ones)."""
    found = _LAYOUTS.get(id(model))
    if found is not None and found[0]() is model:
        return found[1]
    groups = _keys(tuple(model.engine_groups))
    layout = ([int(s) for s in model.arrays.eng[:, E.E_STAGE]], groups, tuple(dict.fromkeys(groups)),
              _keys(tuple(model.tank_names)))
    for key in [k for k, (ref, _) in _LAYOUTS.items() if ref() is None]:
        del _LAYOUTS[key]           # models gone with their runs
    _LAYOUTS[id(model)] = (weakref.ref(model), layout)
    return layout
