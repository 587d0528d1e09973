"""Watch a flight as it flies, or a run's file again, in Foxglove: the live view's front door.

:func:`fly_live` flies a scenario to its MCAP file while a Foxglove WebSocket
server (:class:`rocketsim.live.server.LiveServer`) plays that file as it is
written, at ``warp`` x real time. The flight's telemetry goes to its writer as
it does headless; after each batch of steps (the flight's progress) the flight
waits while it leads the view too far (:meth:`~rocketsim.live.server.LiveServer.keep_pace`),
and never changes a step: the file is byte for byte the one the same flight
writes headless, at every warp, with or without a viewer. :func:`replay_live`
plays a file already written. Both return once the view has played the run to
its end (at ``max``, once the flight has flown) and the server has stopped.

The server listens on the loopback address unless another host is named, and
needs the ``live`` extra (Foxglove's SDK): ``pip install "rocketsim[live]"``.
"""

from __future__ import annotations

import dataclasses
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path
from typing import Callable, Mapping

from rocketsim.argument_checks import expect, switch, whole
from rocketsim.errors import ArgumentError, InputError
from rocketsim.live.clock import parse_warp, warp_text

LOOPBACK = "127.0.0.1"
PORT = 8765             # the Foxglove app's default for a WebSocket connection
MISSING = 'the live view needs Foxglove\'s SDK: pip install "rocketsim[live]"'


@dataclass(frozen=True)
class Live:
    """How a run is shown live: at ``warp`` (a positive number, or None for ``max``),
    served on ``host``:``port`` (0: any free port), from the start or ``paused`` (the
    flight waits until a viewer resumes it). ``on_ready(server)`` is called once the
    server listens, before anything flies (default: a line on stderr saying where)."""

    warp: float | None = 1.0
    port: int = PORT
    host: str = LOOPBACK
    paused: bool = False
    on_ready: Callable | None = None

    @classmethod
    def of(cls, given: "bool | Live | Mapping") -> "Live":
        """``given`` as the ``live`` argument of :func:`rocketsim.fly` takes it: True (the
        defaults), a :class:`Live`, or a mapping of its fields (``warp`` as a number or
        ``"max"``); an :class:`~rocketsim.errors.ArgumentError` naming ``live.<field>`` for a
        field it has not or a value of the wrong type."""
        if isinstance(given, Live):
            return given
        expect(given, (bool, Mapping), "live", "True, False, a Live or a mapping of its fields")
        fields = {} if given is True else dict(given)
        unknown = sorted(set(map(str, fields)) - {f.name for f in dataclasses.fields(cls)})
        if unknown:
            raise ArgumentError(f"no such field {unknown[0]!r}: a live view has warp, port, host, paused, "
                                "on_ready", "live")
        if "warp" in fields:
            try:
                fields["warp"] = parse_warp(fields["warp"])
            except ValueError as error:
                raise ArgumentError(str(error), "live.warp") from None
        if "port" in fields:
            fields["port"] = whole(fields["port"], "live.port", low=0, optional=False)
            if fields["port"] > 65535:
                raise ArgumentError(f"expected a port 0 .. 65535, got {fields['port']}", "live.port")
        expect(fields.get("host", LOOPBACK), (str,), "live.host", "a host name or address")
        fields["paused"] = switch(fields.get("paused", False), "live.paused")
        if fields.get("on_ready") is not None and not callable(fields["on_ready"]):
            expect(fields["on_ready"], (), "live.on_ready", "a callable on_ready(server) or None")
        return cls(**fields)


def available() -> None:
    """Raise an :class:`InputError` saying how to install the live view, if it is not."""
    try:
        import foxglove          # noqa: F401
        from foxglove import websocket  # noqa: F401
    except ImportError:
        raise InputError(MISSING) from None


