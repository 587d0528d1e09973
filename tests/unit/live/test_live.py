"""The live view: a flight served to Foxglove as it flies, at a warp, its file unchanged.

A real client (tests/live_client.py: the ``websockets`` library's WebSocket,
the Foxglove protocol's messages) connects on the loopback address to an
ephemeral port, subscribes, receives the channels and messages, pauses and
resumes, changes the warp; the checks are that the MCAP file is byte for byte
the headless flight's at every warp with and without a client, that the client
receives every message of the file (channels with their schemas, messages with
their log times and bytes, the last one before the server stops), that nothing is
served while paused and the flight stands still, and that a client which stops
reading loses only its own copy.
The flights are a small probe coasting in orbit with 50 Hz telemetry (a
chunk of the file is about 3 s of it, so a 20 s flight is 7 chunks and the
flight waits for the view between them) and a few seconds of the hobby
rocket's boost. Every wait is bounded; every server is stopped (the front door
stops it however the flight ends, and a watchdog stops it if a test stalls).
"""

from __future__ import annotations

import json
import shutil
import sys
import threading
import time
from pathlib import Path

import pytest
from click.testing import CliRunner
from mcap.opcode import Opcode
from mcap.reader import make_reader

from rocketsim.api.live import Live, fly_live, replay_live
from rocketsim.errors import InputError
from rocketsim.live.clock import MAX, PlaybackClock, parse_warp
from rocketsim.live.cpu_share import CpuShare
from rocketsim.live.growing import DamagedFile, GrowingMcap, chunk_messages
from rocketsim.live.server import BACKLOG, LiveServer
from rocketsim.scenario.load import load
from rocketsim.api.telemetry_flight import fly_to_file as fly
from rocketsim.telemetry.reader import raw_messages
from tests.live_client import PAUSE, PLAY, FoxgloveClient

ROOT = Path(__file__).resolve().parents[3]
HOBBY = ROOT / "scenarios" / "hobby-rocket.yaml"
RATE = "telemetry: {rate: 50 Hz}\n"
WATCHDOG = 120.0        # s: a test that stalls longer has its server stopped (and fails)
PATIENCE = 30.0         # s: the longest wait for a server's answer (a shared machine can be slow)


@pytest.fixture
def coast(scenario):
    """coast(duration) -> the probe coasting for ``duration``, loaded."""
    return lambda duration: load(scenario(duration=duration, extra=RATE))


def headless(loaded, path: Path, duration: float | None = None) -> bytes:
    fly(loaded, path, duration=duration)
    return path.read_bytes()


def channels_of(path: Path) -> dict[str, tuple]:
    """topic -> (message encoding, schema name, schema text) of an MCAP file's channels."""
    summary = make_reader(open(path, "rb")).get_summary()
    return {c.topic: (c.message_encoding, summary.schemas[c.schema_id].name,
                      summary.schemas[c.schema_id].data.decode()) for c in summary.channels.values()}


def advertised(client: FoxgloveClient) -> dict[str, tuple]:
    return {c["topic"]: (c["encoding"], c["schemaName"], c["schema"]) for c in client.channels.values()}


def received(client: FoxgloveClient) -> list[tuple[str, int, bytes]]:
    return [(topic, log_time, data) for topic, log_time, data, _ in client.messages]


def watched(loaded, out: Path, warp, *, topics: set[str], script=None, on_progress=None):
    """Fly ``loaded`` live to ``out`` on an ephemeral loopback port, watched by a client that
    connects before anything flies: the flight starts paused, and the client resumes it
    once it is subscribed to every one of ``topics``; then ``script(client, server)`` runs
    on a thread of its own. Returns ``(client, server)``, the client closed."""
    found: dict = {}
    stop = threading.Event()

    def controls(client, server):
        try:
            assert client.wait_until(lambda c: topics <= {c_["topic"] for c_ in c.channels.values()}
                                     and server.subscriptions >= len(topics)), "channels not subscribed"
            client.set_parameters(paused=False)
            if script is not None:
                script(client, server)
        except BaseException as error:
            found["error"] = error
            server.resume()

    def ready(server):
        found["server"] = server
        threading.Thread(target=lambda: stop.wait(WATCHDOG) or server.stop(), daemon=True).start()
        client = found["client"] = FoxgloveClient(server.url, timeout=PATIENCE)
        found["thread"] = threading.Thread(target=controls, args=(client, server), daemon=True)
        found["thread"].start()

    try:
        fly_live(loaded, out, Live(warp=warp, port=0, paused=True, on_ready=ready), on_progress=on_progress)
    finally:
        stop.set()
        if "thread" in found:
            found["thread"].join(WATCHDOG)
        if "client" in found:       # what reached it before the server stopped, read to the close
            found["client"].wait_until(lambda c: c.closed)
            found["client"].close()
    if "error" in found:
        raise found["error"]
    return found["client"], found["server"]


