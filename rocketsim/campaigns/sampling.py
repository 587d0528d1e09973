"""Every run's draws from (campaign seed, run number) alone.

Each dispersion draws a *standard* value per run, which
:mod:`rocketsim.campaigns.cases` scales to the field's units:

* ``normal``: ``z``, a standard normal (truncated to ``za`` .. ``zb`` by the inverse
  CDF, ``z = Φ⁻¹(Φ(za) + u (Φ(zb) - Φ(za)))``; a correlated group ``z = L Φ⁻¹(u)`` with
  ``L`` the Cholesky factor of its correlation matrix);
* ``uniform`` and a uniform ``slip``: ``u`` in [0, 1);
* ``choice``: the index of the value, ``u`` against the cumulated weights;
* ``seed``: an integer ``low`` .. ``high``.

Where each ``u`` comes from (``sampling``):

* ``random``: run ``k``'s dispersion named ``n`` draws from its own stream,
  ``numpy.random.Generator(PCG64(SeedSequence(seed, spawn_key=(k, crc32(n)))))``:
  independent of the other runs, of the number of runs and of the other
  dispersions (adding one changes no other's draws);
* ``sobol``: row ``k`` of the scrambled Sobol sequence (:class:`scipy.stats.qmc.Sobol`,
  one dimension per dispersion in the file's order, seeded by
  ``SeedSequence(seed, spawn_key=(DESIGN,))``): the same row for any number of runs.
  Rows are generated in blocks of :data:`BLOCK` (an engine fast-forwarded to the
  block's first row), so memory does not grow with the runs;
* ``lhs``: row ``k`` of the Latin hypercube of ``runs`` rows
  (:class:`scipy.stats.qmc.LatinHypercube`, the same seeding): it depends on ``runs``,
  and is drawn whole (8 bytes per run and dimension), hence at most :data:`rocketsim.campaigns.spec.MAX_LHS` runs.

Seeds are never a design dimension: they draw from the run's own stream in
every sampling. So run ``k``'s inputs are the same flown alone, serially, in a
pool, on a cluster, first time or resumed.
"""

from __future__ import annotations

import zlib
from dataclasses import dataclass

import numpy as np
from scipy.special import ndtr, ndtri

DESIGN = 2 ** 32 - 1       # spawn key of a Sobol / LHS design's stream (no run has this number)
BLOCK = 4096               # rows of a Sobol design generated at a time (a power of 2)
# u is kept inside (0, 1) so that Φ⁻¹(u) is finite: a draw of exactly 0 (probability
# 2^-53 per draw, 2^-30 for a Sobol point) becomes half the smallest step
_LOW, _HIGH = 2.0 ** -54, 1.0 - 2.0 ** -53


@dataclass(frozen=True)
class Law:
    """One dispersion's standard law: ``kind`` (normal, uniform, choice, seed), the
    truncation ``za`` .. ``zb`` of a normal, a choice's cumulated weights ``cumulated``,
    a seed's ``low`` .. ``high``."""

    kind: str
    za: float = -np.inf
    zb: float = np.inf
    cumulated: tuple[float, ...] = ()
    low: int = 0
    high: int = 0


def stream(seed: int, k: int, name: str) -> np.random.Generator:
    """Run ``k``'s random stream of the dispersion ``name`` (see the module)."""
    key = zlib.crc32(name.encode("utf-8"))
    return np.random.Generator(np.random.PCG64(np.random.SeedSequence(seed, spawn_key=(k, key))))


