"""The campaign file: a base scenario, how many runs, a seed, the dispersions.

A campaign file is YAML validated with pydantic, with the scenario loader's
errors (file, line, column, field; the nearest name of a misspelt field)::

    name: falcon9-landing
    scenario: ../scenarios/falcon9-leo.yaml     # relative to this file
    runs: 200
    seed: 2026
    sampling: random                 # random (default) | sobol | lhs
    overrides:                       # set on every run, as `rocketsim fly --set`
      mission.duration: 470 s
      weather: {kind: random, seed: 0}
    dispersions:                     # name -> a dispersion of one field (by path)
      thrust: {path: "vehicle.stages[booster].engines[*].thrust_vacuum", kind: normal, sigma: 1 %}
      dry_mass: {path: "vehicle.stages[booster].structure_mass", kind: normal, sigma: 150 kg,
                 min: 8500 kg, max: 9300 kg}
      day: {path: weather.seed, kind: seed}
      slip: {kind: slip, low: 0 s, high: 2 h}
    correlations:
      - {names: [thrust, isp], correlation: [[1, 0.6], [0.6, 1]]}
    outputs: [bodies.booster.final.surface_speed_m_s]     # extra summary values, by path
    insertion: {periapsis: 2 km, apoapsis: 2 km, inclination: 0.02 deg}   # the orbit reached vs the target
    telemetry: failed                # none | failed | all | [3, 17]: runs kept as MCAP
    timeout: 10 min                  # a run's wall time before it is stopped
    retries: 2                       # a run re-flown after its worker was lost

Dispersion kinds (every quantity a number in SI or a string with a unit the
field takes, ``"150 kg"``; ``"1 %"`` is relative to the scenario's nominal value):

* ``normal``: ``mean`` (default: the nominal), ``sigma``, optional truncation ``min``, ``max``;
* ``uniform``: ``low``, ``high`` (``"-2 %"`` .. ``"2 %"``: around the nominal);
* ``choice``: ``values`` (as the file would hold them), optional ``weights``;
* ``seed``: an integer drawn per run in ``low`` .. ``high`` (default 0 .. 2^31 - 1): a
  random day's ``weather.seed``, the scenario's ``seed`` (sensor noise);
* ``slip``: a launch slip added to ``mission.epoch``: uniform ``low`` .. ``high`` or
  ``distribution: normal`` with ``sigma`` (and ``mean``).

``correlations``: groups of ``normal`` dispersions drawn jointly, with a
``correlation`` matrix (their own sigmas) or a ``covariance`` matrix (SI units
squared, angles in rad; the group's sigmas are then left out). Correlated
dispersions take no truncation.
"""

from __future__ import annotations

from pathlib import Path
from typing import Annotated, Any, Literal, Mapping, Optional, Union

from pydantic import BaseModel, Field, field_validator, model_validator

from rocketsim.argument_checks import whole
from rocketsim.campaigns.insertion import InsertionTolerance
from rocketsim.errors import ArgumentError, InputError
from rocketsim.scenario.validation import validate
from rocketsim.scenario.units import STRICT, Duration
from rocketsim.scenario.yaml_source import YamlSource, read_yaml

# a value of a quantity: a number (SI) or a string with a unit ("150 kg", "1 %")
Value = Union[float, str]
MAX_RUNS = 10_000_000
MAX_LHS = 1_000_000     # runs of a Latin hypercube: it is drawn whole, 8 bytes per run and dimension
SEED_HIGH = 2 ** 31 - 1
LEADING = ("run",)          # column names a dispersion cannot take


class _Spec(BaseModel):
    model_config = STRICT


class Normal(_Spec):
    """A normal dispersion of the field at ``path``, optionally truncated to ``min`` .. ``max``."""

    kind: Literal["normal"]
    path: str
    mean: Optional[Value] = Field(None, description="default: the scenario's nominal value")
    sigma: Optional[Value] = Field(None, description="standard deviation; '1 %' of the nominal")
    min: Optional[Value] = None
    max: Optional[Value] = None


class Uniform(_Spec):
    """A uniform dispersion of the field at ``path`` between ``low`` and ``high``."""

    kind: Literal["uniform"]
    path: str
    low: Value
    high: Value


class Choice(_Spec):
    """One of ``values`` (as the scenario file would hold them), with optional ``weights``."""

    kind: Literal["choice"]
    path: str
    values: Annotated[list[Any], Field(min_length=1)]
    weights: Optional[list[Annotated[float, Field(ge=0)]]] = None

    @model_validator(mode="after")
    def _weights(self) -> "Choice":
        if self.weights is not None:
            if len(self.weights) != len(self.values):
                raise ValueError(f"{len(self.weights)} weights for {len(self.values)} values")
            if not sum(self.weights) > 0:
                raise ValueError("the weights add up to 0")
        return self


