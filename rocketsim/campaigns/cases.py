"""A campaign's runs as scenarios: each run's inputs and the overrides that fly them.

:class:`Plan` resolves each dispersion's path against the base scenario (with
the campaign's fixed ``overrides``) once, before anything flies: a path that
names no field is an :class:`~rocketsim.errors.InputError` at the campaign
file's line, with the nearest valid path; each quantity is read in the field's
own units (``"150 kg"`` for a mass, ``"0.5 deg"`` for an angle; ``"1 %"`` of the
nominal value, the scenario's validated SI value at that path); and the
scenario is loaded once with every dispersion at its centre, so a value the
field cannot take is reported then too.

Run ``k``'s inputs (:meth:`Plan.inputs`) are SI values (angles in rad, a slip
in s, seeds as integers, a choice as the value chosen); its overrides
(:meth:`Plan.overrides`) are what a scenario file would hold: a bare SI number,
an angle as ``"<x> rad"`` (``repr`` of the float, which reads back to the same
bits), the epoch as a datetime. A path that selects several fields
(``engines[*]``) sets each one from the same standard draw, each around its
own nominal value; the input column holds the first one's value.
"""

from __future__ import annotations

import datetime as dt
import json
import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from rocketsim.campaigns.sampling import Law, Sampler, cholesky
from rocketsim.campaigns.spec import Campaign, Choice, Seed, Slip, Uniform
from rocketsim.errors import InputError
from rocketsim.scenario.field_places import Place, locate, nearest_path
from rocketsim.scenario.load import LoadedScenario, load
from rocketsim.scenario.models import Scenario
from rocketsim.scenario.paths import PathError, parse
from rocketsim.scenario.units import UnitError


@dataclass(frozen=True)
class Scale:
    """How a standard draw becomes a field's SI value: ``offset + scale * draw``."""

    offset: float
    scale: float


