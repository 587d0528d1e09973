"""Mass, centre of mass and inertia of a staged vehicle as its tanks drain.

docs/physics.md#mass-properties, recomputed at every RK4 stage: tank walls are
thin shells, propellant columns solid cylinders settled at the bottom (aft
end) of their tanks, engines, avionics, legs and fins point masses; only 10 %
of a liquid column's own roll inertia counts (a liquid barely spins with its
tank). Body axes: x along the stack from its base to the nose (roll), y and z
lateral (pitch, yaw). Stations ``x`` are metres above the base of the stack.

Everything that does not drain is summed once, by :mod:`.build`, into five
numbers (``fixed``): mass, first moment ``sum m x``, and the second moments
``Ixx``, ``Iyy0``, ``Izz0`` about the base's centre (the origin); each tank
adds its column here, and the parallel-axis theorem moves the lateral
moments to the centre of mass::

    column:  h = m / (rho pi r^2),   x_c = x_bottom + h / 2
             Ixx_c = f_roll * m r^2 / 2,   Iyy_c = Izz_c = m (3 r^2 + h^2) / 12
    total:   M = M_fixed + sum m,   x_cm = (S_fixed + sum m x_c) / M
             Iyy = Iyy0 + sum (Iyy_c + m x_c^2) - M x_cm^2        (same for Izz)

The lateral centre of mass is taken on the axis (engine rings and point-mass
rings are symmetric). Solid motors' propellant (:mod:`.motors`) adds a hollow
cylinder per motor, centred at its station ``x_m``, with ``r^2 = a - b m``::

    Ixx_m = m (R^2 + r^2) / 2,   Iyy_m = Izz_m = m ((R^2 + r^2) / 4 + K) + m x_m^2
"""

from __future__ import annotations

import numpy as np

from rocketsim.jit import njit
from rocketsim.constants import LIQUID_ROLL_INERTIA_FRACTION
from rocketsim.vehicle.motors import M_CORE_A, M_CORE_B, M_LATERAL, M_RADIUS2, M_X_CENTRE

# slots of the ``fixed`` array
F_MASS = 0      # kg
F_MOMENT = 1    # kg m, sum of m x
F_IXX = 2       # kg m^2, about the x axis
F_IYY0 = 3      # kg m^2, about the y axis through the origin
F_IZZ0 = 4      # kg m^2, about the z axis through the origin
N_FIXED = 5


@njit(borrows=True)
def vehicle_mass_properties(veh, y):
    """:func:`mass_properties` of state ``y`` of a staged vehicle with arrays ``veh``
    (:class:`~rocketsim.vehicle.build.VehicleArrays`): its tanks and its motors."""
    return mass_properties(veh.fixed, veh.tank_bottom, veh.tank_radius, veh.tank_density,
                           y[veh.first_tank:veh.first_clock], veh.motor,
                           y[veh.first_motor:veh.first_motor + veh.motor.shape[0]])


@njit
def mass_properties(fixed, tank_bottom, tank_radius, tank_linear_density, propellant, motor,
                    motor_propellant):
    """``(mass kg, x_cm m, Ixx, Iyy, Izz kg m^2)`` of the vehicle.

    ``fixed`` (5,) sums everything that does not drain (see the module
    docstring); per tank: the station of its bottom (m), its radius (m), its
    propellant mass per metre of column ``rho pi r^2`` (kg/m), and the
    propellant mass it holds now (kg); per solid motor its row of ``motor``
    (:mod:`.motors`) and the propellant it holds now (kg). Inertia is about the
    centre of mass, in body axes.
    """
    mass = fixed[F_MASS]
    moment = fixed[F_MOMENT]
    ixx = fixed[F_IXX]
    iyy = fixed[F_IYY0]
    izz = fixed[F_IZZ0]
    for i in range(tank_bottom.shape[0]):
        m = propellant[i]
        r2 = tank_radius[i] * tank_radius[i]
        h = m / tank_linear_density[i]
        xc = tank_bottom[i] + 0.5 * h
        lateral = m * (3.0 * r2 + h * h) / 12.0 + m * xc * xc
        mass += m
        moment += m * xc
        ixx += LIQUID_ROLL_INERTIA_FRACTION * 0.5 * m * r2
        iyy += lateral
        izz += lateral
    for i in range(motor.shape[0]):
        m = max(motor_propellant[i], 0.0)
        xc = motor[i, M_X_CENTRE]
        spread = motor[i, M_RADIUS2] + motor[i, M_CORE_A] - motor[i, M_CORE_B] * m     # R^2 + r^2
        lateral = m * (0.25 * spread + motor[i, M_LATERAL]) + m * xc * xc
        mass += m
        moment += m * xc
        ixx += 0.5 * m * spread
        iyy += lateral
        izz += lateral
    x_cm = moment / mass
    shift = mass * x_cm * x_cm
    return mass, x_cm, ixx, iyy - shift, izz - shift


def shell(mass: float, radius: float, length: float) -> tuple[float, float]:
    """Own ``(Ixx, Iyy)`` (kg m^2) of a thin cylindrical shell without end caps about its centre."""
    return mass * radius ** 2, mass * (radius ** 2 / 2.0 + length ** 2 / 12.0)


def solid_cylinder(mass: float, radius: float, length: float) -> tuple[float, float]:
    """Own ``(Ixx, Iyy)`` (kg m^2) of a uniform solid cylinder about its centre."""
    return mass * radius ** 2 / 2.0, mass * (3.0 * radius ** 2 + length ** 2) / 12.0


def add_fixed(fixed: np.ndarray, mass: float, x: float, own_ixx: float = 0.0, own_iyy: float = 0.0,
              y: float = 0.0, z: float = 0.0) -> None:
    """Add a non-draining part to ``fixed``: its mass at ``(x, y, z)`` (m) and its own
    axisymmetric inertia ``(own_ixx, own_iyy = own_izz)`` about its centre (kg m^2)."""
    fixed[F_MASS] += mass
    fixed[F_MOMENT] += mass * x
    fixed[F_IXX] += own_ixx + mass * (y * y + z * z)
    fixed[F_IYY0] += own_iyy + mass * (x * x + z * z)
    fixed[F_IZZ0] += own_iyy + mass * (x * x + y * y)