def quiet(server) -> None:
    """An ``on_ready`` that says nothing."""


# --- the parts ---------------------------------------------------------------------


def test_parse_warp_takes_numbers_and_max_and_refuses_the_rest():
    assert parse_warp("10") == 10.0 and parse_warp("0.5x") == 0.5 and parse_warp(100) == 100.0
    assert parse_warp("max") is MAX and parse_warp(" MAX ") is MAX
    for bad in ("0", "-1", "fast", "inf", "nan", True, float("inf")):
        with pytest.raises(ValueError, match="positive number or 'max'"):
            parse_warp(bad)


def test_clock_runs_at_the_warp_stands_still_paused_and_changes_without_a_jump():
    wall = [100.0]
    clock = PlaybackClock(10.0, wall=lambda: wall[0])
    assert clock.now() is None and not clock.started
    clock.show(1_000_000_000)
    wall[0] = 100.5
    assert clock.now() == 1_000_000_000 + 5_000_000_000         # 0.5 s at 10x: 5 s
    clock.pause()
    wall[0] = 103.0
    assert clock.now() == 6_000_000_000 and clock.until() == 6_000_000_000
    clock.resume()
    wall[0] = 104.0
    assert clock.now() == 16_000_000_000
    clock.set_warp(2.0)
    wall[0] = 105.0
    assert clock.now() == 18_000_000_000
    clock.set_warp(MAX)
    assert clock.until() > 10 ** 18                              # every time is due
    clock.show(20_000_000_000)                                   # at max: the last served
    clock.set_warp(1.0)
    wall[0] = 106.0
    assert clock.now() == 21_000_000_000


def test_a_growing_file_gives_each_record_once_and_whole(coast, tmp_path):
    """The file copied in pieces of odd sizes, read after each: the messages come out once,
    in order, as the ``mcap`` package reads them from the whole file."""
    whole = tmp_path / "whole.mcap"
    data = headless(coast("5 s"), whole)
    growing_path = tmp_path / "growing.mcap"
    growing = GrowingMcap(growing_path)
    assert growing.next_record() is None                        # not there yet
    topics, messages = {}, []
    with open(growing_path, "wb") as out:
        at, piece = 0, 1
        while at < len(data):
            out.write(data[at:at + piece])
            out.flush()
            at += piece
            piece = piece * 7 % 9973 + 1
            while (record := growing.next_record()) is not None:
                if record.opcode == 4:
                    topics[record.parsed().id] = record.parsed().topic
                elif record.opcode == 6:
                    inner, _ = chunk_messages(record.parsed())
                    messages += [(topics[c], t, d) for c, t, d in inner]
    assert growing.ended
    growing.close()
    assert messages == raw_messages(whole)
    (tmp_path / "not.mcap").write_bytes(b"not an MCAP file at all")
    with pytest.raises(DamagedFile, match="not an MCAP file"):
        GrowingMcap(tmp_path / "not.mcap").next_record()


def test_a_growing_file_passes_over_the_records_not_wanted(coast, tmp_path):
    """Asked for chunks only, the reader gives the chunks of a reading of every record,
    none other, and ends at the Data End record all the same."""
    data = headless(coast("5 s"), tmp_path / "whole.mcap")
    every, chunks = GrowingMcap(tmp_path / "whole.mcap"), GrowingMcap(tmp_path / "whole.mcap")
    records = list(iter(every.next_record, None))
    assert {r.opcode for r in records} > {Opcode.CHUNK} and len(data) > 0
    assert list(iter(lambda: chunks.next_record({Opcode.CHUNK}), None)) == \
        [r for r in records if r.opcode == Opcode.CHUNK]
    assert every.ended and chunks.ended
    every.close(), chunks.close()


