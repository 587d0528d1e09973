"""A flight summary as a person reads it."""

from __future__ import annotations


def format_summary(summary: dict) -> str:
    """Plain-text summary: per body, its events and final state and orbit."""
    lines = [f"epoch {summary['epoch_utc']}, step {summary['step_s']:g} s, "
             f"flown to T+{summary['mission_time_s']:.2f} s"]
    for name, body in summary["bodies"].items():
        final, orbit = body["final"], body["orbit"]
        lines.append(f"{name}:")
        for event in body["events"]:
            figures = ", ".join(f"{k} {_fmt(v)}" for k, v in event.items() if k not in ("name", "time_s"))
            lines.append(f"  T+{event['time_s']:.2f} s  {event['name']}" + (f"  ({figures})" if figures else ""))
        lines.append(f"  final: T+{final['time_s']:.2f} s, altitude {final['altitude_m'] / 1e3:.3f} km, "
                     f"lat {final['latitude_deg']:.4f} deg, lon {final['longitude_deg']:.4f} deg, "
                     f"speed {final['speed_m_s']:.2f} m/s")
        apo = orbit["apoapsis_altitude"]
        lines.append(f"  orbit: periapsis {orbit['periapsis_altitude'] / 1e3:.3f} km, apoapsis "
                     + (f"{apo / 1e3:.3f} km" if apo is not None else "unbound")
                     + f", inclination {orbit['inclination_deg']:.4f} deg, e {orbit['eccentricity']:.6f}")
    return "\n".join(lines)


def _fmt(value) -> str:
    return f"{value:.6g}" if isinstance(value, float) else str(value)
