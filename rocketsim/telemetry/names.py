"""The names rocketsim writes, each with one meaning and, in a column, its unit.

A state message's fields (:data:`rocketsim.telemetry.schemas.BODY_STATE`) become the
columns of a body's table (:func:`rocketsim.telemetry.tables.table`, the CSV and
Parquet exports, :meth:`rocketsim.api.run.BodyRun.table`) flattened (vectors by
component, the orbit as ``orbit_*``, groups of engines and tanks as
``<field>_<stage>_<name>``) and named with their SI unit: ``altitude_m``,
``velocity_x_m_s``, ``dynamic_pressure_Pa``; a field whose name already ends in its
unit keeps it (``latitude_deg``); ratios, counts and text carry none (``mach``,
``engines_running``, ``central_body``). :data:`COLUMNS` says what each column is.

Heights have two references, named apart everywhere (telemetry, tables, events,
summaries):

* ``altitude``: above the central body's reference ellipsoid (WGS84 about Earth), m;
  also ``fc.altitude``;
* ``height_agl``: above the ground the vehicle lands on (the site's
  ``ground_height`` over the ellipsoid, else the ellipsoid itself), m: what a hobby
  altimeter reads.

An orbit's ``periapsis_altitude`` and ``apoapsis_altitude`` are above the central
body's equatorial radius (the conic's radius less that radius), as mission designers
state orbits. Speeds name their reference: ``inertial_speed`` (in the central body's
inertial frame), ``surface_speed`` (over the body's turning ground: Earth-relative),
``airspeed`` (relative to the air, wind included).

The figures of the events and the summary (:data:`FIGURES`) use the same words with
their unit (``height_agl_m``, ``surface_speed_m_s``, ``dynamic_pressure_Pa``);
:data:`AMBIGUOUS` are names that say no reference (``speed_m_s``, ``height_m``) and
are not written. Mission time is ``t`` in a message and ``t_s`` in a table, rounded
to the microsecond (:func:`mission_time`): a sample's time is a whole number of steps,
and the float nearest that decimal (``2.3``, not ``2.3000000000000003``).
"""

from __future__ import annotations

import re

# a message field -> (its unit as a column suffix, "" for none; what it is)
_FIELDS = {
    "t": ("s", "mission time"),
    "position": ("m", "centre of mass in the central body's inertial frame"),
    "velocity": ("m_s", "velocity in the central body's inertial frame"),
    "attitude": ("", "unit quaternion w, x, y, z, body axes to the inertial frame"),
    "body_rates": ("rad_s", "body rates about the body's x (roll), y and z"),
    "latitude_deg": ("", "geodetic latitude on WGS84 (planetocentric about the Moon or Mars), deg"),
    "longitude_deg": ("", "longitude, east positive, deg"),
    "altitude": ("m", "height above the central body's reference ellipsoid (WGS84 about Earth)"),
    "height_agl": ("m", "height above the ground (the site's ground_height over the ellipsoid, "
                        "else the ellipsoid)"),
    "inertial_speed": ("m_s", "speed in the central body's inertial frame"),
    "surface_speed": ("m_s", "speed over the central body's turning ground (Earth-relative)"),
    "pitch_deg": ("", "the nose's elevation above the local horizontal, deg"),
    "heading_deg": ("", "the nose's azimuth from north, towards east, deg"),
    "angle_of_attack_deg": ("", "the angle between the nose and the air-relative velocity, deg"),
    "central_body": ("", "the body the position, velocity and orbit are about (text)"),
    "mass": ("kg", "mass"),
    "acceleration": ("m_s2", "inertial acceleration |dv/dt|"),
    "sensed_acceleration": ("m_s2", "|dv/dt - gravity|: what an accelerometer reads"),
    "airspeed": ("m_s", "speed relative to the air"),
    "mach": ("", "airspeed over the local speed of sound"),
    "dynamic_pressure": ("Pa", "q = rho v_air^2 / 2"),
    "throttle": ("", "throttle flown, 0-1 of vacuum thrust, mean of the engines running"),
    "group_throttle": ("", "throttle flown by engine group <stage>_<group>"),
    "thrust": ("N", "total thrust at the ambient pressure"),
    "group_thrust": ("N", "thrust by engine group <stage>_<group>"),
    "mass_flow": ("kg_s", "propellant drawn by all engines and burnt by solid motors"),
    "engines_running": ("", "engines spooling up, at thrust or tailing off (a count)"),
    "propellant": ("kg", "propellant on board, the unusable reserve included"),
    "propellant_tanks": ("kg", "propellant by tank <stage>_<tank>"),
    "heat_flux": ("W_m2", "cold-wall stagnation-point heat flux (Sutton-Graves)"),
    "shield_temperature": ("K", "the lumped heat shield's temperature"),
}
_ORBIT = {
    "semi_major_axis": ("m", "osculating semi-major axis (negative: a hyperbola)"),
    "eccentricity": ("", "osculating eccentricity"),
    "inclination_deg": ("", "inclination to the central body's equator, deg"),
    "raan_deg": ("", "right ascension of the ascending node, deg"),
    "arg_periapsis_deg": ("", "argument of periapsis, deg"),
    "true_anomaly_deg": ("", "true anomaly, deg"),
    "periapsis_altitude": ("m", "periapsis radius less the central body's equatorial radius"),
    "apoapsis_altitude": ("m", "apoapsis radius less the central body's equatorial radius "
                               "(none: not elliptic)"),
    "period": ("s", "orbital period (none: not elliptic)"),
}
_VECTORS = {"position": "xyz", "velocity": "xyz", "body_rates": "xyz", "attitude": "wxyz"}
_GROUPS = ("group_throttle", "group_thrust", "propellant_tanks")