@pytest.mark.skipif(not Path("/proc/self/task").is_dir(), reason="threads' CPU read from Linux's /proc")
def test_the_views_cpu_is_its_own_thread_and_the_flights_the_other_threads():
    """The thread that made the count spins 0.05 s of CPU, another thread 0.1 s: the view
    is counted the first (and little else), the flight the second (and little else)."""

    def spin(seconds: float) -> None:
        end = time.thread_time() + seconds
        while time.thread_time() < end:
            pass

    spun, counted = threading.Event(), threading.Event()

    def flight() -> None:
        spin(0.1)
        spun.set()
        counted.wait(PATIENCE)          # alive while counted: an ended thread counts as the view's

    share = CpuShare()
    other = threading.Thread(target=flight)
    try:
        spin(0.05)
        other.start()
        assert spun.wait(PATIENCE)
        view, flight_cpu = share.spent()
    finally:
        counted.set()
        other.join()
        share.close()
    assert 0.05 <= view < 0.09 and 0.1 <= flight_cpu < 0.15


# --- flights -----------------------------------------------------------------------


@pytest.mark.parametrize("warp", [1.0, 10.0, 100.0, MAX], ids=["1x", "10x", "100x", "max"])
def test_the_file_is_the_headless_flights_at_every_warp_with_and_without_a_client(coast, tmp_path, warp):
    """A warp of 1 flies 3 s (3 s of wall time), the others 20 s."""
    duration = "3 s" if warp == 1.0 else "20 s"
    loaded = coast(duration)
    expected = headless(loaded, tmp_path / "headless.mcap")
    alone = []
    fly_live(loaded, tmp_path / "alone.mcap", Live(warp=warp, port=0, on_ready=alone.append))
    assert (tmp_path / "alone.mcap").read_bytes() == expected
    assert alone[0].delivered is None           # nobody to deliver to: the end is not waited for
    topics = set(channels_of(tmp_path / "headless.mcap"))
    client, server = watched(loaded, tmp_path / "watched.mcap", warp, topics=topics)
    assert (tmp_path / "watched.mcap").read_bytes() == expected
    assert advertised(client) == channels_of(tmp_path / "headless.mcap")
    assert server.delivered is True             # the server stopped once the client had the end
    file_messages = raw_messages(tmp_path / "watched.mcap")
    if warp is MAX:         # whole chunks as the player's share of a core allows, in order, the last
        got = iter(file_messages)
        assert client.messages and all(message in got for message in received(client))
        assert received(client)[-1] == file_messages[-1]
    else:
        assert received(client) == file_messages
        assert server.served == len(file_messages) and server.dropped_chunks == 0


def test_pause_stands_the_view_and_the_flight_still_then_nothing_is_lost(coast, tmp_path):
    """60 s at 10x, paused for 2 s once 5 s are shown: in those 2 s no message is served,
    the time shown stands, and the flight (its progress) stands too, short of its end."""
    loaded = coast("60 s")
    expected = headless(loaded, tmp_path / "headless.mcap")
    progress: list[float] = []
    seen: dict = {}

    def script(client, server):
        assert client.wait_until(lambda c: c.messages)
        start = client.messages[0][1]
        assert client.wait_until(lambda c: c.messages[-1][1] >= start + 5_000_000_000)
        client.set_parameters(paused=True)
        assert client.wait_until(lambda c: c.parameters.get("paused") is True)
        assert client.wait_until(lambda c: server.holding), \
            f"the flight does not wait while paused (flown to T+{progress[-1] if progress else 0:g} s of 60; " \
            f"the player's error: {server.error!r}; served {server.served}, stalls {server.stalls})"
        time.sleep(0.2)                 # what was on its way has arrived; the flight's batch ended
        seen["paused"] = (len(client.messages), client.messages[-1][1], client.times[-1][1], progress[-1])
        time.sleep(2.0)
        seen["still"] = (len(client.messages), client.messages[-1][1], client.times[-1][1], progress[-1])
        client.set_parameters(paused=False)

    client, server = watched(loaded, tmp_path / "live.mcap", 10.0,
                             topics=set(channels_of(tmp_path / "headless.mcap")),
                             script=script, on_progress=lambda t, phase: progress.append(t))
    assert seen["still"] == seen["paused"]
    assert seen["paused"][3] < 59.0                             # the flight waited, short of its end
    assert seen["paused"][1] < client.messages[-1][1]           # and the view went on after
    assert received(client) == raw_messages(tmp_path / "live.mcap")
    assert (tmp_path / "live.mcap").read_bytes() == expected


