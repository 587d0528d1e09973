"""A Foxglove WebSocket server playing a run's MCAP file as it is written, at a warp.

:class:`LiveServer` serves the Foxglove WebSocket protocol with Foxglove's own
SDK (``foxglove-sdk``): every channel of the file is advertised with its topic,
message encoding and schema as the file registers them, and every message is
served with its log time, in the file's order. A player thread follows the file
(:class:`rocketsim.live.growing.GrowingMcap`) a chunk at a time and serves each
message when the clock (:class:`rocketsim.live.clock.PlaybackClock`) reaches
its log time, telling the viewers the time shown (the protocol's ``time``).

The viewers pause, resume and change the warp (the protocol's parameters
``warp`` and ``paused``, and Foxglove's playback control:
:mod:`rocketsim.live.viewers`). Once the player has ended, :meth:`LiveServer.wait`
waits for the viewers' connections to have the last messages
(:mod:`rocketsim.live.delivery`), which stopping the server would drop.

Memory and the flight's lead are bounded: the player holds at most
:data:`AHEAD` chunks read ahead of the one it plays (the rest waits on disk),
and a flight at a finite warp, or paused, waits after a batch of steps while
it leads the view by more than :meth:`LiveServer.longest_lead`
(:meth:`LiveServer.keep_pace`): it waits, and never changes a step. At ``max``
nothing waits for the player: it serves whole chunks, the newest first, and
spends at most :data:`MAX_SHARE` of the flight's CPU time on them (its own
thread's and the SDK's, :mod:`rocketsim.live.cpu_share`), leaving out of the
live copy (never the file) the chunks it has no CPU for; the flight's last
chunk is always served. A client that reads
slower than it is served loses the oldest of its messages beyond the SDK's
per-client backlog (:data:`BACKLOG` messages), the flight and the other
clients going on: only the live copy is dropped, and the memory held for each
client is bounded.
"""

from __future__ import annotations

import os
import threading
import time
from collections import deque
from pathlib import Path

import foxglove
from foxglove.websocket import Capability
from mcap.opcode import Opcode

from rocketsim.live.cpu_share import CpuShare
from rocketsim.live.clock import MAX, PlaybackClock
from rocketsim.live.delivery import wait_delivered
from rocketsim.live.growing import GrowingMcap, Record, chunk_messages, chunk_times, message_of
from rocketsim.live.viewers import ViewerRequests, parameters, playback_state

# chunks read ahead of the one being played, at most (the rest waits on disk): 256 KiB of
# records each, uncompressed, some 12 s of a 10 Hz single body
AHEAD = 2
# the flight leads the view by at most this many of the file's longest chunks, or this many
# seconds of wall time at the warp, whichever is more: the view plays on while the flight's
# next chunk is flown and written, and a flight paused waits that far ahead
LEAD_CHUNKS = 2
LEAD_WALL = 1.0
# longest single wait of a flight for its view (s) before it looks again
WAIT = 0.1
# longest wait of the player between two looks at the file (s)
POLL = 0.02
# how often the viewers are told the time shown (s of wall time)
TIME_EVERY = 0.05
# at max warp, the CPU the view may spend (its player's thread and the SDK's) as a share of
# the flight's (rocketsim.live.cpu_share)
MAX_SHARE = 0.05
# s the server waits at most after the end for the last messages to reach the viewers
# (rocketsim.live.delivery): a viewer that has not taken them by then is not reading
DELIVERY_WAIT = 1.0
# s a stop waits for the clients' connections to close
STOP_WAIT = 2.0
# messages queued for a client that reads slower than it is served (the SDK drops the oldest):
# some 4 MB of JSON, 200 s of a single body's 10 Hz telemetry (four messages a sample)
BACKLOG = 8192

_CORES = os.cpu_count() or 1
# the records the player reads (the file's indexes are passed over)
_PLAYED = frozenset((Opcode.SCHEMA, Opcode.CHANNEL, Opcode.CHUNK, Opcode.MESSAGE))


