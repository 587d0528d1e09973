"""A staged vehicle on paper, from its file: what ``rocketsim vehicle`` prints and draws.

:func:`vehicle_report` validates the file (a vehicle's, or a scenario's) and computes
its figures (:func:`rocketsim.vehicle.summary.summary`: masses, Delta-v per stage in
vacuum and at sea level, thrust-to-weight at liftoff, centre of mass and inertia full
and empty, SI units) and its design review (:func:`rocketsim.scenario.preflight.review`:
centre of pressure, static margins, loads, steering, warnings); the runtime model the stack is drawn from (each stage's base above the
vehicle's) is built when first asked for. A figure more for the report is a key more
in :attr:`VehicleReport.figures`.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property
from pathlib import Path

from rocketsim.argument_checks import file_path
from rocketsim.scenario.models import VehicleSpec
from rocketsim.scenario.preflight import review
from rocketsim.vehicle.review import Review


@dataclass
class VehicleReport:
    """A staged vehicle's file (``path``: a vehicle's, or a scenario's), its validated
    ``spec``, its ``figures`` (a JSON-ready dict, see
    :func:`rocketsim.vehicle.summary.summary`) and its design ``review``
    (:class:`~rocketsim.vehicle.review.Review`)."""

    path: Path
    spec: VehicleSpec
    figures: dict
    review: Review

    @cached_property
    def model(self):
        """The vehicle's runtime arrays (:func:`rocketsim.vehicle.build.build`): the stages'
        bases and the length the stack is drawn with."""
        from rocketsim.vehicle.build import build
        return build(self.spec)


def vehicle_report(path: str | Path) -> VehicleReport:
    """The :class:`VehicleReport` of the staged vehicle in the file ``path`` (a vehicle
    file, or a scenario: its vehicle, with the rail it starts on); an
    :class:`~rocketsim.errors.InputError` for a missing or invalid file, or a rigid
    body (which has no stack)."""
    file_path(path, "path")
    path = Path(path)
    design = review(path)
    return VehicleReport(path, design.spec, design.summary, design)
