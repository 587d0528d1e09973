"""The pre-flight design review of a vehicle file or a scenario: :func:`review`.

The figures are :func:`rocketsim.vehicle.review.review`'s; from a scenario it
also knows the rail the mission starts on (its rail-exit speed), the pad's
gravity (Somigliana's normal gravity at its latitude) and that the vehicle
lifts off a pad. ``rocketsim.review`` (the front door), ``rocketsim vehicle``
(which prints :meth:`~rocketsim.vehicle.review.Review.text`), and ``rocketsim
validate`` and ``rocketsim fly`` (which print :func:`design_warnings`, one line each,
before anything flies) read it.
"""

from __future__ import annotations

import os
from collections.abc import Mapping
from pathlib import Path

from rocketsim.argument_checks import expect
from rocketsim.constants import G0
from rocketsim.errors import InputError
from rocketsim.scenario.load import LoadedScenario, load, validate
from rocketsim.scenario.models import VehicleSpec
from rocketsim.scenario.yaml_source import YamlSource, read_yaml
from rocketsim.vehicle.review import Review, design_warnings as vehicle_warnings, review as review_vehicle


def review(source: str | Path | Mapping | LoadedScenario, *, base_dir: str | Path | None = None) -> Review:
    """The design review of ``source``: a vehicle file or a scenario file (by its fields: a
    scenario has ``mission``), a mapping of either (file references relative to
    ``base_dir``), or a loaded scenario. :class:`InputError` for bad input and for a
    ``rigid_body`` vehicle (no stack to review)."""
    expect(source, (str, os.PathLike, Mapping, LoadedScenario), "source",
           "a file's path, a mapping or a loaded scenario")
    spec, file, rail, latitude, pad = _vehicle(source, base_dir)
    gravity = G0
    if rail is not None:                  # the pad's normal gravity for its rail exit
        from rocketsim.frames.geodetic import normal_gravity
        gravity = normal_gravity(latitude)
    if spec.stages is None:
        raise InputError("a rigid-body vehicle has no stack to review: the design review reads "
                         "vehicles with 'stages'", file=file, line=1 if file else None,
                         column=1 if file else None, field="stages")
    return review_vehicle(spec, rail, gravity, pad)


def design_warnings(source: str | Path | Mapping | LoadedScenario, *, base_dir: str | Path | None = None) -> list[str]:
    """The review's warnings for ``source`` (as :func:`review` reads it): one line for each
    way its design will fail; none for a rigid body, a site or a mission file. Pure
    Python: no array library, no compiled kernel (``rocketsim validate`` stays light)."""
    if isinstance(source, (str, Path)):
        data = read_yaml(Path(source)).data
        if not isinstance(data, dict) or not ("mission" in data or "stages" in data):
            return []
    spec, _, _, _, pad = _vehicle(source, base_dir)
    return [] if spec.stages is None else vehicle_warnings(spec, pad)


def _vehicle(source, base_dir):
    """``(vehicle spec, its file or None, rail or None, the site's latitude (rad) or None,
    starts on a pad)``."""
    if isinstance(source, LoadedScenario):
        return _of_scenario(source)
    if isinstance(source, Mapping):
        if "mission" in source:
            return _of_scenario(load(source, base_dir=base_dir))
        folder = Path(base_dir or ".").resolve()
        spec = validate(YamlSource(None, dict(source), {}), VehicleSpec, base_dir=folder)
        return spec, None, None, None, False
    path = Path(source)
    if not path.is_file():
        raise InputError(f"file not found: {path}", file=path)
    read = read_yaml(path)
    if isinstance(read.data, dict) and "mission" in read.data:
        return _of_scenario(load(path))
    return validate(read, VehicleSpec), path, None, None, False


def _of_scenario(loaded: LoadedScenario):
    scenario = loaded.scenario
    start = scenario.mission.start.site
    rail = None
    if start is not None and start.rail is not None:
        rail = (start.rail.length, start.nose_elevation, start.rail.last_button)
    latitude = scenario.site.latitude if scenario.site is not None else None
    return scenario.vehicle, loaded.files.get("vehicle"), rail, latitude, start is not None
