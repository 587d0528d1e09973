"""Load a scenario and the files it references, with errors a user can act on.

``load(path)`` reads the scenario YAML, resolves each referenced file
(``vehicle``, ``site``, ``mission`` given as paths, and the ``program``)
relative to the scenario file (``site: classic`` names no file: it is the
classic range generated from the scenario's seed,
:mod:`rocketsim.scenario.classic_range`), validates everything with the pydantic models
and returns a :class:`LoadedScenario`. Any problem raises one
:class:`~rocketsim.errors.InputError` naming the file, line, column and field
path, what was expected, and for a misspelt field the closest valid name.
"""

from __future__ import annotations

import os
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable

from rocketsim.errors import InputError
from rocketsim.scenario.classic_range import CLASSIC
from rocketsim.scenario.models import MissionSpec, Scenario, VehicleSpec
from rocketsim.scenario.start_spec import SiteSpec
from rocketsim.scenario.overrides import Overrides
from rocketsim.scenario.paths import PathError
from rocketsim.scenario.validation import quoted, validate
from rocketsim.scenario.weather import load_weather
from rocketsim.scenario.yaml_source import YamlSource, read_yaml

# fields of a scenario that may be a path to a file of their own, and its model
REFERENCED = {"vehicle": VehicleSpec, "site": SiteSpec, "mission": MissionSpec,
              "spacecraft": VehicleSpec}


@dataclass(frozen=True)
class LoadedScenario:
    """A validated scenario and every file it was read from.

    ``files`` maps a role (``scenario``, ``vehicle``, ``site``, ``mission``,
    ``weather``, ``sounding`` or ``reanalysis``, ``program``, ``program/<stage>``) to the file's
    resolved path; these travel in the telemetry. ``callables`` maps the role of a
    program given as a Python callable to it (its file, when it has one, is in
    ``files``). ``overrides``: the paths and values set over the files (they travel
    in the telemetry too). A scenario given as a mapping has no ``scenario`` file; its
    ``path`` is ``<base_dir>/<name>.yaml``, no file: its references are relative
    to that folder. ``written`` is that mapping as a scenario file would hold it
    (a callable program named by its file, relative to the folder), which the
    telemetry carries in place of the file; None for a scenario read from a file.
    ``step_line``: the line of ``step`` in the scenario's file, where an error the step
    causes in flight points (None: not written there, e.g. the default or an override).
    """

    scenario: Scenario
    path: Path
    files: dict[str, Path] = field(default_factory=dict)
    callables: dict[str, Callable] = field(default_factory=dict)
    overrides: dict[str, Any] = field(default_factory=dict)
    written: dict | None = None
    step_line: int | None = None

    @property
    def program_path(self) -> Path | None:
        """The program's file (a callable's: the file defining it)."""
        return self.programs().get("program", (None, None))[1]

    @property
    def stage_program_paths(self) -> dict[str, Path]:
        """Programs of separating stages, by stage name."""
        return {role.split("/", 1)[1]: path for role, (_, path) in self.programs().items()
                if role.startswith("program/")}

    def programs(self) -> dict[str, tuple[Callable | None, Path]]:
        """``role -> (main, file)`` of every program: ``main`` the callable given, or
        None for a file's ``main`` (to load)."""
        found = {role: (None, path) for role, path in self.files.items()
                 if role == "program" or role.startswith("program/")}
        found.update({role: (main, program_file(main)) for role, main in self.callables.items()})
        return found

    def atmosphere(self):
        """The day's 50 m atmosphere table (the standard atmosphere without weather)."""
        from rocketsim.scenario.weather import StandardWeather, build_atmosphere
        site = self.scenario.site
        weather = self.scenario.weather or StandardWeather(kind="standard")
        base_dir = (self.files.get("weather") or self.path).parent
        return build_atmosphere(weather, site.latitude if site else 0.0, base_dir,
                                standard_gravity=site is not None and site.model == CLASSIC,
                                site_longitude=site.longitude if site else None,
                                epoch=self.scenario.mission.epoch)


