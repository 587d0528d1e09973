"""The MCAP writer and the in-memory recorder are both telemetry sinks, and the world
writes through nothing else.

:class:`~rocketsim.telemetry.sink.TelemetrySink` names the calls a flight writes
its telemetry through. Each implementation must define every one of them itself
(not inherit the protocol's empty body) with the protocol's parameters: names,
kinds and defaults; and the world's modules (``rocketsim/sim/``) and the flight
that opens the telemetry (``rocketsim/api/telemetry_flight.py``) must call no other
method of it. A call added to one side only fails here.
"""

from __future__ import annotations

import ast
import inspect
from pathlib import Path

import pytest

from rocketsim.api.recorder import Recorder
from rocketsim.live.tee import Tee
from rocketsim.sim.sample_watch import SampleWatch
from rocketsim.telemetry.sink import TelemetrySink
from rocketsim.telemetry.writer import TelemetryWriter

ROOT = Path(__file__).resolve().parents[3]
CALLS = sorted(name for name, value in vars(TelemetrySink).items()
               if callable(value) and (not name.startswith("_") or name in ("__enter__", "__exit__")))


def _parameters(function) -> list[tuple]:
    return [(p.name, p.kind, p.default) for p in inspect.signature(function).parameters.values()]


def test_the_protocol_names_the_calls_of_a_flight():
    assert CALLS == ["__enter__", "__exit__", "add_body", "attach", "close", "error", "event", "log",
                     "metadata", "sample", "sample_interleaved", "sample_rows"]


def problems(sink: type) -> list[str]:
    """Each call of the protocol ``sink`` does not define itself, or defines with other
    parameters."""
    found = []
    for name in CALLS:
        member = getattr(sink, name, None)
        if member is None or member is getattr(TelemetrySink, name):
            found.append(f"{sink.__name__} lacks {name}")
        elif _parameters(getattr(sink, name)) != _parameters(getattr(TelemetrySink, name)):
            found.append(f"{sink.__name__}.{name}{inspect.signature(getattr(sink, name))} is not the protocol's")
    return found


@pytest.mark.parametrize("sink", [TelemetryWriter, Recorder, Tee, SampleWatch])
def test_each_sink_defines_every_call_with_the_protocols_parameters(sink):
    assert issubclass(sink, TelemetrySink)
    assert not problems(sink)


def test_a_writer_and_a_recorder_are_sinks(tmp_path):
    writer = TelemetryWriter(tmp_path / "run.mcap", 0)
    try:
        assert isinstance(writer, TelemetrySink)
    finally:
        writer.close()
    assert isinstance(Recorder(0), TelemetrySink)


def test_a_sink_missing_a_call_or_mislabelling_one_is_caught():
    class Silent(Recorder):             # declares the protocol, and takes ``error`` back out
        error = TelemetrySink.error

    class Mislabelled(Recorder):
        def log(self, t, message):
            pass

    class Duck:                         # no declaration, no ``error``
        add_body = Recorder.add_body

    assert "Silent lacks error" in problems(Silent)
    assert problems(Mislabelled) == ["Mislabelled.log(self, t, message) is not the protocol's"]
    assert not isinstance(Duck(), TelemetrySink)


def _telemetry_calls(path: Path) -> set[str]:
    """The methods ``path`` calls on a telemetry: ``telemetry.x(...)``, ``*.telemetry.x(...)``."""
    found = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute):
            owner = node.func.value
            name = owner.id if isinstance(owner, ast.Name) else owner.attr if isinstance(owner, ast.Attribute) else None
            if name == "telemetry":
                found.add(node.func.attr)
    return found


def test_the_world_calls_only_the_protocol():
    # the world's modules, and the flight around it that opens the telemetry
    writers = [*sorted((ROOT / "rocketsim" / "sim").glob("*.py")), ROOT / "rocketsim/api/telemetry_flight.py"]
    called = {(path.name, call) for path in writers for call in _telemetry_calls(path)}
    assert {call for _, call in called} >= {"add_body", "sample", "sample_rows", "sample_interleaved",
                                             "event", "log", "error", "attach", "metadata"}
    assert not [f"{name}: telemetry.{call}" for name, call in called if call not in CALLS]