class LiveServer:
    """A Foxglove WebSocket server on ``host``:``port`` (0: any free port) playing the
    MCAP file ``path`` as it is written, at warp ``warp`` (None: max), from the start or
    ``paused``.

    ``time_range`` (ns, ns): the telemetry times the run spans at most, which lets
    Foxglove's play/pause and speed buttons drive the clock. Call :meth:`play` once the
    file is there (created: not a file of the same name before it), :meth:`finish` once
    it is complete (at once for a file already written), :meth:`wait` for the playing to
    end, and :meth:`stop` always (a context manager does)."""

    def __init__(self, path: str | Path, *, warp: float | None = 1.0, paused: bool = False, host: str = "127.0.0.1",
                 port: int = 8765, name: str = "rocketsim", time_range: tuple[int, int] | None = None):
        self.clock = PlaybackClock(warp, paused)
        self._file = GrowingMcap(path)
        self._context = foxglove.Context()
        self._schemas: dict[int, object] = {}           # MCAP schema id -> foxglove.Schema
        self._ahead: deque = deque()                    # chunk records read ahead
        self._complete = threading.Event()              # the file will not grow
        self._done = threading.Event()                  # the player has ended
        self._room = threading.Condition()              # notified as the view moves on
        self._between = True                            # the player has played its chunk out
        self._reading = threading.Lock()                # the file is read by one thread at a time
        self.holding = False                            # a flight waits for the view
        self.subscriptions = 0                          # (viewer, channel) pairs subscribed
        self._first: int | None = None                  # log time of the first chunk's start
        self._span = 0                                  # longest chunk read, ns of log time
        self._stopping = False
        self.error: BaseException | None = None         # what ended the player early
        self.served = 0                                 # messages served
        self.dropped_chunks = 0                         # chunks left out of the live copy at max
        self.cpu: tuple[float, float] | None = None     # at max: CPU s of the view and the flight, last counted
        self.stalls = 0                                 # times the player ran out of telemetry
        self.delivered: bool | None = None              # the viewers had the end (None: none to wait for)
        self.first_played: tuple[float, int] | None = None     # (wall s, log time ns), served or not
        self.last_played: tuple[float, int] | None = None
        self._shown_at = 0.0
        self._next_look = 0.0                           # at max: when to ask for CPU again (monotonic s)
        self._log: dict[int, object] = {}               # MCAP channel id -> its foxglove channel's log
        self._server = foxglove.start_server(
            name=name, host=host, port=port, context=self._context,
            capabilities=[Capability.Parameters, Capability.Time],
            server_listener=ViewerRequests(self), playback_time_range=time_range,
            message_backlog_size=BACKLOG)
        self._ranged = time_range is not None           # Foxglove's playback control is on
        self.port = self._server.port
        self.host = host
        self._player = threading.Thread(target=self._play, name=f"live view {Path(path).name}", daemon=True)

    # --- what the flight and the front door ask -------------------------------
    @property
    def url(self) -> str:
        """The WebSocket address a Foxglove app connects to."""
        host = f"[{self.host}]" if ":" in self.host else self.host
        return f"ws://{host}:{self.port}"

    def lead(self, flight_ns: int) -> int | None:
        """How far (ns) a flight that has written its telemetry up to ``flight_ns`` leads
        the view (None: the view has nothing to show yet)."""
        shown = self.clock.now() if self.clock.started else self._first
        return None if shown is None else flight_ns - shown

    def ahead_of_view(self, flight_ns: int) -> bool:
        """Whether a flight that has written its telemetry up to ``flight_ns`` (log time) is
        to wait for the view: it leads it by more than :meth:`longest_lead`, at a finite
        warp or paused, and the player has telemetry to play (waiting for the flight's
        next chunk, it has not: the flight goes on, whatever its lead)."""
        if not self._player.is_alive() or self.clock.warp is MAX and not self.clock.paused:
            return False
        self._read_ahead()              # what the flight wrote since the player last looked
        if self._between and not self._ahead:
            return False
        lead = self.lead(flight_ns)
        return lead is not None and lead > self.longest_lead()

    def longest_lead(self) -> int:
        """The lead (ns) a flight may keep over the view: :data:`LEAD_CHUNKS` of the file's
        longest chunk so far (what the view plays while the flight's next chunk is written)
        and :data:`LEAD_WALL` seconds of wall time at the warp."""
        warp = self.clock.warp or 0.0
        return max(LEAD_CHUNKS * self._span, round(LEAD_WALL * warp * 1e9))

    def keep_pace(self, flight_ns: int) -> None:
        """Wait while a flight that has written its telemetry up to ``flight_ns`` is
        :meth:`ahead_of_view` (:attr:`holding` meanwhile; Ctrl-C reaches the flight)."""
        try:
            while self.ahead_of_view(flight_ns) and not self._stopping:
                self.holding = True
                with self._room:
                    self._room.wait(WAIT)
        finally:
            self.holding = False

    def play(self) -> None:
        """Begin playing the file."""
        self._player.start()

    def finish(self) -> None:
        """The file is complete: play it to its end."""
        self._complete.set()
        self.clock.changed()

    def wait(self, longest: float | None = None) -> bool:
        """Wait for the player to end and, if a viewer is subscribed, for the last messages
        to reach it (:func:`~rocketsim.live.delivery.wait_delivered`, at most
        :data:`DELIVERY_WAIT` s) (True), or ``longest`` seconds (False); Ctrl-C reaches
        the caller meanwhile."""
        if self._player.is_alive() and not self._done.wait(longest):
            return False
        if self._listened():
            self.delivered = wait_delivered(self.port, DELIVERY_WAIT)
        return True

    def stop(self) -> None:
        """Stop the player and the server (again: nothing)."""
        if self._stopping:
            return
        self._stopping = True
        self._complete.set()
        self.clock.changed()
        if self._player.is_alive():
            self._player.join(5.0)
        # the SDK's stop waits for every client's connection to close, which a client that
        # stopped reading never lets happen: it is left to end with that client (or the process)
        stopping = threading.Thread(target=self._server.stop, name="live view stop", daemon=True)
        stopping.start()
        stopping.join(STOP_WAIT)
        self._file.close()

    def __enter__(self) -> "LiveServer":
        return self

    def __exit__(self, *exc) -> None:
        self.stop()

    # --- the controls ------------------------------------------------------------
    def set_warp(self, warp: float | None) -> None:
        self.clock.set_warp(warp)
        self._announce()

    def pause(self) -> None:
        self.clock.pause()
        self._announce()

    def resume(self) -> None:
        self.clock.resume()
        self._announce()

    def tell(self, message: str, level) -> None:
        """Show the viewers a status ``message`` (a ``foxglove.StatusLevel``)."""
        self._server.publish_status(message, level)

    def _announce(self) -> None:
        """Tell the viewers the controls' values, and wake a flight waiting for room."""
        self._server.publish_parameter_values(parameters(self.clock))
        if self._ranged:
            self._server.broadcast_playback_state(playback_state(self.clock))
        with self._room:
            self._room.notify_all()

    # --- the player ----------------------------------------------------------------
    def _play(self) -> None:
        share = CpuShare()                  # at max: the view's CPU against the flight's
        try:
            self._play_file(share)
        except BaseException as error:      # the live copy ends; the flight and its file go on
            self.error = error
            try:
                self.tell(f"the live view stopped: {error}", foxglove.StatusLevel.Error)
            except Exception:
                pass
        finally:
            share.close()
            self._done.set()
            with self._room:
                self._room.notify_all()

    def _play_file(self, share: CpuShare) -> None:
        chunk, messages, at = None, [], 0   # the chunk being played, its messages, the next one
        last = None                         # log time of the last message played (served or not)
        waited = False                      # the player ran out of telemetry before the file's end
        while not self._stopping:
            complete = self._complete.is_set()      # before reading: all of the file is read after
            paused = self.clock.paused
            at_max = self.clock.warp is MAX and not paused
            self._between = at == len(messages)
            if at_max and self._between and not complete and time.monotonic() < self._next_look:
                self._complete.wait(POLL)           # resting until the flight has earned the view's CPU
                continue
            self._read_ahead()
            if self._between and not self._ahead:
                with self._room:
                    self._room.notify_all()     # a flight waiting goes on, to write what is to play
            if at == len(messages):
                if self._ahead and not paused and not (at_max and not self._may_serve(share, complete)):
                    chunk, messages, at = *self._take(at_max), 0
                    if waited and last is not None:
                        self.clock.show(last)       # take up where the view stopped
                        self.stalls += 1
                    waited = False
                    continue
                if complete and not self._ahead:
                    break
                waited = waited or not self._ahead
                self._complete.wait(POLL)
                continue
            if messages[at][0] is None and chunk is not None and self._listened():
                messages, at = self._messages(chunk, last)      # a viewer came while it played unread
                continue
            if not self.clock.started:
                self.clock.show(messages[at][1])
            until = self.clock.until()
            log = self._log
            while at < len(messages) and messages[at][1] <= until:
                channel, log_time, data = messages[at]
                if channel is not None:
                    log[channel](data, log_time, None)
                    self.served += 1
                last = log_time
                at += 1
            if last is not None:
                self.last_played = (time.monotonic(), last)
                self.first_played = self.first_played or self.last_played
            self._tell_time(last)
            with self._room:
                self._room.notify_all()
            if at < len(messages):
                self.clock.wait_for(messages[at][1], POLL)
            elif at_max:
                self.clock.show(last)
        if last is not None:
            self._server.broadcast_time(last)
        if self._ranged:
            self._server.broadcast_playback_state(playback_state(self.clock, ended=True))

    def _may_serve(self, share: CpuShare, complete: bool) -> bool:
        """At max: whether the view may play another chunk, having spent at most
        :data:`MAX_SHARE` of the flight's CPU (:class:`~rocketsim.live.cpu_share.CpuShare`),
        or the flight has ended (its last chunk is played, the view ending on it). If not,
        the player rests until the flight can have earned the CPU it lacks, running on
        every core (:attr:`_next_look`)."""
        if complete:
            return True
        view, flight = self.cpu = share.spent()
        lacking = view / MAX_SHARE - flight        # flight CPU (s) that earns the view's CPU
        if lacking <= 0:
            return True
        self._next_look = time.monotonic() + max(POLL, lacking / _CORES)
        return False

    def _read_ahead(self) -> None:
        """Read the file's new whole records: channels are advertised at once, chunks
        (and messages outside chunks) queued, up to :data:`AHEAD` (at max, the oldest
        left out to make room)."""
        with self._reading:
            self._read_records()

    def _read_records(self) -> None:
        while len(self._ahead) < AHEAD or self.clock.warp is MAX and not self.clock.paused:
            record = self._file.next_record(_PLAYED)
            if record is None:
                return
            if record.opcode in (Opcode.SCHEMA, Opcode.CHANNEL):
                self._register(record)
            elif record.opcode in (Opcode.CHUNK, Opcode.MESSAGE):
                if record.opcode == Opcode.CHUNK:
                    start, end = chunk_times(record)
                    self._first = start if self._first is None else self._first
                    self._span = max(self._span, end - start)
                if len(self._ahead) >= AHEAD:
                    self._ahead.popleft()
                    self.dropped_chunks += 1
                self._ahead.append(record)

    def _take(self, at_max: bool) -> tuple:
        """``(chunk, messages)``: the next chunk to play (at max, the newest, those before it
        left out) and its messages, ``(channel id, log time, data)`` (:meth:`_messages`);
        a message outside any chunk is a chunk of its own (None)."""
        with self._reading:
            if at_max:
                record = self._ahead.pop()
                self.dropped_chunks += len(self._ahead)
                self._ahead.clear()
            else:
                record = self._ahead.popleft()
        with self._room:
            self._room.notify_all()
        if record.opcode == Opcode.MESSAGE:
            return None, [message_of(record)]
        chunk = record.parsed()
        return chunk, self._messages(chunk, None)[0]

    def _messages(self, chunk, after: int | None) -> tuple[list[tuple], int]:
        """``(messages, first)``: a chunk's messages and the first not earlier than ``after``
        (log time: a viewer that comes while a chunk plays unread gets the instant shown);
        while nobody listens, only its first and last times (``(None, time, None)``), played
        by the clock unread."""
        if not self._listened():
            return [(None, chunk.message_start_time, None), (None, chunk.message_end_time, None)], 0
        messages, records = chunk_messages(chunk)
        for inner in records:
            self._register(inner)
        first = 0
        if after is not None:
            while first < len(messages) and messages[first][1] < after:
                first += 1
        return messages, first

    def _listened(self) -> bool:
        """Whether a viewer is subscribed to any channel."""
        return self.subscriptions > 0

    def _register(self, record: Record) -> None:
        """Advertise an MCAP channel (its schema kept until then)."""
        parsed = record.parsed()
        if record.opcode == Opcode.SCHEMA:
            self._schemas[parsed.id] = foxglove.Schema(name=parsed.name, encoding=parsed.encoding,
                                                             data=parsed.data)
        elif parsed.id not in self._log:
            channel = foxglove.Channel(
                parsed.topic, schema=self._schemas.get(parsed.schema_id),
                message_encoding=parsed.message_encoding, metadata=dict(parsed.metadata) or None,
                context=self._context)
            self._log[parsed.id] = channel.base.log

    def _tell_time(self, shown: int | None) -> None:
        now = time.monotonic()
        if shown is not None and now - self._shown_at >= TIME_EVERY:
            self._server.broadcast_time(shown)
            self._shown_at = now
