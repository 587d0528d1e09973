"""A scenario folder written once per test module (for module-scoped flights)."""

import textwrap
from pathlib import Path

from tests.conftest import MISSION, VEHICLE


def write_scenario(folder: Path, program: str, duration: str) -> Path:
    """The conftest coasting probe with ``program``, in ``folder``; returns the scenario path."""
    (folder / "vehicle.yaml").write_text(VEHICLE)
    (folder / "mission.yaml").write_text(MISSION.format(duration=duration))
    (folder / "program.py").write_text(textwrap.dedent(program))
    path = folder / "scenario.yaml"
    path.write_text("name: test\nvehicle: vehicle.yaml\nmission: mission.yaml\nprogram: program.py\n")
    return path
