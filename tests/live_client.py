"""A client of the Foxglove WebSocket protocol for the live view's tests.

The WebSocket itself is the ``websockets`` library's (its synchronous client:
handshake, framing, pings); this module speaks the protocol's messages over it,
as the Foxglove app does: it reads the server's info, channels (``advertise``),
parameter values and time; subscribes to channels; receives their messages
(binary opcode 1: subscription id, log time, payload); sets parameters and sends
playback control requests (binary opcode 3, as the app's play, pause and speed
buttons do). Every wait has a timeout.
"""

from __future__ import annotations

import contextlib
import json
import socket
import struct
import threading
import time

from websockets.exceptions import ConnectionClosed
from websockets.sync.client import connect
from websockets.typing import Subprotocol

# what the Foxglove app offers: the SDK's server speaks the first, older servers the second
SUBPROTOCOLS = [Subprotocol("foxglove.sdk.v1"), Subprotocol("foxglove.websocket.v1")]
MESSAGE_DATA, TIME = 0x01, 0x02                 # server binary opcodes
PLAYBACK_CONTROL = 0x03                         # client binary opcode
PLAY, PAUSE = 0, 1


class FoxgloveClient:
    """A connection to ``url``; with ``subscribe`` every channel advertised is subscribed
    to at once, as are the parameters' updates. A thread reads what the server sends
    unless ``reading`` is False: then only :meth:`read_until` and :meth:`read_all` read
    (a client that stops reading; ``receive_buffer`` bytes of socket buffer, if given)."""

    def __init__(self, url: str, *, subscribe: bool = True, reading: bool = True,
                 receive_buffer: int | None = None, timeout: float = 10.0):
        sock = None
        if receive_buffer is not None:
            host, port = url.removeprefix("ws://").rsplit(":", 1)
            sock = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
            sock.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, receive_buffer)
            sock.settimeout(timeout)
            sock.connect((host, int(port)))
        self._stack = contextlib.ExitStack()
        self.ws = self._stack.enter_context(connect(url, sock=sock, subprotocols=SUBPROTOCOLS,
                                                    open_timeout=timeout, close_timeout=1.0,
                                                    ping_interval=None, proxy=None, max_size=None,
                                                    compression=None))
        self.timeout = timeout
        self.info: dict | None = None
        self.channels: dict[int, dict] = {}             # server channel id -> its advertisement
        self.subscriptions: dict[int, int] = {}         # subscription id -> channel id
        self.messages: list[tuple[str, int, bytes, float]] = []    # topic, log time, payload, wall s
        self.times: list[tuple[float, int]] = []        # (wall s, server time ns)
        self.parameters: dict[str, object] = {}
        self.statuses: list[dict] = []
        self._subscribe = subscribe
        self._changed = threading.Condition()
        self._closed = False
        self._reader = None
        if reading:
            self._reader = threading.Thread(target=self._read, daemon=True)
            self._reader.start()

    # --- reading -----------------------------------------------------------------
    def _read(self) -> None:
        try:
            while not self._closed:
                self._handle(self.ws.recv())
        except Exception:           # the server closed the connection, or we did
            pass
        finally:
            with self._changed:
                self._closed = True
                self._changed.notify_all()

    def _handle(self, frame) -> None:
        with self._changed:
            if isinstance(frame, bytes):
                if frame[0] == MESSAGE_DATA:
                    subscription, log_time = struct.unpack_from("<IQ", frame, 1)
                    topic = self.channels[self.subscriptions[subscription]]["topic"]
                    self.messages.append((topic, log_time, frame[13:], time.monotonic()))
                elif frame[0] == TIME:
                    self.times.append((time.monotonic(), struct.unpack_from("<Q", frame, 1)[0]))
            else:
                message = json.loads(frame)
                op = message["op"]
                if op == "serverInfo":
                    self.info = message
                    if self._subscribe and "parametersSubscribe" in message["capabilities"]:
                        self.ws.send(json.dumps({"op": "subscribeParameterUpdates",
                                                 "parameterNames": ["warp", "paused"]}))
                elif op == "advertise":
                    fresh = {c["id"]: c for c in message["channels"]}
                    self.channels.update(fresh)
                    if self._subscribe:
                        self._subscribe_to(list(fresh))
                elif op == "parameterValues":
                    self.parameters.update({p["name"]: p.get("value") for p in message["parameters"]})
                elif op == "status":
                    self.statuses.append(message)
                    unknown = message["message"].removeprefix("Unknown channel ID: ")
                    if self._subscribe and unknown != message["message"] and int(unknown) in self.channels:
                        self._resubscribe(int(unknown))
            self._changed.notify_all()

    def _subscribe_to(self, channel_ids: list[int]) -> None:
        subscriptions = []
        for channel in channel_ids:
            subscription = max(self.subscriptions, default=0) + 1
            self.subscriptions[subscription] = channel
            subscriptions.append({"id": subscription, "channelId": channel})
        self.ws.send(json.dumps({"op": "subscribe", "subscriptions": subscriptions}))

    def _resubscribe(self, channel: int) -> None:
        """Subscribe again to ``channel``, which the server advertised but did not know yet.

        foxglove-sdk 0.30 sends a channel's advertisement before it records the channel
        as advertised to that client (websocket/connected_client.rs, advertise_channels):
        a client that answers within that instant is told the channel is unknown."""
        for subscription, subscribed in list(self.subscriptions.items()):
            if subscribed == channel:
                del self.subscriptions[subscription]
        self._subscribe_to([channel])

    def wait_until(self, condition, timeout: float | None = None) -> bool:
        """Wait until ``condition(self)`` holds (True) or ``timeout`` s (the client's)."""
        deadline = time.monotonic() + (self.timeout if timeout is None else timeout)
        with self._changed:
            while not condition(self):
                left = deadline - time.monotonic()
                if left <= 0 or self._closed:
                    return condition(self)
                self._changed.wait(min(left, 0.05))
            return True

    @property
    def closed(self) -> bool:
        return self._closed

    # --- sending -------------------------------------------------------------------
    def set_parameters(self, **values) -> None:
        self.ws.send(json.dumps({"op": "setParameters", "id": "set",
                                 "parameters": [{"name": k, "value": v} for k, v in values.items()]}))

    def get_parameters(self) -> None:
        self.ws.send(json.dumps({"op": "getParameters", "id": "get", "parameterNames": []}))

    def playback(self, command: int, speed: float, request_id: str = "request") -> None:
        """A playback control request, as Foxglove's play and pause buttons send it."""
        name = request_id.encode()
        self.ws.send(struct.pack("<BBfBQI", PLAYBACK_CONTROL, command, speed, 0, 0, len(name)) + name)

    def read_until(self, condition, timeout: float | None = None) -> bool:
        """Read on this thread until ``condition(self)`` holds (True) or ``timeout`` s."""
        deadline = time.monotonic() + (self.timeout if timeout is None else timeout)
        while not condition(self):
            left = deadline - time.monotonic()
            if left <= 0:
                return False
            try:
                self._handle(self.ws.recv(timeout=min(left, 0.05)))
            except TimeoutError:
                continue
            except ConnectionClosed:
                return condition(self)
        return True

    def read_all(self, timeout: float) -> None:
        """Read what the server sends for ``timeout`` s, on this thread."""
        self.read_until(lambda c: False, timeout)

    def close(self) -> None:
        self._closed = True
        self._stack.close()
        if self._reader is not None:
            self._reader.join(self.timeout)


def watch_servers(url: str, stop, reports, timeout: float = 60.0) -> None:
    """Watch the servers that come and go at ``url`` (run in a process of its own, as a
    Foxglove app is): connect as soon as one listens, subscribe to everything, read until
    it closes, and put ``(messages, [(arrival (time.monotonic s), log time (ns)), ...])``
    on ``reports`` (every tenth message's); again, until ``stop`` is set."""
    while not stop.is_set():
        try:
            client = FoxgloveClient(url, timeout=timeout)
        except Exception:           # no server there yet, or one stopping as it was reached
            time.sleep(0.005)
            continue
        client.wait_until(lambda c: c.closed, timeout=3600)
        client.close()
        if client.messages:
            reports.put((len(client.messages), [(wall, t) for _, t, _, wall in client.messages[::10]]))
