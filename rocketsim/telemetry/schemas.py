"""JSON schemas of the telemetry messages (one home for each message's shape).

Every channel carries JSON messages described by a JSON Schema registered in
the MCAP file, so Foxglove's Plot panel and any MCAP reader can use them.
Units are SI and stated in each field's description; angles in telemetry
are degrees where the field name ends in ``_deg``.
"""

from __future__ import annotations

import json

_VEC3 = {"type": "array", "items": {"type": "number"}, "minItems": 3, "maxItems": 3}

BODY_STATE = {
    "title": "rocketsim.BodyState",
    "description": "State of one body at one instant, in the frame of its central body: "
                   "the ECI of the mission epoch about Earth; about the Moon and Mars (n-body "
                   "missions) the body's IAU pole as z and the node of its equator on the J2000 "
                   "equator as x, fixed at the sphere-of-influence handover. A value that does not "
                   "exist (the apoapsis of an unbound orbit, the throttle with no engine running) is "
                   "left out of the message, never written as null: every field present has its "
                   "declared type.",
    "type": "object",
    "properties": {
        "t": {"type": "number", "description": "mission time, s"},
        "position": {**_VEC3, "description": "centre of mass, ECI, m"},
        "velocity": {**_VEC3, "description": "velocity, ECI, m/s"},
        "attitude": {"type": "array", "items": {"type": "number"}, "minItems": 4, "maxItems": 4,
                     "description": "unit quaternion (w, x, y, z), body axes -> ECI"},
        "body_rates": {**_VEC3, "description": "body rates about x (roll), y, z, rad/s"},
        "latitude_deg": {"type": "number", "description": "geodetic latitude (WGS84), deg; about "
                         "the Moon or Mars planetocentric"},
        "longitude_deg": {"type": "number", "description": "longitude, east positive, deg (about the "
                          "Moon or Mars from its IAU prime meridian)"},
        "altitude": {"type": "number", "description": "height above the WGS84 ellipsoid, m (about the "
                     "Moon or Mars over its ellipsoid, along the radius)"},
        "height_agl": {"type": "number", "description": "height above the ground: the altitude less the "
                       "site's ground_height (0: the ellipsoid), m"},
        "inertial_speed": {"type": "number", "description": "speed in the central body's inertial frame, m/s"},
        "surface_speed": {"type": "number", "description": "speed over the central body's turning ground "
                          "(Earth-relative), m/s"},
        "pitch_deg": {"type": "number", "description": "the nose's (body x axis) elevation above the local "
                      "horizontal, deg"},
        "heading_deg": {"type": "number", "description": "the nose's azimuth from north towards east, "
                        "0-360 deg"},
        "orbit": {
            "type": "object",
            "description": "osculating classical elements about the central body",
            "properties": {
                "semi_major_axis": {"type": "number", "description": "m (negative: hyperbola)"},
                "eccentricity": {"type": "number"},
                "inclination_deg": {"type": "number"},
                "raan_deg": {"type": "number", "description": "from the equinox (J2000 axes), deg"},
                "arg_periapsis_deg": {"type": "number"},
                "true_anomaly_deg": {"type": "number"},
                "periapsis_altitude": {"type": "number",
                                       "description": "above the central body's equatorial radius, m"},
                "apoapsis_altitude": {"type": "number",
                                      "description": "above the central body's equatorial radius, m "
                                      "(absent if unbound)"},
                "period": {"type": "number", "description": "s (absent if unbound)"},
            },
        },
        "central_body": {"type": "string", "enum": ["sun", "earth", "moon", "mars"],
                         "description": "the body the position, velocity and orbit are about; "
                         "at a handover the state is sampled in both frames at the same t"},
        "mass": {"type": "number", "description": "kg"},
        "acceleration": {"type": "number", "description": "inertial acceleration |dv/dt|, m/s^2 "
                         "(absent where it is not defined)"},
        "sensed_acceleration": {"type": "number",
                                "description": "|dv/dt - gravity| (what an accelerometer reads: 0 in "
                                "free fall), m/s^2"},
        "airspeed": {"type": "number", "description": "speed relative to the air, m/s"},
        "angle_of_attack_deg": {"type": "number", "description": "total angle of attack: between the "
                                "nose and the air-relative velocity, deg (absent at zero airspeed)"},
        "mach": {"type": "number", "description": "airspeed over the local speed of sound"},
        "dynamic_pressure": {"type": "number", "description": "q = rho v_air^2 / 2, Pa (absent for a "
                             "body the flight model flies without air)"},
        # a staged vehicle (rocketsim.sim.sampling)
        "throttle": {"type": "number", "description": "throttle flown (after slew and the "
                     "flow-separation floor, 0-1 of vacuum thrust), mean of the engines running; absent "
                     "when none runs"},
        "group_throttle": {"type": "object", "additionalProperties": {"type": "number"},
                           "description": "throttle flown by engine group <stage>_<group> (a group "
                           "with none of its engines running is absent)"},
        "thrust": {"type": "number", "description": "total thrust at the ambient pressure, N"},
        "group_thrust": {"type": "object", "additionalProperties": {"type": "number"},
                         "description": "thrust by engine group <stage>_<group>, N"},
        "mass_flow": {"type": "number", "description": "propellant drawn by all engines, kg/s"},
        "engines_running": {"type": "integer", "minimum": 0,
                            "description": "engines spooling up, at thrust or tailing off"},
        "propellant": {"type": "number", "description": "propellant on board (unusable reserve "
                       "included), kg"},
        "propellant_tanks": {"type": "object", "additionalProperties": {"type": "number"},
                             "description": "propellant by tank <stage>_<tank>, kg"},
        # a body with a heat shield
        "heat_flux": {"type": "number", "description": "cold-wall stagnation-point heat flux "
                      "(Sutton-Graves on the shield's nose radius), W/m^2"},
        "shield_temperature": {"type": "number", "description": "lumped heat-shield temperature, K"},
    },
    "required": ["t", "position", "velocity", "attitude", "body_rates", "latitude_deg",
                 "longitude_deg", "altitude", "height_agl", "inertial_speed", "surface_speed", "pitch_deg",
                 "heading_deg", "orbit"],
}

EVENT = {
    "title": "rocketsim.Event",
    "description": "Something that happened in flight, with its figures (SI units).",
    "type": "object",
    "properties": {
        "t": {"type": "number", "description": "mission time, s"},
        "body": {"type": "string"},
        "name": {"type": "string"},
        "figures": {"type": "object"},
    },
    "required": ["t", "body", "name", "figures"],
}

def schema_bytes(schema: dict) -> bytes:
    """The schema as registered in the file (stable key order), written once per schema
    dictionary (the schemas are constants; encoding the state's is not cheap)."""
    found = _BYTES.get(id(schema))
    if found is None or found[0] is not schema:
        found = _BYTES[id(schema)] = (schema, json.dumps(schema, sort_keys=True, separators=(",", ":")).encode())
    return found[1]


_BYTES: dict[int, tuple[dict, bytes]] = {}      # id(schema) -> (the schema, its bytes)