# fields of files written before a field was renamed: read under today's name
FORMER_FIELDS = {"speed": "inertial_speed"}

# the unit suffixes a name may end in (SI, and degrees, calibers and standard gravities)
UNIT_SUFFIXES = ("_m", "_m_s", "_m_s2", "_s", "_kg", "_kg_s", "_N", "_N_s", "_Pa", "_Pa_deg", "_K",
                 "_W_m2", "_deg", "_rad_s", "_g", "_cal")


def column_name(field: str) -> str:
    """The table column of the flattened message field ``field`` (``altitude`` ->
    ``altitude_m``, ``propellant_tanks_booster_LOX`` -> ``propellant_tanks_booster_LOX_kg``);
    a name it does not know is returned as it is."""
    found = _FIELDS.get(field)
    if found is None and field.startswith("orbit_"):
        found = _ORBIT.get(field[len("orbit_"):])
    if found is None:
        for prefix in (*_VECTORS, *_GROUPS):
            if field.startswith(prefix + "_"):
                found = _FIELDS[prefix]
                break
    return f"{field}_{found[0]}" if found and found[0] else field


def _columns() -> dict[str, str]:
    """Every column a table may have (groups as ``<field>_*``), with what it is."""
    out = {}
    for field, (unit, meaning) in _FIELDS.items():
        if field in _VECTORS:
            for axis in _VECTORS[field]:
                out[column_name(f"{field}_{axis}")] = f"{meaning}: {axis} component"
        elif field in _GROUPS:
            out[f"{field}_*" + (f"_{unit}" if unit else "")] = meaning
        else:
            out[column_name(field)] = meaning
    for key, (_, meaning) in _ORBIT.items():
        out[column_name(f"orbit_{key}")] = meaning
    return out


COLUMNS = _columns()

