"""A run flown in this process (``workers=1``, no Dask) asks nothing of Dask: counting the
times a task was lost with its worker is 0 there, and does not import Dask's distributed
(whose import would be paid inside the first run)."""

import subprocess
import sys

import pytest

pytest.importorskip("distributed")


def test_a_run_outside_a_worker_was_never_lost_and_leaves_distributed_unimported():
    code = ("import sys\n"
            "from rocketsim.campaigns.run_task import _times_lost\n"
            "print(_times_lost(), 'distributed' in sys.modules)\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120, check=True)
    assert out.stdout.split() == ["0", "False"]