class Seed(_Spec):
    """An integer seed drawn per run, ``low`` .. ``high`` inclusive."""

    kind: Literal["seed"]
    path: str
    low: Annotated[int, Field(ge=0)] = 0
    high: Annotated[int, Field(ge=0)] = SEED_HIGH

    @model_validator(mode="after")
    def _order(self) -> "Seed":
        if self.high < self.low:
            raise ValueError("high is below low")
        return self


class Slip(_Spec):
    """A launch slip (s) added to the epoch at ``path``: uniform or normal in time."""

    kind: Literal["slip"]
    path: str = "mission.epoch"
    distribution: Literal["uniform", "normal"] = "uniform"
    low: Optional[Duration] = None
    high: Optional[Duration] = None
    mean: Duration = 0.0
    sigma: Optional[Annotated[Duration, Field(gt=0)]] = None

    @model_validator(mode="after")
    def _given(self) -> "Slip":
        if self.distribution == "uniform":
            if self.low is None or self.high is None or self.sigma is not None:
                raise ValueError("a uniform slip takes 'low' and 'high' (no 'sigma')")
            if not self.high > self.low:
                raise ValueError("high must be after low")
        elif self.sigma is None or self.low is not None or self.high is not None:
            raise ValueError("a normal slip takes 'sigma' (and 'mean'), no 'low' or 'high'")
        return self


Dispersion = Annotated[Union[Normal, Uniform, Choice, Seed, Slip], Field(discriminator="kind")]


class Correlation(_Spec):
    """Normal dispersions drawn jointly: a ``correlation`` or a ``covariance`` matrix."""

    names: Annotated[list[str], Field(min_length=2)]
    correlation: Optional[list[list[float]]] = None
    covariance: Optional[list[list[float]]] = None

    @model_validator(mode="after")
    def _matrix(self) -> "Correlation":
        if (self.correlation is None) == (self.covariance is None):
            raise ValueError("give exactly one of 'correlation' and 'covariance'")
        matrix = self.matrix
        n = len(self.names)
        if len(set(self.names)) != n:
            raise ValueError("a dispersion is named twice")
        if len(matrix) != n or any(len(row) != n for row in matrix):
            raise ValueError(f"the matrix must be {n} x {n}, one row and column per name")
        if any(matrix[i][j] != matrix[j][i] for i in range(n) for j in range(n)):
            raise ValueError("the matrix is not symmetric")
        if self.correlation is not None and any(matrix[i][i] != 1.0 for i in range(n)):
            raise ValueError("a correlation matrix has 1 on its diagonal")
        return self

    @property
    def matrix(self) -> list[list[float]]:
        return self.correlation if self.correlation is not None else self.covariance


Retention = Union[Literal["none", "failed", "all"], list[Annotated[int, Field(ge=0)]]]


class CampaignSpec(_Spec):
    """A campaign file (see the module)."""

    name: str
    description: str = ""
    scenario: Annotated[str, Field(pattern=r"\.ya?ml$")] = Field(
        description="the base scenario file, relative to the campaign file")
    runs: Annotated[int, Field(gt=0, le=MAX_RUNS)]
    seed: Annotated[int, Field(ge=0)] = Field(description="the campaign's seed: every run's inputs "
                                                          "derive from it and the run's number alone")
    sampling: Literal["random", "sobol", "lhs"] = "random"
    overrides: dict[str, Any] = Field(default_factory=dict, description="set on every run")
    dispersions: dict[str, Dispersion] = Field(default_factory=dict)
    correlations: list[Correlation] = Field(default_factory=list)
    outputs: list[str] = Field(default_factory=list, description="extra summary values, by path")
    insertion: Optional[InsertionTolerance] = Field(
        None, description="measure each run's insertion against the mission's target orbit, with these "
        "tolerances (rocketsim.campaigns.insertion)")
    telemetry: Retention = "none"
    timeout: Optional[Annotated[Duration, Field(gt=0)]] = Field(
        None, description="wall time a run may take before it is stopped (status timeout)")
    retries: Annotated[int, Field(ge=0, le=10)] = Field(
        2, description="times a run is re-flown after the worker flying it was lost")

    @field_validator("dispersions")
    @classmethod
    def _names(cls, value: dict) -> dict:
        for name in value:
            if name in LEADING or not name.strip():
                raise ValueError(f"{name!r} cannot name a dispersion (it names a column of its own)")
        return value