# the figures of the events and the summary the simulator writes, with what each is
FIGURES = {
    "t_s": "mission time, s (a table's; rounded to the microsecond)",
    "time_s": "mission time of an event or a state in the summary, s",
    "at_s": "the exact instant of what an event reports (between steps), s",
    "burnout_s": "the instant a motor's curve or a stage's propellant ends, s",
    "altitude_m": COLUMNS["altitude_m"],
    "height_agl_m": COLUMNS["height_agl_m"],
    "latitude_deg": COLUMNS["latitude_deg"], "longitude_deg": COLUMNS["longitude_deg"],
    "inertial_speed_m_s": COLUMNS["inertial_speed_m_s"],
    "surface_speed_m_s": COLUMNS["surface_speed_m_s"],
    "vertical_speed_m_s": "speed up from the ground (negative: down), m/s",
    "horizontal_speed_m_s": "speed along the ground, m/s",
    "mach": COLUMNS["mach"], "dynamic_pressure_Pa": COLUMNS["dynamic_pressure_Pa"],
    "q_alpha_Pa_deg": "dynamic pressure times the angle of attack, Pa deg",
    "angle_of_attack_deg": COLUMNS["angle_of_attack_deg"],
    "axial_load_g": "axial load in standard gravities (9.80665 m/s^2)",
    "mass_kg": "the body's mass, kg",
    "stage_mass_kg": "a separated stage's mass, kg", "upper_mass_kg": "the stack's mass above it, kg",
    "payload_mass_kg": "a deployed payload's mass, kg", "fairing_mass_kg": "the fairing's mass, kg",
    "total_impulse_N_s": "a solid motor's total impulse, N s",
    "stability_margin_cal": "(x_cm - x_cp) / d: static margin in calibers",
    "tilt_deg": "the body's x axis from the local vertical, deg",
    "distance_to_target_m": "along the ground from the mission's pad (else the launch site), m",
    "descent_time_s": "from apogee to touchdown, s", "drift_time_s": "under a parachute, s",
    "periapsis_altitude_m": COLUMNS["orbit_periapsis_altitude_m"],
    "apoapsis_altitude_m": COLUMNS["orbit_apoapsis_altitude_m"],
    "semi_major_axis_m": COLUMNS["orbit_semi_major_axis_m"], "period_s": COLUMNS["orbit_period_s"],
    "inclination_deg": COLUMNS["orbit_inclination_deg"], "eccentricity": COLUMNS["orbit_eccentricity"],
    "raan_deg": COLUMNS["orbit_raan_deg"], "arg_periapsis_deg": COLUMNS["orbit_arg_periapsis_deg"],
    "true_anomaly_deg": COLUMNS["orbit_true_anomaly_deg"],
    "shield_temperature_K": COLUMNS["shield_temperature_K"], "heat_flux_W_m2": COLUMNS["heat_flux_W_m2"],
    "max_surface_speed_m_s": "the largest surface speed in flight, m/s",
    "max_mach": "the largest Mach number in flight",
    "max_dynamic_pressure_Pa": "the largest dynamic pressure in flight, Pa",
    "max_sensed_acceleration_g": "the largest sensed acceleration in flight, in standard gravities",
    "apogee_height_agl_m": "the highest height above the ground, m",
    "apogee_time_s": "mission time of the highest height above the ground, s",
    "ground_height_m": "the ground's height above the ellipsoid, m",
    "drift_m": "along the ground from where the body started to where it came down, m",
    "rail_exit_time_s": "the instant the last rail button left the rail, s",
    "rail_exit_surface_speed_m_s": "the speed along the rail as it left it, m/s",
    "rail_exit_stability_margin_cal": "the static margin off the rail, calibers",
    "landing_time_s": "mission time of the first touchdown or impact, s",
    "landing_surface_speed_m_s": "the speed over the ground at the first touchdown or impact, m/s",
    "landing_latitude_deg": "geodetic latitude where the body came down, deg",
    "landing_longitude_deg": "longitude where the body came down, deg",
    "mission_time_s": "mission time the flight reached, s", "step_s": "the integration step, s",
    "propellant_kg": "liquid propellant left in a staged body's tanks, the unusable reserve included, kg",
    "usable_propellant_kg": "the liquid propellant left above each stage's unusable reserve, kg",
}

# names that say no reference: not written by the simulator or a shipped program
AMBIGUOUS = {
    "speed_m_s": "inertial_speed_m_s, surface_speed_m_s or airspeed_m_s",
    "height_m": "height_agl_m (above the ground) or altitude_m (above the ellipsoid)",
    "q_Pa": "dynamic_pressure_Pa",
    "speed": "inertial_speed, surface_speed or airspeed",
}

_UNIT = re.compile("(" + "|".join(re.escape(s) for s in sorted(UNIT_SUFFIXES, key=len, reverse=True)) + ")$")


def has_unit(name: str) -> bool:
    """Whether ``name`` ends in one of :data:`UNIT_SUFFIXES`."""
    return _UNIT.search(name) is not None


# the columns that carry no unit: ratios, counts, text, the quaternion's components
UNITLESS = frozenset(name for name in COLUMNS if not has_unit(name))


def mission_time(t):
    """Mission time ``t`` (s, a number or an array) rounded to the microsecond: the
    float nearest a whole number of microseconds, which a table and a CSV file hold
    (``115 * 0.02`` is ``2.3000000000000003``, its mission time ``2.3``)."""
    import numpy as np
    rounded = np.rint(np.asarray(t, dtype=float) * 1e6) / 1e6
    return float(rounded) if rounded.ndim == 0 else rounded
