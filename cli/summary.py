"""A flight summary as a person reads it, shaped by each body's flight: a body in orbit
by its orbit, a suborbital one by its apogee, speeds, loads, rail exit and landing."""

from __future__ import annotations

import math


def format_summary(summary: dict) -> str:
    """Plain-text summary: per body, its events, its flight or orbit, and its final state."""
    lines = [f"epoch {summary['epoch_utc']}, step {summary['step_s']:g} s, "
             f"flown to T+{summary['mission_time_s']:.2f} s"]
    for name, body in summary["bodies"].items():
        lines.append(f"{name}:")
        for event in body["events"]:
            figures = ", ".join(f"{k} {_fmt(v)}" for k, v in event.items() if k not in ("name", "time_s"))
            lines.append(f"  T+{event['time_s']:.2f} s  {event['name']}" + (f"  ({figures})" if figures else ""))
        if "flight" in body:
            lines += _flight(body["flight"])
        final = body["final"]
        orbit = body.get("orbit")
        speed = (f"inertial speed {final['inertial_speed_m_s']:.2f} m/s" if orbit else
                 f"{final['surface_speed_m_s']:.2f} m/s over the ground")
        lines.append(f"  final: T+{final['time_s']:.2f} s, altitude {_height(final['altitude_m'])}, "
                     f"lat {final['latitude_deg']:.4f} deg, lon {final['longitude_deg']:.4f} deg, {speed}")
        if orbit:
            apo = orbit["apoapsis_altitude_m"]
            lines.append(f"  orbit about {orbit['central_body']}: periapsis {orbit['periapsis_altitude_m'] / 1e3:.3f} km, "
                         "apoapsis " + (f"{apo / 1e3:.3f} km" if apo is not None else "unbound")
                         + f", inclination {orbit['inclination_deg']:.4f} deg, e {orbit['eccentricity']:.6f}")
    return "\n".join(lines)


def _flight(flight: dict) -> list[str]:
    """The lines of a suborbital body's flight figures (those it has)."""
    parts = []
    if _number(flight.get("apogee_height_agl_m")):
        parts.append(f"apogee {_height(flight['apogee_height_agl_m'])} above the ground "
                     f"at T+{flight['apogee_time_s']:.2f} s")
    if _number(flight.get("max_surface_speed_m_s")):
        mach = f" (Mach {flight['max_mach']:.2f})" if _number(flight.get("max_mach")) else ""
        parts.append(f"max speed {flight['max_surface_speed_m_s']:.1f} m/s over the ground{mach}")
    if _number(flight.get("max_dynamic_pressure_Pa")) and flight["max_dynamic_pressure_Pa"] > 0:
        parts.append(f"max q {flight['max_dynamic_pressure_Pa'] / 1e3:.2f} kPa")
    if _number(flight.get("max_sensed_acceleration_g")):
        parts.append(f"max {flight['max_sensed_acceleration_g']:.1f} g")
    lines = ["  flight: " + "; ".join(parts)] if parts else []
    if "rail_exit_time_s" in flight:
        margin = flight.get("rail_exit_stability_margin_cal")
        lines.append(f"  rail exit: T+{flight['rail_exit_time_s']:.3f} s at "
                     f"{flight['rail_exit_surface_speed_m_s']:.1f} m/s"
                     + (f", stability margin {margin:.2f} cal" if margin is not None else ""))
    if "landing_kind" in flight:
        drift = f", {flight['drift_m']:,.0f} m from where it started" if "drift_m" in flight else ""
        lines.append(f"  {flight['landing_kind']}: T+{flight['landing_time_s']:.2f} s at "
                     f"{flight['landing_surface_speed_m_s']:.1f} m/s{drift}")
    return lines


def _number(value) -> bool:
    return isinstance(value, (int, float)) and math.isfinite(value)


def _height(metres: float) -> str:
    """A height in m below 10 km, else in km."""
    return f"{metres:,.1f} m" if abs(metres) < 1e4 else f"{metres / 1e3:,.3f} km"


def _fmt(value) -> str:
    return f"{value:.6g}" if isinstance(value, float) else str(value)
