"""Stagnation-point heating and a heat shield as one lumped thermal mass.

docs/physics.md#heating: the Sutton-Graves stagnation-point relation, reduced
for a hot wall, with radiative cooling, and a heat shield treated as a single
lumped mass with a 2 400 K limit::

    q_cold = k sqrt(rho / r_n) v^3                (W/m^2; K. Sutton & R. A. Graves,
                                                   NASA TR R-376, 1971)
    q_hot  = q_cold (1 - h_w / h_0)               hot-wall reduction: the wall's
             h_w = c_p T_w,  h_0 = c_p T + v^2/2  enthalpy against the flow's total
                                                  (M. E. Tauber, NASA TP-2914, 1989, eq. 1)
    m c dT/dt = A (q_hot - eps sigma T^4)         lumped shield, radiating from the same area

``k`` is :data:`~rocketsim.constants.SUTTON_GRAVES_EARTH` in air and
:data:`~rocketsim.constants.SUTTON_GRAVES_MARS` in CO2; ``r_n`` the effective
nose radius (m), ``rho`` (kg/m^3) and ``v`` (m/s) the free stream's density
and the air-relative speed. Exceeding
:data:`~rocketsim.constants.HEAT_SHIELD_LIMIT` is a failure (an event of the
world).
"""

from __future__ import annotations

import math

from rocketsim.jit import njit
from rocketsim.constants import MARS_MU, STEFAN_BOLTZMANN, SUTTON_GRAVES_EARTH, SUTTON_GRAVES_MARS


def sutton_graves_constant(mu: float) -> float:
    """``k`` of the air about the central body of gravitational parameter ``mu``
    (m^3/s^2): CO2 about Mars, air elsewhere (the Moon has none to heat with)."""
    return SUTTON_GRAVES_MARS if mu == MARS_MU else SUTTON_GRAVES_EARTH


@njit
def sutton_graves(rho, speed, nose_radius, k):
    """Cold-wall stagnation-point convective heat flux (W/m^2), ``k sqrt(rho / r_n) v^3``.

    Parameters
    ----------
    rho : float
        Free-stream density, kg/m^3 (no heating at or below 0).
    speed : float
        Air-relative speed, m/s.
    nose_radius : float
        Effective nose radius ``r_n``, m.
    k : float
        Sutton-Graves constant of the gas, kg^0.5/m
        (:func:`sutton_graves_constant`).
    """
    if rho <= 0.0:
        return 0.0
    return k * math.sqrt(rho / nose_radius) * speed ** 3


@njit
def hot_wall_factor(wall_temperature, air_temperature, speed, cp):
    """``1 - h_w / h_0`` (0 when the wall is as hot as the flow's total enthalpy).

    Parameters
    ----------
    wall_temperature : float
        The wall's temperature ``T_w``, K (``h_w = c_p T_w``).
    air_temperature : float
        The free stream's static temperature ``T``, K.
    speed : float
        Air-relative speed ``v``, m/s (``h_0 = c_p T + v^2 / 2``).
    cp : float
        Specific heat of the gas at constant pressure, J/(kg K).
    """
    total = cp * air_temperature + 0.5 * speed * speed
    return max(0.0, 1.0 - cp * wall_temperature / total)


@njit
def shield_rate(temperature, rho, speed, air_temperature, nose_radius, k, cp, emissivity,
                area, heat_capacity):
    """dT/dt (K/s) of a lumped shield: ``A (q_hot - eps sigma T^4) / (m c)``.

    Parameters
    ----------
    temperature : float
        The shield's temperature, K.
    rho, speed, air_temperature : float
        Free-stream density (kg/m^3), air-relative speed (m/s) and static
        temperature (K).
    nose_radius : float
        Effective nose radius, m.
    k : float
        Sutton-Graves constant, kg^0.5/m.
    cp : float
        Specific heat of the gas at constant pressure, J/(kg K).
    emissivity : float
        The shield's emissivity (0-1).
    area : float
        Heated and radiating area, m^2.
    heat_capacity : float
        ``m c`` of the shield, J/K.
    """
    q = sutton_graves(rho, speed, nose_radius, k) * hot_wall_factor(temperature, air_temperature, speed, cp)
    return area * (q - emissivity * STEFAN_BOLTZMANN * temperature ** 4) / heat_capacity


@njit
def advance_shield(temperature, h, rho, speed, air_temperature, nose_radius, k, cp, emissivity,
                   area, heat_capacity):
    """The shield's temperature (K) after ``h`` seconds at the given flow (held): one RK4 step.

    ``h`` in s; the other parameters as :func:`shield_rate`'s.
    """
    args = (rho, speed, air_temperature, nose_radius, k, cp, emissivity, area, heat_capacity)
    k1 = shield_rate(temperature, *args)
    k2 = shield_rate(temperature + 0.5 * h * k1, *args)
    k3 = shield_rate(temperature + 0.5 * h * k2, *args)
    k4 = shield_rate(temperature + h * k3, *args)
    return temperature + h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4)