def test_the_warp_changes_from_the_viewer_by_parameter_and_by_foxglove_buttons(coast, tmp_path):
    """At 0.5x the 20 s flight would take 40 s: the viewer takes it to 40x (a parameter),
    pauses it and plays it at 80x with Foxglove's playback control; the watchdog would stop
    a view whose warp did not change, and the client would miss messages."""
    loaded = coast("20 s")
    expected = headless(loaded, tmp_path / "headless.mcap")
    acks = []

    def script(client, server):
        assert client.wait_until(lambda c: c.messages)
        client.set_parameters(warp="40")
        assert client.wait_until(lambda c: c.parameters.get("warp") == "40x")
        acks.append(client.parameters["warp"])
        client.playback(PAUSE, 40.0)
        assert client.wait_until(lambda c: c.parameters.get("paused") is True)
        acks.append(server.clock.paused)
        client.playback(PLAY, 80.0)
        assert client.wait_until(lambda c: c.parameters.get("paused") is False
                                 and c.parameters.get("warp") == "80x")
        acks.append(server.clock.warp)

    client, server = watched(loaded, tmp_path / "live.mcap", 0.5, topics=set(channels_of(tmp_path / "headless.mcap")),
                             script=script)
    assert acks == ["40x", True, 80.0]
    assert received(client) == raw_messages(tmp_path / "live.mcap")
    assert (tmp_path / "live.mcap").read_bytes() == expected


def test_a_client_that_stops_reading_loses_only_its_own_copy(coast, tmp_path):
    """A client subscribes and stops reading (64 KiB of socket buffer). Flying: the player
    serves every message, nothing waits for that client, the file is whole. Replaying the
    file, the server kept up: read at last, the client has a small part of the run, in
    order: the SDK keeps at most its backlog of messages for it (dropping the oldest), and
    the sockets' buffers hold some thousands more, whatever the length of the run."""
    loaded = coast("600 s")
    expected = headless(loaded, tmp_path / "headless.mcap")
    topics = set(channels_of(tmp_path / "headless.mcap"))
    stalled = []

    def subscribe_and_stop_reading(server):
        client = FoxgloveClient(server.url, reading=False, receive_buffer=64 * 1024, timeout=PATIENCE)
        stalled.append(client)

        def subscribe():
            try:
                client.read_until(lambda c: topics <= {c_["topic"] for c_ in c.channels.values()}
                                  and server.subscriptions >= len(topics))
            finally:
                server.resume()
        subscribing = threading.Thread(target=subscribe, daemon=True)
        subscribing.start()
        return subscribing

    try:
        fly_live(loaded, tmp_path / "live.mcap", Live(warp=1000.0, port=0, paused=True,
                                                       on_ready=subscribe_and_stop_reading))
        file_messages = raw_messages(tmp_path / "live.mcap")
        assert (tmp_path / "live.mcap").read_bytes() == expected
        assert len(file_messages) > 120_000
        with LiveServer(tmp_path / "live.mcap", warp=1000.0, paused=True, port=0) as server:
            server.play()
            subscribe_and_stop_reading(server).join(WATCHDOG)
            server.finish()
            assert server.wait(WATCHDOG)
            assert server.served == len(file_messages)
            stalled[-1].read_all(2.0)
    finally:
        for client in stalled:
            client.close()
    got = received(stalled[-1])
    assert BACKLOG <= len(got) < len(file_messages) // 4
    in_order = iter(file_messages)
    assert all(message in in_order for message in got)


