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
  ``SeedSequence(seed, spawn_key=(DESIGN,))``): the same row for any number of runs;
* ``lhs``: row ``k`` of the Latin hypercube of ``runs`` rows
  (:class:`scipy.stats.qmc.LatinHypercube`, the same seeding): it depends on ``runs``.

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
        self._design = None

    def design(self) -> np.ndarray | None:
        """The Sobol or LHS design (rows: runs, columns: :attr:`dims`), None for random."""
        if self.sampling == "random" or not self.dims:
            return None
        if self._design is None:
            from scipy.stats import qmc
            rng = np.random.Generator(np.random.PCG64(np.random.SeedSequence(self.seed, spawn_key=(DESIGN,))))
            if self.sampling == "sobol":
                m = max(int(np.ceil(np.log2(self.runs))), 0)
                self._design = qmc.Sobol(len(self.dims), scramble=True, rng=rng).random_base2(m)
            else:
                self._design = qmc.LatinHypercube(len(self.dims), rng=rng).random(self.runs)
        return self._design

    def uniforms(self, k: int) -> dict[str, float]:
        """Run ``k``'s ``u`` of every design dimension."""
        table = self.design()
        if table is None:
            found = {name: float(stream(self.seed, k, name).random()) for name in self.dims}
        else:
            found = {name: float(u) for name, u in zip(self.dims, table[k])}
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