def _announce(server) -> None:
    exposed = "" if server.host in (LOOPBACK, "localhost", "::1") else \
        "; other machines can watch and control it"
    print(f"live view: {server.url} at {warp_text(server.clock.warp)}{' paused' if server.clock.paused else ''} "
          f"(Foxglove: open a connection, Foxglove WebSocket, this address; controls: play/pause, speed, "
          f"or the parameters 'warp' and 'paused'{exposed})", file=sys.stderr, flush=True)


def _serve(path: Path, live: Live, name: str, time_range: tuple[int, int] | None):
    from rocketsim.live.server import LiveServer
    try:
        server = LiveServer(path, warp=live.warp, paused=live.paused, host=live.host, port=live.port,
                            name=name, time_range=time_range)
    except RuntimeError as error:       # the SDK's: the port is taken, the host not this machine's
        raise ArgumentError(f"cannot serve the live view on {live.host}:{live.port}: "
                            f"{str(error).removeprefix('FoxgloveError: ')}", "live.port") from None
    (live.on_ready or _announce)(server)
    return server


def fly_live(loaded, out: str | Path | None, live: Live, *, step: float | None = None,
             duration: float | None = None, on_progress=None, also: Callable | None = None) -> dict:
    """Fly ``loaded`` (a :class:`~rocketsim.scenario.load.LoadedScenario`) to the MCAP file
    ``out`` (None: a temporary file, removed after) shown live as ``live`` says; return
    the flight's summary (:func:`rocketsim.api.telemetry_flight.fly_to_file`'s).

    ``also(epoch_ns, program_file)``, if given, opens a second sink that gets the same
    calls as the file (a :class:`~rocketsim.api.recorder.Recorder`). The file is
    finished however the flight ends; the server is stopped however the view ends
    (Ctrl-C included)."""
    available()
    from rocketsim.live.tee import Tee
    from rocketsim.api.telemetry_flight import fly_into
    from rocketsim.telemetry.writer import TelemetryWriter

    with tempfile.TemporaryDirectory(prefix="rocketsim-live-") as folder:
        path = Path(out) if out is not None else Path(folder) / f"{loaded.path.stem}.mcap"
        flown = loaded.scenario.mission.duration if duration is None else duration
        servers, epochs = [], []

        def open_telemetry(epoch_ns: int, program_file: str):
            # the server first: a port it cannot have leaves no file behind
            servers.append(_serve(path, live, f"rocketsim {loaded.scenario.name}",
                                  (epoch_ns, epoch_ns + round(flown * 1e9))))
            epochs.append(epoch_ns)
            writer = TelemetryWriter(path, epoch_ns, program_file)
            servers[0].play()
            return writer if also is None else Tee([writer, also(epoch_ns, program_file)])

        def paced(t: float, phase: str) -> None:
            servers[0].keep_pace(epochs[0] + round(t * 1e9))    # the log time of mission time t
            if on_progress is not None:
                on_progress(t, phase)

        try:
            summary = fly_into(loaded, open_telemetry, step=step, duration=duration, on_progress=paced)
            servers[0].finish()
            servers[0].wait()
        finally:
            if servers:
                servers[0].stop()
        _report(servers[0])
    return summary


def replay_live(path: str | Path, live: Live) -> None:
    """Play the MCAP file ``path`` live as ``live`` says, to its end."""
    available()
    from rocketsim.telemetry.reader import read_run

    path = Path(path)
    if not path.is_file():
        raise InputError(f"no such file: {path}", file=path)
    run = read_run(path)
    if run.start_ns is None:
        raise InputError(f"nothing in it can be played{f': {run.problem}' if run.problem else ''}", file=path)
    time_range = (run.start_ns, run.end_ns)
    server = _serve(path, live, f"rocketsim {path.name}", time_range)
    try:
        server.play()
        server.finish()
        server.wait()
    finally:
        server.stop()
    _report(server)


def _report(server) -> None:
    """A live view that ended early says so (the file is whole all the same)."""
    if server.error is not None:
        print(f"the live view stopped early: {type(server.error).__name__}: {server.error} "
              "(the telemetry file is complete)", file=sys.stderr)