def test_a_flight_in_memory_shown_live_is_the_same_run(tmp_path):
    import rocketsim
    alone = rocketsim.fly(HOBBY, duration=3)
    shown = rocketsim.fly(HOBBY, duration=3, live={"warp": "max", "port": 0, "on_ready": quiet})
    assert shown == alone and shown.path is None


def test_replay_live_serves_every_message_of_the_file(coast, tmp_path):
    path = tmp_path / "run.mcap"
    headless(coast("10 s"), path)
    topics = channels_of(path)
    clients = []

    def ready(server):              # before the server plays: subscribed, the client resumes it
        client = FoxgloveClient(server.url, timeout=PATIENCE)
        clients.append(client)

        def resume():
            try:
                assert client.wait_until(lambda c: server.subscriptions == len(topics))
            finally:
                client.set_parameters(paused=False)
        threading.Thread(target=resume, daemon=True).start()

    try:
        replay_live(path, Live(warp=100.0, port=0, paused=True, on_ready=ready))
    finally:
        for client in clients:
            client.close()
    assert received(clients[0]) == raw_messages(path)


# --- the command line ----------------------------------------------------------------


def rocketsim(*args):
    from rocketsim_cli.main import main
    return CliRunner().invoke(main, [str(a) for a in args], catch_exceptions=False)


def test_fly_live_writes_the_headless_file_and_the_options_are_checked(tmp_path):
    plain = rocketsim("fly", HOBBY, "--duration", "3s", "-o", tmp_path / "plain.mcap")
    shown = rocketsim("fly", HOBBY, "--duration", "3s", "-o", tmp_path / "live.mcap", "--live", "--warp", "max",
                      "--port", 0)
    assert plain.exit_code == shown.exit_code == 0, shown.output
    assert "live view: ws://127.0.0.1:" in shown.output
    assert (tmp_path / "live.mcap").read_bytes() == (tmp_path / "plain.mcap").read_bytes()
    alone = rocketsim("fly", HOBBY, "--warp", "10")
    assert alone.exit_code == 2 and "--warp go with --live" in alone.output
    bad = rocketsim("fly", HOBBY, "--live", "--warp", "fast")
    assert bad.exit_code == 2 and "a warp is a positive number or 'max', not 'fast'" in bad.output


def test_a_port_taken_is_refused_before_anything_is_written(tmp_path):
    import socket
    with socket.socket() as taken:
        taken.bind(("127.0.0.1", 0))
        taken.listen()
        port = taken.getsockname()[1]
        result = rocketsim("fly", HOBBY, "--duration", "1s", "-o", tmp_path / "x.mcap", "--live", "--port", port)
    assert result.exit_code == 2
    assert f"cannot serve the live view on 127.0.0.1:{port}" in result.output
    assert not (tmp_path / "x.mcap").exists()


def test_without_the_live_extra_one_line_says_how_to_install_it(tmp_path, monkeypatch):
    monkeypatch.setitem(sys.modules, "foxglove", None)          # import foxglove raises ImportError
    result = rocketsim("fly", HOBBY, "-o", tmp_path / "x.mcap", "--live")
    assert result.exit_code == 2
    assert result.output.strip().splitlines()[-1] == \
        'error: the live view needs Foxglove\'s SDK: pip install "rocketsim[live]"'
    assert not (tmp_path / "x.mcap").exists()
    with pytest.raises(InputError, match=r'rocketsim\[live\]'):
        replay_live(tmp_path / "x.mcap", Live())


def test_replay_live_plays_a_file_and_refuses_one_that_is_not_a_run(coast, tmp_path):
    path = tmp_path / "run.mcap"
    headless(coast("2 s"), path)
    shown = rocketsim("replay", path, "--live", "--warp", "max", "--port", 0)
    assert shown.exit_code == 0, shown.output
    assert "live view: ws://127.0.0.1:" in shown.output
    (tmp_path / "not.mcap").write_text("hello")
    with pytest.raises(InputError, match="nothing in it can be played"):
        replay_live(tmp_path / "not.mcap", Live(port=0, on_ready=quiet))
