"""A campaign's inputs are drawn lazily: run k draws what it drew when the design was whole.

Sobol rows come in blocks (an engine fast-forwarded to the block), the inputs
file is written block by block beside the first runs, and nothing is drawn for
every run before the first flies. Run k's draws must not change by it: they are
checked against the draws this campaign gave when every design was drawn whole
(``DRAWN``, written down, as hexadecimal floats, from that code), and the Sobol
rows against scipy's whole design (:meth:`scipy.stats.qmc.Sobol.random_base2`),
in an order that crosses blocks forwards, backwards and from a fresh engine.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import pyarrow.parquet as pq
import pytest
from scipy.stats import qmc

from rocketsim.campaigns import store as store_module
from rocketsim.campaigns.cases import Plan
from rocketsim.campaigns.sampling import BLOCK, DESIGN, Law, Sampler
from rocketsim.campaigns.spec import MAX_LHS, read_campaign
from rocketsim.errors import InputError
from tests.campaign_files import write_arc
from tests.unit.campaigns.test_campaign_sampling import CAMPAIGN

NAMES = ["elevation", "mass", "noise", "rate_x", "rate_y", "slip", "step", "v_north", "v_up"]
# run k's standard draws of CAMPAIGN (5000 runs), by sampling, as the whole-design code drew them
DRAWN = {
    ('lhs', 0): ['0x1.f529a9736558ep-1', '-0x1.8d42f601b16b4p-2', 12, '0x1.b8af19990d65cp-5', '-0x1.788b1c80e179dp-3', '0x1.6f6991a04134dp-1', 1, '0x1.174ff20474bcep-3', '-0x1.4c419e0751f19p+0'],  # noqa: E501
    ('lhs', 4095): ['0x1.ef3421efdaf21p-4', '-0x1.34eb19b883ce4p-4', 17, '-0x1.fd1fa0087bc77p-1', '0x1.3c1b219e75792p-3', '0x1.d43a004ef4c57p-3', 0, '-0x1.4af620bfb3cf3p-3', '0x1.3052d2fff4d05p+0'],  # noqa: E501
    ('lhs', 4999): ['0x1.533cf7dd783f5p-1', '-0x1.79b3eb3ad423ap-1', 18, '0x1.1d6e07241d2e4p-1', '-0x1.34e704a64fc46p+0', '0x1.84c19c2d3a219p-1', 0, '0x1.7df4ed26c6721p-1', '0x1.7fd1e896ebf0dp-1'],  # noqa: E501
    ('random', 0): ['0x1.6bed6e7d451c8p-2', '0x1.9320e12203bc0p-2', 12, '0x1.726ef671d3e40p+0', '-0x1.d121e420abdefp+0', '0x1.add0d31e7e3cdp-1', 0, '-0x1.26ee308133a4cp-4', '0x1.3a95d37132bbdp-1'],  # noqa: E501
    ('random', 4096): ['0x1.4254466213cf6p-1', '-0x1.c6485e8f9965bp-4', 10, '0x1.1c27cd3d26b5bp-2', '-0x1.13cb0b56f9041p-1', '0x1.b54e213e80f2fp-1', 2, '0x1.2744ad8d0b8bcp+0', '0x1.53346185c923dp-1'],  # noqa: E501
    ('random', 4999): ['0x1.1d4b0ca12d198p-4', '-0x1.560c659071085p-2', 18, '0x1.439ac127ac864p-1', '-0x1.031c7cae82124p-5', '0x1.e9238ccb5f8a0p-4', 2, '0x1.a429b0fbc84b7p-3', '0x1.67106e0112db0p+0'],  # noqa: E501
    ('sobol', 0): ['0x1.d2ef413000000p-1', '0x1.268b935c799c3p-1', 12, '-0x1.b11cdd30a0febp-2', '0x1.1188252440c5fp-5', '0x1.48f9817000000p-2', 1, '-0x1.0681db0abb350p+0', '0x1.c4ac543c97090p-2'],  # noqa: E501
    ('sobol', 1): ['0x1.174683d000000p-2', '-0x1.3faf07820045ap-3', 11, '0x1.b98cb6ad1132cp+0', '-0x1.fa4270a800593p-1', '0x1.ec91197000000p-1', 0, '0x1.8adaa04d0fb5dp+0', '0x1.9aac9faf3a010p-1'],  # noqa: E501
    ('sobol', 4095): ['0x1.954641a000000p-3', '0x1.719f2bec5d344p+0', 17, '0x1.3b177cb5b6754p-5', '-0x1.2e428b9394df1p+0', '0x1.3b1e14f000000p-2', 0, '-0x1.066f1092ddd23p+0', '-0x1.556e74f77cffbp+0'],  # noqa: E501
    ('sobol', 4096): ['0x1.421cca5000000p-2', '-0x1.7b2b19242cdf0p-1', 10, '0x1.20ab3bb74a2acp+0', '-0x1.b885d110e5bddp-4', '0x1.fbe0501800000p-1', 1, '-0x1.065d55a0bc32dp+0', '-0x1.23a65767e7ffcp-3'],  # noqa: E501
    ('sobol', 4999): ['0x1.b4dc8af800000p-1', '0x1.2d402617600b5p-4', 18, '-0x1.84ecaaddc0b17p-2', '0x1.48efc8e6bb326p+0', '0x1.5090288000000p-1', 2, '-0x1.2b148b0c36a3bp+0', '-0x1.25043c781d4cap+0'],  # noqa: E501
}


def plan_of(folder, sampling: str, runs: int = 5000) -> Plan:
    return Plan(read_campaign(write_arc(folder, CAMPAIGN.format(runs=runs, sampling=sampling))))


def written(draws: dict) -> list:
    return [draws[name] if isinstance(draws[name], int) else float(draws[name]).hex() for name in NAMES]


@pytest.mark.parametrize("sampling", ["random", "sobol", "lhs"])
def test_each_run_draws_what_it_drew_with_the_whole_design(sampling, tmp_path):
    plan = plan_of(tmp_path, sampling)
    # the last block first (a fresh engine fast-forwarded), then back to the first, then on
    for k in sorted((k for s, k in DRAWN if s == sampling), key=lambda k: -k if k > BLOCK else k):
        assert written(plan.sampler.draw(k)) == DRAWN[sampling, k], (sampling, k)


def test_sobol_rows_in_any_order_are_the_whole_designs_rows():
    runs = 3 * BLOCK + 5
    laws = {name: Law("uniform") for name in "abc"}
    sampler = Sampler(11, runs, "sobol", laws)
    rng = np.random.Generator(np.random.PCG64(np.random.SeedSequence(11, spawn_key=(DESIGN,))))
    whole = qmc.Sobol(3, scramble=True, rng=rng).random_base2(int(np.ceil(np.log2(runs))))
    order = [runs - 1, 2 * BLOCK, 2 * BLOCK - 1, 0, 1, BLOCK - 1, BLOCK, BLOCK + 1, 3 * BLOCK, 17]
    for k in order:
        row = sampler.uniforms(k)
        assert [row[name] for name in "abc"] == [max(u, 2.0 ** -54) for u in whole[k]], k


def test_the_inputs_file_is_written_block_by_block_and_holds_every_run(tmp_path, monkeypatch):
    monkeypatch.setattr(store_module, "INPUTS_BLOCK", 7)
    plan = plan_of(tmp_path, "random", runs=20)
    path = tmp_path / "inputs.parquet"
    store_module.InputsWriter(plan, path).finish()
    assert pq.ParquetFile(path).metadata.num_row_groups == 3        # 7 + 7 + 6 runs
    table = pd.read_parquet(path)
    pd.testing.assert_frame_equal(table, plan.inputs_table())
    for k in (0, 6, 7, 19):
        assert table.iloc[k].drop("run").to_dict() == pytest.approx(plan.inputs(k), rel=0, abs=0)
    assert not list(tmp_path.glob(".inputs.parquet*"))


def test_a_cancelled_inputs_file_is_absent(tmp_path, monkeypatch):
    monkeypatch.setattr(store_module, "INPUTS_BLOCK", 1)
    plan = plan_of(tmp_path, "sobol", runs=2000)
    writer = store_module.InputsWriter(plan, tmp_path / "inputs.parquet")
    writer.cancel()
    writer.finish()         # nothing to raise: it was stopped, not broken
    assert not list(tmp_path.glob("*inputs.parquet*"))


def test_a_latin_hypercube_too_large_to_draw_is_refused_at_its_line(tmp_path):
    path = write_arc(tmp_path, CAMPAIGN.format(runs=MAX_LHS + 1, sampling="lhs"))
    with pytest.raises(InputError) as error:
        read_campaign(path)
    assert (error.value.line, error.value.field) == (3, "runs")
    assert "1,000,001 runs" in str(error.value) and "sobol or random" in str(error.value)
    with pytest.raises(InputError, match="^runs: "):
        read_campaign(write_arc(tmp_path, CAMPAIGN.format(runs=10, sampling="lhs"))).with_runs(MAX_LHS + 1)
