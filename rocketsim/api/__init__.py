"""The front door: what a notebook, a script or the command line calls.

Every command of ``rocketsim`` is a call of these functions (and of
:mod:`rocketsim.plots` for its pictures); a notebook calls the same::

    from rocketsim import api
    loaded = api.load("scenarios/falcon9-hop.yaml", {"seed": 3})
    summary = api.fly_to_file(loaded, "hop.mcap")       # what `rocketsim fly` writes
    api.verify("hop.mcap", trust=True).identical         # `rocketsim replay --verify --trust`

Flying and reading runs:

* :func:`load` (a file or mapping, overrides) -> a validated scenario;
* :func:`fly` -> a :class:`Run`, in memory or written to an MCAP file and read back;
* :func:`fly_to_file` -> the flight summary of a run written to an MCAP file (no read
  back); :func:`fly_into` flies into any sink with the telemetry writer's interface;
* :func:`open_run` -> the :class:`Run` in an MCAP file; :func:`read_run` -> its
  :class:`RunFile` (summary, events, logs, metadata: no samples);
* :func:`export_tables` -> one CSV or Parquet table per body, and the events;
* :func:`verify` -> a :class:`Verdict`: the run flown again from its attachments and
  compared message by message (:class:`UntrustedProgram` without ``trust``);
* :func:`strict_json` -> JSON text with NaN and infinities as null (the summary's file);
* :func:`telemetry_size` -> the :class:`SizeEstimate` of a flight's MCAP file, before it flies.
* :func:`fly_live` / :func:`replay_live`: a flight, or a run's file, served to Foxglove as it
  plays at a warp (a :class:`Live` server's settings; :func:`parse_warp` reads a warp).

Files, quantities and the things a scenario names:

* :func:`validate_file` -> the kind of a scenario, vehicle, site or mission file, or an
  :class:`InputError`; :func:`schema` -> the JSON Schema of a kind (:func:`schema_kinds`);
* :func:`parse_quantity` -> SI from ``"20 km2/s2"`` (:data:`UNITS`, :class:`UnitError`);
* :func:`classic_site` -> the site ``site: classic`` flies from with a seed.

What a scenario's parts are on paper and in the sky:

* :func:`vehicle_report` -> a staged vehicle's :class:`VehicleReport` (its file a vehicle's
  or a scenario's): masses, Delta-v, thrust-to-weight, centre of mass and inertia, and its
  design review (drawn by :func:`rocketsim.plots.vehicle`);
* :func:`review` -> the pre-flight :class:`Review` of a vehicle or scenario (a file, a
  mapping or what ``load`` returned): centre of pressure and static margin at liftoff
  and burnout, thrust-to-weight, rail-exit speed, peak axial loads against the limit,
  how each stage steers, warnings; :func:`design_warnings` -> the warnings alone (pure
  Python; none for a rigid body, a site or a mission file);
* :func:`atmosphere` -> an :class:`AirProfile`: the air of a day or of Mars against height
  (drawn by :func:`rocketsim.plots.atmosphere`);
* :func:`ephemeris` -> the :class:`BodyPositions` of the Sun, Earth, Moon or Mars
  (:data:`EPHEMERIS_BODIES`) at UTC instants;
* :func:`window_grid` and :func:`launch_windows` -> the :class:`LaunchWindows` to Mars or
  the Moon (:func:`window_targets`) over UTC dates: rows, a mission-file fragment, the
  porkchop plot (:func:`rocketsim.plots.porkchop`); :func:`days` reads a time of flight.

Monte Carlo campaigns (:mod:`rocketsim.campaigns`): :func:`campaign` (a notebook's
DataFrame), :func:`run_campaign`, :func:`rerun_campaign` with :func:`same_row`,
:func:`campaign_report`; Ctrl-C raises :class:`CampaignInterrupted`.

The compiled kernels: :func:`kernel_cache_dir`, :func:`set_compiling_beside`,
:func:`finish_compiling_beside`.

The names load on first use (:mod:`rocketsim.exports`): ``import rocketsim.api``
imports nothing else, so a light command stays light.
"""

from rocketsim.exports import lazy
from rocketsim.version import __version__

_HOMES = {
    "load": "rocketsim.api.flying", "fly": "rocketsim.api.flying",
    "fly_to_file": "rocketsim.api.telemetry_flight", "fly_into": "rocketsim.api.telemetry_flight",
    "open_run": "rocketsim.api.run", "Run": "rocketsim.api.run",
    "read_run": "rocketsim.telemetry.reader", "RunFile": "rocketsim.telemetry.reader",
    "export_tables": ("rocketsim.telemetry.tables", "export"),
    "verify": "rocketsim.api.reflight", "Verdict": "rocketsim.api.reflight",
    "UntrustedProgram": "rocketsim.scenario.trust",
    "fly_live": "rocketsim.api.live", "replay_live": "rocketsim.api.live", "Live": "rocketsim.api.live",
    "parse_warp": "rocketsim.api.live", "LOOPBACK": "rocketsim.api.live", "PORT": "rocketsim.api.live",
    "strict_json": "rocketsim.telemetry.encoding",
    "telemetry_size": ("rocketsim.api.file_size", "estimate"),
    "SizeEstimate": "rocketsim.api.file_size",
    "parse_quantity": "rocketsim.scenario.units", "UnitError": "rocketsim.scenario.units",
    "UNITS": "rocketsim.scenario.units",
    "classic_site": "rocketsim.scenario.classic_range",
    "validate_file": "rocketsim.api.scenario_files", "schema": "rocketsim.api.scenario_files",
    "schema_kinds": "rocketsim.api.scenario_files",
    "vehicle_report": "rocketsim.api.vehicle_figures", "VehicleReport": "rocketsim.api.vehicle_figures",
    "review": "rocketsim.scenario.preflight", "design_warnings": "rocketsim.scenario.preflight",
    "Review": "rocketsim.vehicle.review",
    "atmosphere": "rocketsim.api.air_profile", "AirProfile": "rocketsim.api.air_profile",
    "ephemeris": "rocketsim.api.body_positions", "BodyPositions": "rocketsim.api.body_positions",
    "EPHEMERIS_BODIES": ("rocketsim.ephemeris.solar_system", "BODIES"),
    "window_grid": "rocketsim.api.window_search", "launch_windows": "rocketsim.api.window_search",
    "window_targets": "rocketsim.api.window_search", "days": "rocketsim.api.window_search",
    "LaunchWindows": "rocketsim.api.window_search", "WindowGrid": "rocketsim.api.window_search",
    "campaign": "rocketsim.campaigns.execute",
    "run_campaign": ("rocketsim.campaigns.execute", "run"),
    "rerun_campaign": ("rocketsim.campaigns.execute", "rerun"),
    "same_row": "rocketsim.campaigns.execute",
    "CampaignInterrupted": ("rocketsim.campaigns.execute", "Interrupted"),
    "campaign_report": ("rocketsim.campaigns.report", "report"),
    "kernel_cache_dir": ("rocketsim.jit", "cache_dir"),
    "finish_compiling_beside": ("rocketsim.jit", "finish_beside"),
    "set_compiling_beside": "rocketsim.api.kernels",
    "InputError": "rocketsim.errors",
}
__all__ = ["__version__", *_HOMES]

__getattr__, __dir__ = lazy(globals(), _HOMES)