class Sampler:
    """The standard draws of every run of a campaign.

    ``laws``: name -> :class:`Law`, in the file's order (the design's dimensions);
    ``groups``: (names, Cholesky factor of their correlation) of correlated normals."""

    def __init__(self, seed: int, runs: int, sampling: str, laws: dict[str, Law],
                 groups: list[tuple[list[str], np.ndarray]] = ()):
        self.seed, self.runs, self.sampling = seed, runs, sampling
        self.laws = laws
        self.groups = list(groups)
        self.dims = [name for name, law in laws.items() if law.kind != "seed"]
        self._lhs = None
        self._block: tuple[int, np.ndarray] | None = None      # (first row, rows) of a Sobol design
        self._engine = None         # the Sobol engine positioned after that block

    def fresh(self) -> "Sampler":
        """The same sampler with caches of its own (the Latin hypercube, once drawn, shared):
        for another thread."""
        other = Sampler(self.seed, self.runs, self.sampling, self.laws, self.groups)
        other._lhs = self._lhs
        return other

    def _design_rng(self) -> np.random.Generator:
        return np.random.Generator(np.random.PCG64(np.random.SeedSequence(self.seed, spawn_key=(DESIGN,))))

    def _sobol_row(self, k: int) -> np.ndarray:
        """Row ``k`` of the Sobol design, from the block of :data:`BLOCK` rows holding it
        (the next block continues the engine; another one starts a fresh engine, the same
        scramble, fast-forwarded to it)."""
        first = k - k % BLOCK
        if self._block is None or self._block[0] != first:
            from scipy.stats import qmc
            following = self._block is not None and self._block[0] + BLOCK == first
            if not following:
                self._engine = qmc.Sobol(len(self.dims), scramble=True, rng=self._design_rng())
                if first:
                    self._engine.fast_forward(first)
            self._block = (first, self._engine.random(BLOCK))
        return self._block[1][k - first]

    def _lhs_row(self, k: int) -> np.ndarray:
        if self._lhs is None:
            from scipy.stats import qmc
            self._lhs = qmc.LatinHypercube(len(self.dims), rng=self._design_rng()).random(self.runs)
        return self._lhs[k]

    def uniforms(self, k: int) -> dict[str, float]:
        """Run ``k``'s ``u`` of every design dimension."""
        if self.sampling == "random" or not self.dims:
            found = {name: float(stream(self.seed, k, name).random()) for name in self.dims}
        else:
            row = self._sobol_row(k) if self.sampling == "sobol" else self._lhs_row(k)
            found = {name: float(u) for name, u in zip(self.dims, row)}
        return {name: min(max(u, _LOW), _HIGH) for name, u in found.items()}

    def draw(self, k: int) -> dict[str, float | int]:
        """Run ``k``'s standard draw of every dispersion (see the module)."""
        if not 0 <= k < self.runs:
            raise IndexError(f"run {k} is not one of the campaign's {self.runs} runs (0 .. {self.runs - 1})")
        u = self.uniforms(k)
        found: dict[str, float | int] = {}
        grouped = {name for names, _ in self.groups for name in names}
        for name, law in self.laws.items():
            if law.kind == "seed":
                found[name] = int(stream(self.seed, k, name).integers(law.low, law.high, endpoint=True))
            elif law.kind == "normal" and name not in grouped:
                if np.isinf(law.za) and np.isinf(law.zb):
                    found[name] = float(ndtri(u[name]))
                else:
                    pa, pb = ndtr(law.za), ndtr(law.zb)
                    found[name] = float(np.clip(ndtri(pa + u[name] * (pb - pa)), law.za, law.zb))
            elif law.kind == "choice":
                found[name] = min(int(np.searchsorted(law.cumulated, u[name], side="right")),
                                  len(law.cumulated) - 1)
            elif law.kind != "normal":
                found[name] = u[name]
        for names, factor in self.groups:
            z = factor @ ndtri(np.array([u[name] for name in names]))
            found.update({name: float(value) for name, value in zip(names, z)})
        return {name: found[name] for name in self.laws}


def cholesky(correlation) -> np.ndarray:
    """The lower Cholesky factor of a correlation matrix; ValueError when it is not
    positive definite (no joint normal law has it)."""
    try:
        return np.linalg.cholesky(np.asarray(correlation, dtype=float))
    except np.linalg.LinAlgError:
        raise ValueError("the matrix is not positive definite: no joint normal law has it") from None
