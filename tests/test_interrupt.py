"""Ctrl-C and SIGTERM mid-flight: the MCAP is finished and readable."""

import signal
import subprocess
import sys
import time

import pytest
from mcap.reader import make_reader

from rocketsim.telemetry.reader import metadata


@pytest.mark.parametrize("signum, status", [(signal.SIGINT, 130), (signal.SIGTERM, 143)])
def test_a_signal_mid_flight_finishes_the_telemetry(scenario, tmp_path, signum, status):
    program = """
    def main(fc):
        fc.log("started")
        while True:
            fc.step()
    """
    path = scenario(program, duration="2 d")       # far longer than the test waits
    out = tmp_path / "run.mcap"
    process = subprocess.Popen([sys.executable, "-m", "rocketsim_cli.main", "fly", str(path), "-o", str(out)],
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + 60
    while (not out.exists() or out.stat().st_size < 20_000) and time.monotonic() < deadline:
        time.sleep(0.2)
    process.send_signal(signum)
    _, stderr = process.communicate(timeout=60)
    assert process.returncode == status, stderr
    assert "telemetry so far" in stderr and "Traceback" not in stderr
    with open(out, "rb") as stream:
        summary = make_reader(stream).get_summary()       # the summary section was written
    assert summary is not None and summary.statistics.message_count > 0
    assert metadata(out)["outcome"]["status"] == "error"