class Campaign:
    """A validated campaign: ``spec``, the file it came from (``path``, None for a
    mapping), where each field was written (``source``) and the base scenario's path."""

    def __init__(self, spec: CampaignSpec, path: Path | None, source: YamlSource | None,
                 base_dir: Path):
        self.spec = spec
        self.path = path
        self.source = source
        self.scenario = (base_dir / spec.scenario).resolve()

    def with_runs(self, runs: int | None) -> "Campaign":
        """This campaign flying ``runs`` runs in place of its file's (None: the file's), as
        the command line's ``--runs`` asks: run k is the same flight either way (its inputs
        derive from the seed and k alone; a Latin hypercube is drawn for the runs asked)."""
        if runs is not None:
            runs = whole(runs, "runs")
            if not 0 < runs <= MAX_RUNS:
                raise ArgumentError(f"{runs} runs: a campaign flies 1 .. {MAX_RUNS:,}", "runs")
            if self.spec.sampling == "lhs" and runs > MAX_LHS:
                raise ArgumentError(f"{runs:,} runs: a Latin hypercube (sampling: lhs) takes at most "
                                    f"{MAX_LHS:,}", "runs")
            self.spec = self.spec.model_copy(update={"runs": runs})
        return self

    def check_groups(self) -> None:
        """Each correlated group names normal dispersions, once each, untruncated, with
        sigmas given for a correlation matrix and left out for a covariance."""
        spec = self.spec
        seen: set[str] = set()
        for k, group in enumerate(spec.correlations):
            for name in group.names:
                given = spec.dispersions.get(name)
                if given is None:
                    raise self.error(f"no dispersion named {name!r}", "correlations", k, "names")
                if not isinstance(given, Normal):
                    raise self.error(f"{name!r} is not a normal dispersion", "correlations", k, "names")
                if name in seen:
                    raise self.error(f"{name!r} is in two groups", "correlations", k, "names")
                if given.min is not None or given.max is not None:
                    raise self.error(f"{name!r} is truncated: correlated dispersions take no min or max",
                                     "dispersions", name)
                if (given.sigma is None) == (group.covariance is None):
                    raise self.error("a dispersion of a covariance group takes its sigma from the matrix: "
                                     "leave 'sigma' out" if given.sigma is not None else
                                     "give 'sigma' (its group has a correlation matrix)", "dispersions", name)
                seen.add(name)
        for name, given in spec.dispersions.items():
            if isinstance(given, Normal) and given.sigma is None and name not in seen:
                raise self.error("give 'sigma'", "dispersions", name)

    def error(self, message: str, *loc) -> InputError:
        """An :class:`InputError` at the field ``loc`` of the campaign file."""
        line, column = (self.source.position(loc) if self.source is not None else None) or (None, None)
        return InputError(message, file=self.path, line=line, column=column,
                          field=".".join(str(part) for part in loc) or None)

    def resolved(self) -> dict:
        """The campaign as data with the scenario's absolute path (``campaign.yaml`` of a
        campaign directory; flying it gives the same runs from anywhere)."""
        data = self.spec.model_dump(mode="json", exclude_defaults=False)
        data["scenario"] = str(self.scenario)
        data["dispersions"] = {name: self.spec.dispersions[name].model_dump(mode="json", exclude_none=True)
                               for name in self.spec.dispersions}
        data["correlations"] = [group.model_dump(mode="json", exclude_none=True)
                                for group in self.spec.correlations]
        return data


def read_campaign(campaign: str | Path | Mapping, base_dir: str | Path | None = None) -> Campaign:
    """Read and validate a campaign file (or a mapping, its scenario relative to
    ``base_dir``, default the current folder); :class:`InputError` names the file,
    line and field of the first problem, and a missing scenario file."""
    if isinstance(campaign, Mapping):
        path, source = None, YamlSource(None, dict(campaign), {})     # errors name the field
        spec = validate(source, CampaignSpec)
        folder = Path(base_dir or ".")
    else:
        path = Path(campaign)
        source = read_yaml(path)
        if not isinstance(source.data, dict):
            raise InputError("expected a YAML mapping of campaign fields", file=path, line=1, column=1)
        spec = validate(source, CampaignSpec)
        folder = path.parent
    found = Campaign(spec, path, source, folder)
    if spec.sampling == "lhs" and spec.runs > MAX_LHS:
        raise found.error(f"{spec.runs:,} runs: a Latin hypercube (sampling: lhs) is drawn whole, in memory, "
                          f"and takes at most {MAX_LHS:,} runs; sampling sobol or random takes more", "runs")
    if not found.scenario.is_file():
        raise found.error(f"scenario file {spec.scenario!r} not found (looked for {found.scenario})",
                          "scenario")
    return found
