"""Mars: the NASA Glenn engineering model below 40 km, a smooth hydrostatic profile above.

Heights are metres above the reference sphere of radius ``MARS_RADIUS_EQ``.

Below 40 km, exactly the Glenn Research Center model
(www.grc.nasa.gov/www/k-12/airplane/atmosmrm.html, fitted to Mars Global
Surveyor radio-occultation data of April 1996)::

    h >  7000 m:  T = -23.4 - 0.00222 h   (°C)
    h <= 7000 m:  T = -31   - 0.000998 h  (°C)
    p = 0.699 exp(-0.00009 h)   (kPa)
    rho = p / (0.1921 (T + 273.1))

The two temperature lines do not meet at 7 km (-37.99 °C below, -38.94 °C
above): the model is used as published, so temperature and density step
there by 0.95 K and 0.41 % (denser above). Uncertainty: about 1 % below 20 km; the model is
known to be too dense above (x1.8 at 30 km, x2.6 at 40 km;
docs/physics.md#mars-atmosphere).

Above 40 km (this module's construction; the spacecraft climatologies of the
seed description are not available, so every number below is a documented
choice, and the density anywhere above 40 km is uncertain by a factor of two
either way):

- Temperature, C¹ in height: a cubic from the Glenn value and slope at 40 km
  (160.9 K, -2.22 K/km) down to a 110 K mesopause at :data:`MESOPAUSE_HEIGHT`
  = 100 km (110 K: the coldest Mars mesopause observed, SPICAM stellar
  occultations, Forget et al. 2009, JGR 114 E01004; the 100 km height is
  within the 80-120 km they report, uncertainty +-20 km), with zero slope
  there; a smoothstep up to the exospheric 230 K at 140 km (Mars Global
  Surveyor accelerometer thermosphere, Bougher et al. 2000, uncertainty
  +-50 K), constant above. Both cubics are monotonic.
- Pressure: the hydrostatic equation ``d ln p/dh = -g(h)/(R T)`` with
  ``g = MARS_MU / (R_eq + h)^2`` and the density gas constant 192.1, plus a
  hand-over term that removes, linearly over :data:`HANDOVER_DEPTH` = 20 km,
  the difference between the Glenn formula's constant 11.1 km pressure
  scale height and the hydrostatic one at 40 km. It makes pressure and
  density C¹ at 40 km and leaves the profile purely hydrostatic above 60 km;
  its integrated effect, the labelled :func:`handover_factor` (about 1.3), is
  the ratio of this profile's density above 60 km to a purely hydrostatic
  continuation of the Glenn 40 km state.
- Density ``p / (192.1 T)``; speed of sound ``sqrt(gamma 188.92 T)`` (the
  published model's two gas constants); viscosity: CO2 Sutherland law.
"""

from __future__ import annotations

import functools
from typing import NamedTuple

import numpy as np

from rocketsim.atmosphere.hydrostatic import hermite, integrate_log_pressure
from rocketsim.atmosphere.table import STEP, AtmosphereTable, grid, make_table
from rocketsim.constants import (CO2_SUTHERLAND_S, CO2_VISCOSITY_REF, CO2_VISCOSITY_T0,
                                 MARS_CELSIUS_OFFSET, MARS_GAMMA, MARS_GAS_CONSTANT_DENSITY,
                                 MARS_GAS_CONSTANT_SOUND, MARS_MU, MARS_RADIUS_EQ)

GLENN_TOP = 40_000.0           # m, top of the Glenn model
GLENN_JOINT = 7_000.0          # m, where the Glenn model changes temperature line
MESOPAUSE_HEIGHT = 100_000.0   # m
MESOPAUSE_TEMPERATURE = 110.0  # K
EXOBASE_HEIGHT = 140_000.0     # m, constant temperature above
EXOSPHERE_TEMPERATURE = 230.0  # K
HANDOVER_DEPTH = 20_000.0      # m, 40-60 km
LOWEST = -8_000.0              # m, Hellas floor; the Glenn lines are extrapolated below 0
TOP = 1_000_000.0              # m, top of the profile


class MarsAir(NamedTuple):
    """The air at a height: K, Pa, kg/m^3, m/s, Pa s."""

    temperature: np.ndarray
    pressure: np.ndarray
    density: np.ndarray
    speed_of_sound: np.ndarray
    viscosity: np.ndarray


