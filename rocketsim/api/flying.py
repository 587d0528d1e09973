"""Load and fly a scenario from Python: :func:`load` and :func:`fly`.

``fly`` returns a :class:`~rocketsim.api.run.Run`. With ``telemetry=None`` nothing
is written to disk: the samples are kept in memory as columns of numbers
(:class:`~rocketsim.api.recorder.Recorder`); with a path the run is written to that
MCAP file as ``rocketsim fly`` writes it, and read back from it. Either way the
flight is the same, bit for bit.
"""

from __future__ import annotations

import os
import sys
import time
from dataclasses import replace
from pathlib import Path
from typing import TYPE_CHECKING, Any, Callable, Mapping

from rocketsim.argument_checks import expect
from rocketsim.scenario.load import LoadedScenario, load as load_scenario, program_file, unknown_stage

if TYPE_CHECKING:
    from rocketsim.api.run import Run


def load(scenario: str | Path | Mapping | LoadedScenario, overrides: Mapping[str, Any] | None = None, *,
         base_dir: str | Path | None = None) -> LoadedScenario:
    """A validated scenario from a YAML file or a mapping, with ``overrides`` (path -> value,
    e.g. ``{"vehicle.stages[booster].structure_mass": "26 t"}``) set first.

    Paths: ``a.b.c`` for fields, ``list[name]`` for the item of that name, ``list[2]`` by
    index, ``list[*]`` for every item (:mod:`rocketsim.scenario.paths`). Errors are
    :class:`~rocketsim.errors.InputError`: a file's name its line and field, a mapping's
    and an override's the field's path (and, for a misspelt one, the nearest valid
    name). A mapping's file references are relative to ``base_dir`` (default: the
    current folder); its ``program`` and ``programs`` may be callables ``main(fc)``."""
    if isinstance(scenario, LoadedScenario):
        if overrides:
            raise TypeError("overrides apply to a scenario's file or mapping, not to a scenario "
                            "already loaded: load it again with them")
        return scenario
    return load_scenario(scenario, overrides, base_dir=base_dir)


def fly(scenario: str | Path | Mapping | LoadedScenario, telemetry: str | Path | None = None, *,
        step: float | None = None, duration: float | None = None, progress: bool | Callable = False,
        program: Callable | str | Path | None = None,
        programs: Mapping[str, Callable | str | Path] | None = None, live: bool | Mapping = False) -> Run:
    """Fly ``scenario`` (loaded, or a file or mapping :func:`load` reads) and return its :class:`Run`.

    ``telemetry``: None keeps the samples in memory and writes nothing; a path writes the
    MCAP file there. ``step``, ``duration`` (s) override the scenario's. ``progress``: True
    shows mission time and phase on stderr, or a callable ``progress(t, phase)``.
    ``program`` and ``programs`` (stage name -> program) fly in place of the scenario's:
    a callable ``main(fc)`` or a program file. ``live``: True, or the fields of a
    :class:`rocketsim.api.live.Live` (``{"warp": 10, "port": 8765}``), shows the flight in
    Foxglove as it flies (:func:`rocketsim.api.live.fly_live`), and returns once it is shown;
    the run is the same, bit for bit.

    A flight that ends in an error (a program's exception, a state no longer finite,
    Ctrl-C) raises it; kept in memory, the run up to the error is the exception's
    ``run`` (written to a file, the file holds it)."""
    expect(telemetry, (str, os.PathLike, type(None)), "telemetry", "a file's path or None")
    expect(programs, (Mapping, type(None)), "programs", "a mapping of stage names to programs")
    if not (isinstance(progress, bool) or callable(progress)):
        expect(progress, (), "progress", "True, False or a callable progress(t, phase)")
    loaded = with_programs(load(scenario), program, programs or {})
    on_progress = _progress_line() if progress is True else progress or None
    # the flight's modules (numba's kernels) and the run's reader load with the first
    # flight, not with rocketsim or load
    from rocketsim.api.recorder import Recorder
    from rocketsim.api.run import Run, open_run
    from rocketsim.api.telemetry_flight import fly_into, fly_to_file
    recorders = []
    if telemetry is None:

        def open_recorder(epoch_ns: int, program_file: str) -> Recorder:
            recorders.append(Recorder(epoch_ns, program_file))
            return recorders[0]

    try:
        if live:
            from rocketsim.api.live import Live, fly_live
            fly_live(loaded, telemetry, Live.of(live), step=step, duration=duration, on_progress=on_progress,
                     also=open_recorder if telemetry is None else None)
        elif telemetry is None:
            fly_into(loaded, open_recorder, step=step, duration=duration, on_progress=on_progress)
        else:
            fly_to_file(loaded, telemetry, step=step, duration=duration, on_progress=on_progress)
    except BaseException as error:
        if recorders:       # what flew before the error, as the file would keep it
            error.run = Run(recorders[0].run, recorders[0].samples)
        raise
    finally:
        if progress is True:
            print(file=sys.stderr)
    if telemetry is None:
        return Run(recorders[0].run, recorders[0].samples)
    return open_run(telemetry)


def with_programs(loaded: LoadedScenario, program, programs: Mapping) -> LoadedScenario:
    """``loaded`` flying ``program`` and the stage ``programs`` (callables or files) in
    place of its own."""
    if program is None and not programs:
        return loaded
    files, callables = dict(loaded.files), dict(loaded.callables)
    for role, given in ([("program", program)] if program is not None else []) + \
            [(f"program/{stage}", given) for stage, given in programs.items()]:
        if not callable(given):
            expect(given, (str, os.PathLike), role, "a function main(fc) or a program file's path")
        files.pop(role, None)
        callables.pop(role, None)
        if callable(given):
            callables[role] = given
            path = program_file(given)
            if path.is_file():
                files[role] = path
        else:
            files[role] = Path(given).resolve()
    for stage in programs:
        if stage not in [s.name for s in loaded.scenario.vehicle.stages or []]:
            raise unknown_stage(stage, loaded.scenario.vehicle)
    return replace(loaded, files=files, callables=callables)


def _progress_line() -> Callable[[float, str], None]:
    """A progress callback writing ``T+<s>  <phase>`` over itself on stderr, twice a second."""
    shown = [0.0]

    def show(t: float, phase: str) -> None:
        now = time.monotonic()
        if now - shown[0] >= 0.5:
            shown[0] = now
            print(f"\rT+{t:,.0f} s  {phase}".ljust(60), end="", file=sys.stderr, flush=True)

    return show