def load(scenario: str | Path | Mapping, overrides: Mapping[str, Any] | None = None, *,
         base_dir: str | Path | None = None) -> LoadedScenario:
    """Read and validate a scenario file (or a scenario given as a mapping) and what it
    references, with ``overrides`` (path -> value, :mod:`rocketsim.scenario.overrides`)
    set first.

    A mapping's file references are relative to ``base_dir`` (default: the current
    folder), and its errors name the field's path instead of a file and line. Its
    ``program`` and ``programs`` may be Python callables ``main(fc)`` as well as files
    (and so may the values of overrides of those fields)."""
    edits = Overrides(overrides)
    scenario_data = scenario
    if isinstance(scenario, Mapping):
        path = Path(base_dir or ".").resolve() / f"{scenario.get('name') or 'scenario'}.yaml"
        source = edits.source(None, dict(scenario))
        files = {}
    else:
        path = Path(scenario)
        source = read_yaml(path)
        files = {"scenario": path.resolve()}
    data = source.data
    if not isinstance(data, dict):
        raise InputError("expected a YAML mapping of scenario fields", file=path, line=1, column=1)
    opened: dict[str, tuple[Path, YamlSource]] = {}

    def open_reference(name: str, value: str):
        if name not in REFERENCED and name != "weather" or (name == "site" and value == CLASSIC):
            raise PathError(f"{name} is {value!r}, not a mapping or a file of fields")
        ref = _resolve(path, value, source, (name,))
        opened[name] = (ref, read_yaml(ref))
        return opened[name][1].data

    data = edits.apply(dict(data), Scenario, open_reference)
    source = edits.source(source if isinstance(source, YamlSource) else None, data)
    callables = _callables(data)
    for name, model in REFERENCED.items():
        value = data.get(name)
        if name in opened:
            ref, read = opened[name]
            data[name] = validate(edits.source(read, value, (name,)), model, base_dir=ref.parent)
            files[name] = ref
        elif isinstance(value, str) and not (name == "site" and value == CLASSIC):
            if name == "site" and not value.endswith((".yaml", ".yml")):
                line, column = source.position((name,)) or (None, None)
                raise InputError(f"{value!r} is neither a site file (.yaml) nor {CLASSIC!r} "
                                 "(the classic range)", file=source.path, line=line, column=column,
                                 field=name)
            ref = _resolve(path, value, source, (name,))
            data[name] = validate(read_yaml(ref), model)
            files[name] = ref
    weather = data.get("weather")
    weather_source = source
    if "weather" in opened:
        ref, weather_source = opened["weather"]
        weather_source = edits.source(weather_source, weather, ("weather",))
        data["weather"] = load_weather(weather_source)
        files["weather"] = ref
    elif isinstance(weather, str):
        ref = _resolve(path, weather, source, ("weather",))
        weather_source = read_yaml(ref)
        data["weather"] = load_weather(ref)
        files["weather"] = ref
    program = data.get("program")
    if isinstance(program, str):
        ref = _resolve(path, program, source, ("program",))
        data["program"] = ref
        files["program"] = ref
    elif "program" in callables and program.is_file():
        files["program"] = program
    programs = data.get("programs")
    if isinstance(programs, dict):
        resolved = {}
        for stage, reference in programs.items():
            if isinstance(reference, str):
                resolved[stage] = _resolve(path, reference, source, ("programs", stage))
                files[f"program/{stage}"] = resolved[stage]
            else:
                resolved[stage] = reference
                if f"program/{stage}" in callables and reference.is_file():
                    files[f"program/{stage}"] = reference
        data["programs"] = resolved
    scenario = validate(source, Scenario, data, base_dir=path.parent)
    for stage in scenario.vehicle.stages or []:
        for motor in stage.motors:
            if motor.file is not None:
                files[f"motor/{stage.name}/{motor.name}"] = Path(motor.file)
    for stage in scenario.programs:
        if stage not in [s.name for s in scenario.vehicle.stages or []]:
            line, column = source.position(("programs", stage)) or (None, None)
            raise unknown_stage(stage, scenario.vehicle, file=source.path, line=line, column=column)
    _check_followed(scenario, source)
    sounding = getattr(scenario.weather, "file", None)
    if sounding is not None:
        # a sounding (or reanalysis) file is relative to the file that names it
        loc = ("file",) if "weather" in files else ("weather", "file")
        files[scenario.weather.kind] = _resolve(weather_source.path or path, sounding,
                                                weather_source, loc)
    written = _as_written(scenario_data, path.parent) if isinstance(scenario_data, Mapping) else None
    step_line = (source.position(("step",)) or (None,))[0]
    return LoadedScenario(scenario, path.resolve(), files, callables, dict(overrides or {}), written,
                          step_line)


