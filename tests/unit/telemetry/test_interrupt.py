"""Ctrl-C and SIGTERM mid-flight: the MCAP is finished and readable, and whole
wherever the signal lands in the writer."""

import random
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
from mcap.reader import make_reader

from rocketsim.scenario.load import load
from rocketsim.api.telemetry_flight import fly_into
from rocketsim.telemetry import writer
from rocketsim.telemetry.reader import metadata
from rocketsim.telemetry.writer import TelemetryWriter
from tests.unit.telemetry.test_mcap_stream import InterruptAt, in_a_fresh_process, records_agreeing


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


class _Calls:
    """A flight's telemetry that keeps every call made to it, to make them again."""

    def __init__(self):
        self.calls = []

    def __getattr__(self, name):
        return lambda *args, **kwargs: self.calls.append((name, args, kwargs))

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        pass


def _write(path, calls, epoch_ns, tracer=None):
    """Make ``calls`` to a TelemetryWriter of ``path``, traced by ``tracer`` once it is open."""
    with TelemetryWriter(path, epoch_ns) as telemetry:
        sys.settrace(tracer)
        try:
            for name, args, kwargs in calls:
                getattr(telemetry, name)(*args, **kwargs)
        except KeyboardInterrupt:
            pass
        finally:
            try:
                telemetry.close()
            finally:
                sys.settrace(None)


def interrupted_writes(scenario_path: str, folder: str) -> None:
    """Fly ``scenario_path`` keeping its telemetry calls, then make them again into
    files of ``folder`` with SIGINT sent at 60 moments drawn over every bytecode the
    telemetry package runs on the flight's thread; assert each file whole."""
    folder = Path(folder)
    kept = _Calls()
    epoch_ns = 1795694400 * 10**9
    fly_into(load(Path(scenario_path)), lambda epoch, program_file: kept)
    whole = folder / "whole.mcap"
    _write(whole, kept.calls, epoch_ns)
    every = records_agreeing(whole.read_bytes())
    count = InterruptAt(-1, str(Path(writer.__file__).parent))
    _write(folder / "counted.mcap", kept.calls, epoch_ns, count)
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        for n in random.Random(11).sample(range(1, -count.n), 60):
            out = folder / f"{n}.mcap"
            try:
                _write(out, kept.calls, epoch_ns, InterruptAt(n, count.under))
            except KeyboardInterrupt:
                pass                        # it came in close, after the summary
            written = records_agreeing(out.read_bytes())
            assert written == every[:len(written)]
    finally:
        signal.signal(signal.SIGINT, previous)


def test_a_ctrl_c_at_any_moment_of_the_writer_leaves_a_whole_file(scenario, tmp_path):
    """The telemetry of a 30 s flight (300 samples over two chunks, a log line, an event,
    metadata, attachments) written again with SIGINT sent at 60 moments drawn over
    every bytecode the telemetry package runs on the flight's thread (the only one a
    signal interrupts: the file is written on the writer's own thread): each file's
    summary agrees with its records, and its messages are those of the whole file up
    to where it stopped, none twice, none skipped. (in a fresh
    process: :func:`tests.unit.telemetry.test_mcap_stream.in_a_fresh_process`)."""
    program = """
    def main(fc):
        fc.sleep(12.0)
        fc.log("twelve seconds")
        fc.event("marker", altitude_m=fc.altitude)
    """
    in_a_fresh_process("tests.unit.telemetry.test_interrupt:interrupted_writes",
                       str(scenario(program, duration="30 s")), str(tmp_path))
