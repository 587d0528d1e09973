"""A staged vehicle on paper, from its file: what ``rocketsim vehicle`` prints and draws.

:func:`vehicle_report` validates the file and computes its figures
(:func:`rocketsim.vehicle.summary.summary`: masses, Delta-v per stage in vacuum and at
sea level, thrust-to-weight at liftoff, centre of mass and inertia full and empty,
SI units); the runtime model the stack is drawn from (each stage's base above the
vehicle's) is built when first asked for. A figure more for the report is a key more
in :attr:`VehicleReport.figures`.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property
from pathlib import Path

from rocketsim.errors import InputError
from rocketsim.scenario.load import validate
from rocketsim.scenario.models import VehicleSpec
from rocketsim.scenario.yaml_source import read_yaml


@dataclass
class VehicleReport:
    """A staged vehicle's file (``path``), its validated ``spec`` and its ``figures`` (a
    JSON-ready dict, see :func:`rocketsim.vehicle.summary.summary`)."""

    path: Path
    spec: VehicleSpec
    figures: dict

    @cached_property
    def model(self):
        """The vehicle's runtime arrays (:func:`rocketsim.vehicle.build.build`): the stages'
        bases and the length the stack is drawn with."""
        from rocketsim.vehicle.build import build
        return build(self.spec)


def vehicle_report(path: str | Path) -> VehicleReport:
    """The :class:`VehicleReport` of the staged vehicle in the file ``path``; an
    :class:`~rocketsim.errors.InputError` for a missing or invalid file, or a rigid
    body (which has no stack)."""
    path = Path(path)
    if not path.is_file():
        raise InputError(f"vehicle file not found: {path}", file=path)
    spec = validate(read_yaml(path), VehicleSpec)
    if spec.stages is None:
        raise InputError("a rigid-body vehicle has no stack to show: this command reads "
                         "vehicles with 'stages'", file=path, line=1, column=1, field="stages")
    from rocketsim.vehicle.summary import summary
    return VehicleReport(path, spec, summary(spec))
