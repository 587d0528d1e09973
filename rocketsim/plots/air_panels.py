"""An air profile drawn against height: temperature, pressure (log), density (log) and,
when the day has wind, its east and north components; heights in km."""

from __future__ import annotations

from pathlib import Path

from rocketsim.plots.canvas import Picture, pyplot, save


def atmosphere(profile, out: str | Path | None = None, title: str | None = None) -> Path | Picture:
    """Draw ``profile`` (an :class:`~rocketsim.api.air_profile.AirProfile`) under ``title``
    (default: the profile's name) to the PNG ``out`` and return its path, or without
    ``out`` return the picture."""
    plt = pyplot()
    columns, wind = profile.columns, profile.has_wind
    km = columns["height_m"] / 1000.0
    panels = [("temperature (K)", columns["temperature_K"], False),
              ("pressure (Pa)", columns["pressure_Pa"], True),
              ("density (kg/m³)", columns["density_kg_m3"], True)]
    fig, axes = plt.subplots(1, 4 if wind else 3, figsize=(14 if wind else 11, 6), sharey=True)
    for ax, (label, values, log) in zip(axes, panels):
        ax.plot(values, km)
        ax.set_xlabel(label)
        if log:
            ax.set_xscale("log")
    if wind:
        axes[3].plot(columns["wind_east_m_s"], km, label="east")
        axes[3].plot(columns["wind_north_m_s"], km, label="north")
        axes[3].set_xlabel("wind (m/s)")
        axes[3].legend()
    axes[0].set_ylabel("height (km)")
    fig.suptitle(profile.name if title is None else title)
    fig.tight_layout()
    return save(fig, out)