def glenn(h):
    """The Glenn model as published: (temperature K, pressure Pa, density kg/m^3) at h (m)."""
    h = np.asarray(h, dtype=float)
    t_c = np.where(h > GLENN_JOINT, -23.4 - 0.00222 * h, -31.0 - 0.000998 * h)
    p_kpa = 0.699 * np.exp(-0.00009 * h)
    rho = p_kpa / (0.1921 * (t_c + MARS_CELSIUS_OFFSET))
    return t_c + MARS_CELSIUS_OFFSET, p_kpa * 1000.0, rho


def upper_temperature(h):
    """Temperature (K) and its slope (K/m) above 40 km: cubic Hermite through the Glenn 40 km
    state, the mesopause and the exobase, constant above."""
    rows = np.array([GLENN_TOP, MESOPAUSE_HEIGHT, EXOBASE_HEIGHT, TOP])
    temps = np.array([float(glenn(GLENN_TOP)[0]), MESOPAUSE_TEMPERATURE, EXOSPHERE_TEMPERATURE,
                      EXOSPHERE_TEMPERATURE])
    return hermite(rows, temps, np.array([-0.00222, 0.0, 0.0, 0.0]), h, slope=True)


def gravity(h):
    """Point-mass gravity of Mars (m/s^2) at height h (m) above the reference sphere."""
    return MARS_MU / (MARS_RADIUS_EQ + np.asarray(h, dtype=float)) ** 2


def _handover_rate(h):
    """The hand-over term of d ln p/dh (1/m): k0 (1 - x/L) on 40-60 km, 0 above."""
    t40 = float(glenn(GLENN_TOP)[0])
    k0 = float(gravity(GLENN_TOP)) / (MARS_GAS_CONSTANT_DENSITY * t40) - 0.00009
    x = np.clip((np.asarray(h, dtype=float) - GLENN_TOP) / HANDOVER_DEPTH, 0.0, 1.0)
    return k0 * (1.0 - x)


def handover_factor() -> float:
    """The labelled correction: exp of the integrated hand-over term (dimensionless)."""
    return float(np.exp(_handover_rate(GLENN_TOP) * HANDOVER_DEPTH / 2.0))


def _rate(h):
    t, _ = upper_temperature(h)
    return -gravity(h) / (MARS_GAS_CONSTANT_DENSITY * t) + _handover_rate(h)


@functools.cache
def _upper_rows():
    rows = np.arange(GLENN_TOP, TOP + 1.0, 25.0)
    mids = rows[:-1] + 12.5
    log_p = integrate_log_pressure(rows, _rate(rows), _rate(mids),
                                   float(np.log(glenn(GLENN_TOP)[1])))
    return rows, log_p, _rate(rows)


def co2_viscosity(t):
    """Dynamic viscosity (Pa s) of CO2 at temperature t (K), Sutherland's law."""
    t = np.asarray(t, dtype=float)
    return (CO2_VISCOSITY_REF * (t / CO2_VISCOSITY_T0) ** 1.5
            * (CO2_VISCOSITY_T0 + CO2_SUTHERLAND_S) / (t + CO2_SUTHERLAND_S))


def mars_atmosphere(h):
    """Mars's mean atmosphere at height ``h`` (m above the reference sphere), -8 to 1000 km.

    Vectorised; returns :class:`MarsAir` (floats for a scalar ``h``).
    """
    z = np.atleast_1d(np.asarray(h, dtype=float))
    if np.any(~np.isfinite(z)) or np.any(z < LOWEST) or np.any(z > TOP):
        raise ValueError("the Mars atmosphere is defined from -8 km to 1000 km")
    t_low, p_low, _ = glenn(np.minimum(z, GLENN_TOP))
    rows, log_p, rate = _upper_rows()
    zu = np.clip(z, GLENN_TOP, TOP)
    t_up, _ = upper_temperature(zu)
    p_up = np.exp(hermite(rows, log_p, rate, zu))
    low = z <= GLENN_TOP
    t = np.where(low, t_low, t_up)
    p = np.where(low, p_low, p_up)
    rho = p / (MARS_GAS_CONSTANT_DENSITY * t)
    out = MarsAir(t, p, rho, np.sqrt(MARS_GAMMA * MARS_GAS_CONSTANT_SOUND * t), co2_viscosity(t))
    if np.ndim(h) == 0:
        return MarsAir(*(float(v[0]) for v in out))
    return out


def mars_table() -> AtmosphereTable:
    """Mars's mean atmosphere every 50 m from -8 km to 600 km, calm."""
    z = grid(LOWEST)
    air = mars_atmosphere(z)
    return make_table(z[0], STEP, air.density, air.pressure, air.temperature,
                      air.speed_of_sound, air.viscosity)
