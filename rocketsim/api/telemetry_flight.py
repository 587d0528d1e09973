"""Fly a loaded scenario into its telemetry: the world plus an MCAP file, or any sink
with the writer's interface (:func:`fly_into`).

The telemetry is opened first and closed last, whatever happens in between (a
program error, Ctrl-C): what was written stays readable, with the error logged
as an event. The world's modules (the compiled kernels) are imported with this
module, so the front door imports it only when a flight begins.
"""

from __future__ import annotations

import json
import os
from pathlib import Path

from rocketsim.errors import signal_behind
from rocketsim.version import __version__
from rocketsim.scenario.load import LoadedScenario
from rocketsim.sim.build import build_world
from rocketsim.telemetry.encoding import strict_json
from rocketsim.telemetry.writer import TelemetryWriter

# media type of an attached file by its suffix (the rest are YAML: scenario, vehicle, ...)
MEDIA_TYPES = {".py": "text/x-python", ".nc": "application/x-netcdf"}


def fly_to_file(loaded: LoadedScenario, out: str | Path, *, step: float | None = None,
                duration: float | None = None, on_progress=None) -> dict:
    """Fly ``loaded`` and write its telemetry to ``out``; return the summary.

    ``on_progress(t, phase)``, if given, is called after every batch of steps with the
    mission time (s) and the flight's phase, its latest event as ``"<body>: <name>"``
    (:attr:`rocketsim.sim.world.World.phase`); a coast's compiled run of sample intervals
    is one batch (:data:`rocketsim.sim.coast_runs.MAX_INTERVALS` of them at most), and so
    is a single body's compiled run through sample steps
    (:data:`rocketsim.sim.window.RUN_SAMPLES` samples at most).

    Errors in the scenario or the program are raised after the telemetry
    file has been finished.
    """
    return fly_into(loaded, lambda epoch_ns, program: TelemetryWriter(out, epoch_ns, program),
                    step=step, duration=duration, on_progress=on_progress)


def fly_into(loaded: LoadedScenario, open_telemetry, *, step: float | None = None,
             duration: float | None = None, on_progress=None) -> dict:
    """:func:`fly_to_file` into the telemetry ``open_telemetry(epoch_ns, program_file)`` opens
    (a context manager with the interface of
    :class:`~rocketsim.telemetry.writer.TelemetryWriter`: an MCAP file, or samples kept
    in memory by :class:`rocketsim.api.recorder.Recorder`)."""
    world = build_world(loaded, step=step, duration=duration)
    world.on_progress = None if on_progress is None else (lambda t: on_progress(t, world.phase))
    epoch_ns = round(world.epoch.utc.timestamp() * 1e9)
    program = loaded.program_path
    with open_telemetry(epoch_ns, program.name if program else "") as telemetry:
        telemetry.metadata("rocketsim", {
            "version": __version__,
            "scenario": loaded.scenario.name,
            "epoch_utc": world.epoch.utc.isoformat(),
            "step_s": repr(world.h),
            "duration_s": repr(world.duration),
            "seed": str(loaded.scenario.seed),
        })
        for role, path in loaded.files.items():
            telemetry.attach(f"{role}/{path.name}", path.read_bytes(),
                             MEDIA_TYPES.get(path.suffix.lower(), "application/yaml"))
        layout = {role: Path(os.path.relpath(path, loaded.path.parent)).as_posix()
                  for role, path in loaded.files.items()}
        mapping = _scenario_text(loaded)
        if mapping is not None:     # a scenario given as a mapping travels as the file it would be
            telemetry.attach(f"scenario/{loaded.path.name}", mapping, "application/yaml")
            layout["scenario"] = loaded.path.name
        # where each file sits relative to the scenario's folder, so a replay
        # can lay the attachments out again and re-fly the run
        telemetry.metadata("files", layout)
        entries = {role: main.__name__ for role, main in loaded.callables.items()
                   if getattr(main, "__name__", "main") != "main"}
        if entries:                 # programs given as functions not named main
            telemetry.metadata("entries", entries)
        if loaded.overrides:        # set over the files: a re-flight sets them again
            telemetry.metadata("overrides", {path: json.dumps(value, default=str)
                                             for path, value in loaded.overrides.items()})
        try:
            summary = world.run(telemetry)
        except BaseException as caught:
            error = signal_behind(caught)
            try:
                telemetry.error(world.t, f"{type(error).__name__}: {error}" if str(error) else type(error).__name__)
                telemetry.metadata("outcome", {"status": "error", "error": str(error) or type(error).__name__})
            except OSError:
                pass        # a full disk takes no more: what was written stays readable
            if error is not caught:
                raise error from None
            raise
        telemetry.metadata("outcome", {"status": "ok"})
        telemetry.metadata("summary", {"json": strict_json(summary)})
    return summary


def _scenario_text(loaded: LoadedScenario) -> bytes | None:
    """The YAML of a scenario given as a mapping (None: read from a file, or holding
    values YAML cannot write, and then the run cannot be flown again from itself)."""
    if loaded.written is None or "scenario" in loaded.files:
        return None
    import yaml
    # libyaml's emitter where PyYAML was built with it: the same text, faster than the
    # pure-Python one
    dumper = getattr(yaml, "CSafeDumper", yaml.SafeDumper)
    try:
        return yaml.dump(loaded.written, Dumper=dumper, sort_keys=False, allow_unicode=True).encode()
    except yaml.YAMLError:
        return None
