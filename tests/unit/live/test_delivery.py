"""Whether the SDK has delivered its messages: a server stopped once it has loses none.

A Foxglove SDK server on an ephemeral loopback port serves one channel to a
real client (tests/live_client.py) that subscribes with 64 KiB of socket
buffer and does not read. Messages of 4 KiB, twice what the sockets may
buffer (8 MB with Linux's defaults), fill the sockets' buffers, and the rest
waits in the SDK's queue for that client (its backlog holds them all: none is
dropped for being late). Stopped at once, the server drops what
it has not sent: reading at last, the client lacks messages, so the check
of the delivered case can fail. Waited for while the client does not read,
:func:`~rocketsim.live.delivery.wait_delivered` ends at its bound, unsuccessful;
once the client reads, it ends successful, and the server stopped then has
given the client every message. Every server is stopped, every wait bounded.
"""

from __future__ import annotations

import sys
import threading

import pytest

from rocketsim.live.delivery import unacknowledged, wait_delivered
from tests.live_client import FoxgloveClient

foxglove = pytest.importorskip("foxglove")
pytestmark = pytest.mark.skipif(not sys.platform.startswith("linux"),
                                reason="delivery is seen in Linux's /proc and socket queues")

PATIENCE = 30.0                 # s: the longest wait for the server or the client
SIZE = 4096                     # bytes of a message


def _count() -> int:
    """Messages enough to fill a loopback connection's buffers twice over: the most the
    server's socket may buffer (Linux's tcp_wmem, 4 MiB by default) over SIZE, times 2."""
    with open("/proc/sys/net/ipv4/tcp_wmem") as wmem:
        return max(2000, 2 * int(wmem.read().split()[2]) // SIZE)


class _Subscribed(foxglove.ServerListener):
    def __init__(self):
        self.done = threading.Event()

    def on_subscribe(self, client, channel) -> None:
        self.done.set()


@pytest.fixture
def not_reading():
    """``(server, client, count)``: ``count`` messages logged to a client subscribed on the
    loopback address that has read none; the client closed and the server stopped after."""
    count = _count()
    context, listener = foxglove.Context(), _Subscribed()
    server = foxglove.start_server(host="127.0.0.1", port=0, context=context, server_listener=listener,
                                   message_backlog_size=count + 100)
    client = None
    try:
        channel = foxglove.Channel("/bulk", message_encoding="json", context=context)
        client = FoxgloveClient(f"ws://127.0.0.1:{server.port}", reading=False, receive_buffer=64 * 1024,
                                timeout=PATIENCE)
        assert client.read_until(lambda c: listener.done.is_set()), "the client did not subscribe"
        pad = b"x" * (SIZE - 32)
        for number in range(count):
            channel.log(b'{"n": %d, "pad": "%s"}' % (number, pad), log_time=number)
        yield server, client, count
    finally:
        if client is not None:
            client.close()          # first: the server's stop waits for the connection to close
        server.stop()


def stop_and_read(server, client, reading: threading.Thread | None = None) -> list[int]:
    """Stop ``server`` (on a thread: the SDK's stop waits for the client to take its
    closing frame), read what reaches ``client`` until the connection closes (after
    ``reading``, a thread reading it, if any, has ended); the log times received."""
    stopping = threading.Thread(target=server.stop, daemon=True)
    stopping.start()
    try:
        if reading is not None:
            reading.join(PATIENCE)
        client.read_all(PATIENCE)
    finally:
        stopping.join(PATIENCE)
        client.close()
    return [log_time for _, log_time, _, _ in client.messages]


def test_a_server_stopped_at_once_drops_what_it_has_not_sent(not_reading):
    server, client, count = not_reading
    assert unacknowledged(server.port) > 0          # the client's buffers are full
    got = stop_and_read(server, client)
    assert 0 < len(got) < count and got == list(range(len(got)))


def test_stopped_once_delivered_the_server_has_given_the_client_every_message(not_reading):
    server, client, count = not_reading
    reading = threading.Thread(target=client.read_until, args=(lambda c: len(c.messages) == count, PATIENCE),
                               daemon=True)
    assert wait_delivered(server.port, 0.2) is False        # the client does not read
    reading.start()
    assert wait_delivered(server.port, PATIENCE) is True
    assert stop_and_read(server, client, reading) == list(range(count))


def test_nothing_is_unacknowledged_on_a_port_without_connections():
    server = foxglove.start_server(host="127.0.0.1", port=0, context=foxglove.Context())
    try:
        assert unacknowledged(server.port) == 0
        assert wait_delivered(server.port, PATIENCE) is True
    finally:
        server.stop()