class Plan:
    """The runs of ``campaign`` (a :class:`~rocketsim.campaigns.spec.Campaign`), checked."""

    def __init__(self, campaign: Campaign):
        self.campaign = campaign
        spec = campaign.spec
        campaign.check_groups()
        self.fixed = dict(spec.overrides)
        self.base = self._load(self.fixed)
        if spec.insertion is not None and self.base.scenario.mission.target.orbit is None:
            raise campaign.error("an insertion is measured against the scenario's target orbit, and it "
                                 "names none (mission.target.orbit: altitude, inclination)", "insertion")
        self.places: dict[str, list[Place]] = {}
        self.scales: dict[str, list[Scale]] = {}
        laws: dict[str, Law] = {}
        for name, given in spec.dispersions.items():
            self.places[name] = self._places(name, given.path)
        sigmas = self._group_sigmas()
        for name, given in spec.dispersions.items():
            laws[name], self.scales[name] = self._law(name, given, sigmas.get(name))
        groups = []
        for k, group in enumerate(spec.correlations):
            matrix = np.asarray(group.matrix, dtype=float)
            if group.covariance is not None:
                s = np.sqrt(np.diag(matrix))
                matrix = matrix / np.outer(s, s)
            try:
                groups.append((list(group.names), cholesky(matrix)))
            except ValueError as error:
                raise campaign.error(str(error), "correlations", k) from None
        self.sampler = Sampler(spec.seed, spec.runs, spec.sampling, laws, groups)
        self.nominal()      # every path and unit, once

    # --- what each run flies ------------------------------------------------------

    def inputs(self, k: int) -> dict[str, Any]:
        """Run ``k``'s value of every dispersion (SI; see the module)."""
        return self._inputs(self.sampler, k)

    def _inputs(self, sampler: Sampler, k: int) -> dict[str, Any]:
        draws = sampler.draw(k)
        return {name: self._values(name, draws[name])[0] for name in self.places}

    def overrides(self, k: int) -> dict[str, Any]:
        """Run ``k``'s overrides: the campaign's fixed ones, then every dispersion's."""
        draws = self.sampler.draw(k)
        found = dict(self.fixed)
        for name, places in self.places.items():
            for place, value in zip(places, self._values(name, draws[name])):
                found[place.path] = self._written(name, place, value)
        return found

    def scenario(self, k: int) -> LoadedScenario:
        """Run ``k``'s scenario, loaded with its overrides."""
        return load(self.campaign.scenario, self.overrides(k))

    def nominal(self) -> LoadedScenario:
        """The nominal run's scenario: every dispersion at its centre (a normal's mean, a
        uniform's middle, the first choice, a seed's low); a problem an override causes is
        reported at the campaign's line that gave it."""
        return self._load(self.fixed | self._centre_overrides())

    def variants(self) -> list[LoadedScenario]:
        """The nominal scenario and, for each ``choice`` dispersion, the nominal with each of
        its values: every program any run flies is one of theirs (the other kinds draw
        numbers, seeds and epochs)."""
        found = [self.nominal()]
        centre = self.fixed | self._centre_overrides()
        for name, given in self.campaign.spec.dispersions.items():
            if isinstance(given, Choice):
                for index in range(1, len(given.values)):
                    values = self._values(name, index)
                    found.append(self._load(centre | {place.path: self._written(name, place, value)
                                                      for place, value in zip(self.places[name], values)}))
        return found

    def inputs_table(self, first: int = 0, stop: int | None = None):
        """Runs ``first`` .. ``stop - 1``'s inputs (default: every run's) as a DataFrame:
        ``run``, then a column per dispersion (float64; int64 for seeds; str for a choice
        of strings or of mappings). Drawn with a sampler of its own (:meth:`Sampler.fresh`),
        so a thread writing the table leaves the runs' sampler alone."""
        import pandas as pd
        stop = self.campaign.spec.runs if stop is None else stop
        sampler = self.sampler.fresh()
        rows = [self._inputs(sampler, k) for k in range(first, stop)]
        table = {"run": np.arange(first, stop, dtype=np.int64)}
        for name, given in self.campaign.spec.dispersions.items():
            column = [row[name] for row in rows]
            if isinstance(given, Seed):
                table[name] = np.asarray(column, dtype=np.int64)
            elif isinstance(given, Choice) and not all(_number(v) for v in given.values):
                table[name] = pd.array([v if isinstance(v, str) else json.dumps(v, default=str)
                                        for v in column], dtype=object)
            else:
                table[name] = np.asarray(column, dtype=np.float64)
        return pd.DataFrame(table)

    # --- resolving ----------------------------------------------------------------

    def _load(self, overrides: dict) -> LoadedScenario:
        """The base scenario with ``overrides``; an error an override caused is reported at
        the campaign's line that gave it."""
        try:
            return load(self.campaign.scenario, overrides)
        except InputError as error:
            raise self._placed(error) from None

    def _placed(self, error: InputError) -> InputError:
        text = f"{error.field or ''} {error.message}"

        for name, places in getattr(self, "places", {}).items():
            for place in places:
                if place.path in text:
                    return self.campaign.error(f"{error}", "dispersions", name, "path")
        for path in self.fixed:
            if path in text:        # the campaign's field names the path: said once
                shown = error.message if error.file is None and error.field == path else f"{error}"
                return self.campaign.error(shown, "overrides", path)
        return error

    def _places(self, name: str, path: str) -> list[Place]:
        try:
            steps = parse(path)
            return locate(self.base.scenario, Scenario, steps, "")
        except PathError as error:
            message = f"{error}"
            try:
                fixed = nearest_path(self.base.scenario, Scenario, parse(path))
            except PathError:
                fixed = None
            if fixed is not None and fixed != path:
                message += f"; nearest valid path: {fixed!r}"
            raise self.campaign.error(message, "dispersions", name, "path") from None

    def _group_sigmas(self) -> dict[str, float]:
        found = {}
        for group in self.campaign.spec.correlations:
            if group.covariance is not None:
                found.update({name: math.sqrt(group.covariance[i][i]) for i, name in enumerate(group.names)})
        return found

    def _law(self, name: str, given, covariance_sigma: float | None) -> tuple[Law, list[Scale]]:
        places = self.places[name]
        if isinstance(given, Seed):
            return Law("seed", low=given.low, high=given.high), []
        if isinstance(given, Choice):
            weights = np.asarray(given.weights or [1.0] * len(given.values), dtype=float)
            return Law("choice", cumulated=tuple(np.cumsum(weights) / weights.sum())), []
        if isinstance(given, Slip):
            for place in places:
                if not isinstance(place.nominal, dt.datetime):
                    raise self.campaign.error(f"{place.path} is not an epoch (a date and time): a slip "
                                              "shifts an epoch", "dispersions", name, "path")
            if given.distribution == "uniform":
                return Law("uniform"), [Scale(given.low, given.high - given.low)] * len(places)
            return Law("normal"), [Scale(given.mean, given.sigma)] * len(places)
        scales = []
        bounds = None
        for place in places:
            read = self._reader(name, place)
            if isinstance(given, Uniform):
                low, high = read(given.low, "low"), read(given.high, "high")
                if not high > low:
                    raise self.campaign.error("high must be above low", "dispersions", name, "high")
                scales.append(Scale(low, high - low))
                continue
            mean = read(given.mean, "mean") if given.mean is not None else self._nominal(name, place)
            sigma = covariance_sigma if covariance_sigma is not None else read(given.sigma, "sigma", delta=True)
            if not sigma > 0:
                raise self.campaign.error("sigma must be above 0", "dispersions", name, "sigma")
            scales.append(Scale(mean, sigma))
            if bounds is None:
                za = (read(given.min, "min") - mean) / sigma if given.min is not None else -math.inf
                zb = (read(given.max, "max") - mean) / sigma if given.max is not None else math.inf
                if not zb > za:
                    raise self.campaign.error("max must be above min", "dispersions", name, "max")
                if not (za <= 0 <= zb):
                    raise self.campaign.error("the mean is outside min .. max", "dispersions", name, "min")
                bounds = (za, zb)
        if isinstance(given, Uniform):
            return Law("uniform"), scales
        return Law("normal", za=bounds[0], zb=bounds[1]), scales

    def _nominal(self, name: str, place: Place) -> float:
        if not _number(place.nominal):
            raise self.campaign.error(f"{place.path} has no nominal number in the scenario "
                                      f"({place.nominal!r}): give the dispersion a 'mean'",
                                      "dispersions", name, "path")
        return float(place.nominal)

    def _reader(self, name: str, place: Place):
        """``read(value, field, delta=False)``: a quantity of the dispersion ``name`` in SI at
        ``place``: ``"x %"`` of the nominal (a ``delta``: of its size), a number, or a
        string in the field's units (a ``delta`` read as a difference: ``"2 C"`` is 2 K)."""

        def read(value, field: str, delta: bool = False) -> float:
            if isinstance(value, str) and value.strip().endswith("%"):
                try:
                    fraction = float(value.strip()[:-1]) / 100.0
                except ValueError:
                    raise self.campaign.error(f"expected '<number> %', got {value!r}",
                                              "dispersions", name, field) from None
                nominal = self._nominal(name, place)
                return abs(nominal) * fraction if delta else nominal * (1.0 + fraction)
            if place.read is None:
                if isinstance(value, str):
                    raise self.campaign.error(f"{place.path} is a plain number: give {field} as a "
                                              f"number (or '<x> %'), not {value!r}", "dispersions", name, field)
                return float(value)
            try:
                if delta and isinstance(value, str):
                    number, _, unit = value.strip().partition(" ")
                    return place.read(value) - place.read(f"0 {unit}")
                return place.read(value)
            except UnitError as error:
                raise self.campaign.error(f"{error} (the unit of {place.path})", "dispersions",
                                          name, field) from None

        return read

    def _values(self, name: str, draw) -> list[Any]:
        """The SI value of each place of dispersion ``name`` for the standard ``draw``."""
        given = self.campaign.spec.dispersions[name]
        places = self.places[name]
        if isinstance(given, Seed):
            return [int(draw)] * len(places)
        if isinstance(given, Choice):
            return [given.values[int(draw)]] * len(places)
        return [scale.offset + scale.scale * draw for scale in self.scales[name]]

    def _written(self, name: str, place: Place, value):
        """``value`` as a scenario file would hold it at ``place``."""
        given = self.campaign.spec.dispersions[name]
        if isinstance(given, Slip):
            return place.nominal + dt.timedelta(seconds=value)
        if isinstance(given, (Seed, Choice)):
            return value
        return f"{value!r} rad" if place.angle else value

    def _centre_overrides(self) -> dict[str, Any]:
        """Every dispersion at its centre (see :meth:`nominal`)."""
        found = {}
        for name, given in self.campaign.spec.dispersions.items():
            if isinstance(given, Seed):
                draw = given.low
            elif isinstance(given, Choice):
                draw = 0
            elif isinstance(given, Uniform) or (isinstance(given, Slip) and given.distribution == "uniform"):
                draw = 0.5
            else:
                draw = 0.0
            for place, value in zip(self.places[name], self._values(name, draw)):
                found[place.path] = self._written(name, place, value)
        return found

    # --- what the report reads ---------------------------------------------------

    def target(self) -> dict:
        """The mission's target pad if it has one, else the launch site (meta.json's ``target``)."""
        scenario = self.base.scenario
        pad = scenario.mission.target.pad
        if pad is not None and not isinstance(pad, str):
            return {"name": pad.name, "latitude_deg": math.degrees(pad.latitude),
                    "longitude_deg": math.degrees(pad.longitude), "kind": "pad"}
        site = scenario.site
        if site is None:
            return {"name": None, "latitude_deg": math.nan, "longitude_deg": math.nan, "kind": "site"}
        return {"name": site.name, "latitude_deg": math.degrees(site.latitude),
                "longitude_deg": math.degrees(site.longitude), "kind": "site"}


def _number(value) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool)