def unknown_stage(stage: str, vehicle: VehicleSpec, **where) -> InputError:
    """The error for a program given to ``stage``, not a stage of ``vehicle``."""
    stages = [s.name for s in vehicle.stages or []]
    return InputError(f"no stage named {stage!r} in vehicle {vehicle.name!r}"
                      + (f" (stages: {', '.join(stages)})" if stages else ""),
                      field=f"programs.{stage}", **where)


def _check_followed(scenario: Scenario, source) -> None:
    """An error for a name in ``follow`` that no body of the flight can have (it would
    never fly, and every other body would then be flown to the end): the bodies are the
    vehicle (the stack, and what is left of it), each stage that separates (all but the
    top one), the fairing's halves and the payload."""
    vehicle = scenario.vehicle
    names = [vehicle.name] + [stage.name for stage in (vehicle.stages or [])[:-1]]
    names += ["fairing_1", "fairing_2"] if vehicle.fairing is not None else []
    names += ["payload"] if vehicle.payload is not None else []
    for i, name in enumerate(scenario.follow or []):
        if name not in names:
            line, column = source.position(("follow", i)) or source.position(("follow",)) or (None, None)
            raise InputError(f"no body named {name!r} flies in this flight (its bodies: {', '.join(names)})",
                             field=f"follow[{i}]", file=source.path, line=line, column=column)


def _callables(data: dict) -> dict[str, Callable]:
    """The programs of ``data`` given as Python callables, by role (``program``,
    ``program/<stage>``), each replaced in ``data`` by the file that defines it
    (:func:`program_file`)."""
    found = {}
    if callable(data.get("program")):
        found["program"] = data["program"]
    if isinstance(data.get("programs"), dict):
        found.update({f"program/{stage}": main for stage, main in data["programs"].items()
                      if callable(main)})
        data["programs"] = {stage: program_file(main) if callable(main) else main
                            for stage, main in data["programs"].items()}
    if "program" in found:
        data["program"] = program_file(found["program"])
    return found


def _as_written(data, folder: Path):
    """``data`` (a scenario mapping's values) as YAML holds them: a callable as its
    file relative to ``folder``, paths as text, tuples as lists, numbers as numbers."""
    if callable(data):
        return os.path.relpath(program_file(data), folder)
    if isinstance(data, Mapping):
        return {str(key): _as_written(value, folder) for key, value in data.items()}
    if isinstance(data, (list, tuple)):
        return [_as_written(value, folder) for value in data]
    if isinstance(data, Path):
        return str(data)
    if hasattr(data, "item") and not isinstance(data, (str, bytes)):
        return data.item()          # a numpy scalar
    return data


def program_file(main: Callable) -> Path:
    """The file that defines the callable ``main`` (where its errors' lines are)."""
    code = getattr(main, "__code__", None) or getattr(getattr(main, "__call__", None), "__code__", None)
    return Path(code.co_filename if code is not None else "<callable>").resolve()


def _resolve(scenario_path: Path, reference: str, source: YamlSource, loc: tuple) -> Path:
    try:
        ref = (scenario_path.parent / reference).resolve()
        found = ref.is_file()
    except (OSError, ValueError, RuntimeError) as error:    # a name too long for the system, a NUL
        line, column = source.position(loc) or (None, None)            # in it, a loop of symlinks
        problem = "a loop of symbolic links" if isinstance(error, RuntimeError) else \
            getattr(error, "strerror", None) or error
        raise InputError(f"referenced file {quoted(reference)} cannot be a file name ({problem})",
                         file=scenario_path, line=line, column=column,
                         field=".".join(map(str, loc))) from None
    if not found:
        line, column = source.position(loc) or (None, None)
        raise InputError(f"referenced file {reference!r} not found (looked for {ref})",
                         file=source.path, line=line, column=column, field=".".join(map(str, loc)))
    return ref
