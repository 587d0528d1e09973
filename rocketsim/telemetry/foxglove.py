"""Foxglove's well-known message schemas, in JSON, and the messages rocketsim writes with them.

Foxglove recognises a JSON channel by its schema *name* (``foxglove.FrameTransform``,
``foxglove.LocationFix``, ``foxglove.Log``): the 3-D panel then draws each body
with its attitude, the Map panel its ground track, the Log panel its lines.
The schemas below declare the fields rocketsim fills, with the names, types
and meanings of Foxglove's message-schema reference
(docs.foxglove.dev/docs/visualization/message-schemas: FrameTransform,
LocationFix, Log, Timestamp, Vector3, Quaternion). The tests validate every
message against Foxglove's published JSON schemas, kept as test fixtures.

The frames the transforms name are those of :mod:`rocketsim.telemetry.frames`.
"""

from __future__ import annotations

_TIME = {
    "type": "object", "title": "time",
    "properties": {"sec": {"type": "integer", "minimum": 0},
                   "nsec": {"type": "integer", "minimum": 0, "maximum": 999999999}},
}
_XYZ = {"type": "object", "title": "foxglove.Vector3",
        "properties": {k: {"type": "number"} for k in "xyz"}, "required": list("xyz")}
_QUATERNION = {"type": "object", "title": "foxglove.Quaternion",
               "properties": {k: {"type": "number"} for k in "xyzw"}, "required": list("xyzw")}

FRAME_TRANSFORM = {
    "title": "foxglove.FrameTransform",
    "description": "Position and orientation of a child frame in its parent frame "
                   "(translation first, then rotation).",
    "type": "object",
    "properties": {
        "timestamp": {**_TIME, "description": "Timestamp of transform"},
        "parent_frame_id": {"type": "string", "description": "Name of the parent frame"},
        "child_frame_id": {"type": "string", "description": "Name of the child frame"},
        "translation": {**_XYZ, "description": "origin of the child frame in the parent, m"},
        "rotation": {**_QUATERNION, "description": "orientation of the child frame in the parent"},
    },
    "required": ["timestamp", "parent_frame_id", "child_frame_id", "translation", "rotation"],
}

LOCATION_FIX = {
    "title": "foxglove.LocationFix",
    "description": "Where a body is over the WGS84 ellipsoid (written only while it flies about Earth).",
    "type": "object",
    "properties": {
        "timestamp": {**_TIME, "description": "Timestamp of the message"},
        "frame_id": {"type": "string", "description": "Frame whose origin the fix locates"},
        "latitude": {"type": "number", "description": "Latitude in degrees"},
        "longitude": {"type": "number", "description": "Longitude in degrees"},
        "altitude": {"type": "number", "description": "Altitude in meters"},
        "position_covariance": {"type": "array", "items": {"type": "number"}, "minItems": 9,
                                "maxItems": 9, "description": "ENU covariance, m^2 (zero: exact)"},
        "position_covariance_type": {"title": "foxglove.PositionCovarianceType",
                                     "oneOf": [{"title": "UNKNOWN", "const": 0},
                                               {"title": "APPROXIMATED", "const": 1},
                                               {"title": "DIAGONAL_KNOWN", "const": 2},
                                               {"title": "KNOWN", "const": 3}]},
    },
    "required": ["timestamp", "frame_id", "latitude", "longitude", "altitude",
                 "position_covariance", "position_covariance_type"],
}

# Foxglove log levels
DEBUG, INFO, WARNING, ERROR, FATAL = 1, 2, 3, 4, 5

LOG = {
    "title": "foxglove.Log",
    "description": "A line of program output or a flight event. Besides Foxglove's fields it "
                   "carries the mission time t (s) and the body it concerns.",
    "type": "object",
    "properties": {
        "timestamp": {**_TIME, "description": "Timestamp of log message"},
        "level": {"title": "foxglove.LogLevel",
                  "oneOf": [{"title": name, "const": value} for name, value in
                            (("UNKNOWN", 0), ("DEBUG", DEBUG), ("INFO", INFO), ("WARNING", WARNING),
                             ("ERROR", ERROR), ("FATAL", FATAL))]},
        "message": {"type": "string", "description": "Log message"},
        "name": {"type": "string", "description": "the body (or 'rocketsim' for the simulator)"},
        "file": {"type": "string", "description": "the program file ('' for the simulator)"},
        "line": {"type": "integer", "minimum": 0, "description": "0: not recorded"},
        "t": {"type": "number", "description": "mission time, s"},
        "body": {"type": "string"},
    },
    "required": ["timestamp", "level", "message", "name", "file", "line"],
}


def timestamp(stamp_ns: int) -> dict:
    """Foxglove's ``time``: whole seconds and nanoseconds since 1970 (UTC)."""
    sec, nsec = divmod(stamp_ns, 1_000_000_000)
    return {"sec": sec, "nsec": nsec}


def frame_transform(time: dict, parent: str, child: str, translation, quaternion_wxyz) -> dict:
    """A ``foxglove.FrameTransform`` at ``time`` (:func:`timestamp`): ``child`` at
    ``translation`` (m) in ``parent``, turned by the unit quaternion ``(w, x, y, z)``
    (child axes -> parent axes)."""
    w, x, y, z = quaternion_wxyz
    tx, ty, tz = translation
    return {"timestamp": time, "parent_frame_id": parent, "child_frame_id": child,
            "translation": {"x": tx, "y": ty, "z": tz},
            "rotation": {"x": x, "y": y, "z": z, "w": w}}


def location_fix(time: dict, frame: str, latitude_deg: float, longitude_deg: float,
                 altitude: float) -> dict:
    """A ``foxglove.LocationFix`` at ``time`` (:func:`timestamp`) of an exactly known
    (simulated) position: geodetic latitude and longitude in degrees, height above WGS84 in m."""
    return {"timestamp": time, "frame_id": frame, "latitude": latitude_deg,
            "longitude": longitude_deg, "altitude": altitude,
            "position_covariance": [0.0] * 9, "position_covariance_type": 0}


def log_line(stamp_ns: int, level: int, message: str, name: str, file: str, t: float,
             body: str) -> dict:
    """A ``foxglove.Log`` line, with rocketsim's mission time ``t`` and body."""
    return {"timestamp": timestamp(stamp_ns), "level": level, "message": message, "name": name,
            "file": file, "line": 0, "t": t, "body": body}
