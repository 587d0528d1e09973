"""Whether Foxglove's SDK has delivered to the viewers every message it was given.

The SDK (``foxglove-sdk``) queues each viewer's messages and sends them on
threads of its own (the tokio workers of its Rust core); stopping its server
drops what they have not sent. Neither the SDK nor the Foxglove WebSocket
protocol says when a viewer has a message: nothing the server sends is
acknowledged, the SDK tells neither the length of a viewer's queue nor
flushes it on stop, and a viewer's requests (parameters, services) come when
the viewer wants, not after a message. What can be seen is what lies beneath,
on Linux:

* the process's threads that are not Python's (the SDK's): a viewer's queue
  holding a message while its connection takes more keeps one of them running
  or runnable (state ``R`` in ``/proc/self/task/<id>/stat``, CPU time growing
  in ``.../schedstat``);
* the server's connections (this process's TCP sockets on the server's port
  that have a peer): the bytes each has sent or holds to send that the
  viewer's side has not acknowledged (the socket's ``SIOCOUTQ``). Acknowledged
  bytes are on the viewer's machine, which reads them before the closing frame
  that a stop sends after them.

Everything is delivered when two looks :data:`LOOK` seconds apart find every
such thread asleep and none of them run in between (a Python callback the SDK
waits on to take the interpreter's lock runs in between), and no byte
unacknowledged. Where ``/proc`` cannot be read, nothing is seen:
:func:`wait_delivered` then waits :data:`UNSEEN` seconds.
"""

from __future__ import annotations

from __future__ import annotations

import os
import socket
import struct
import sys
import threading
import time

if sys.platform.startswith("linux"):
    from fcntl import ioctl
    from termios import TIOCOUTQ        # SIOCOUTQ for a socket: bytes its peer has not acknowledged
else:                                   # nothing of this is seen
    ioctl = TIOCOUTQ = None

# s between two looks at the SDK's threads and connections
LOOK = 0.002
# s waited where nothing can be seen (no /proc): what the SDK takes to send a chunk's
# messages on a loaded machine
UNSEEN = 0.5


def _sdk_threads() -> dict[int, tuple[str, int]] | None:
    """Native id -> (state, CPU ns) of this process's threads that are not Python's
    (None: not readable)."""
    python = {thread.native_id for thread in threading.enumerate()}
    found = {}
    try:
        for name in os.listdir("/proc/self/task"):
            native_id = int(name)
            if native_id in python:
                continue
            try:
                with open(f"/proc/self/task/{name}/stat") as stat:
                    state = stat.read().rsplit(")", 1)[1].split()[0]
                with open(f"/proc/self/task/{name}/schedstat") as schedstat:
                    cpu = int(schedstat.read().split()[0])
            except FileNotFoundError:       # the thread ended meanwhile
                continue
            found[native_id] = (state, cpu)
    except (OSError, ValueError, IndexError):
        return None
    return found


def unacknowledged(port: int) -> int | None:
    """Bytes the TCP connections this process has on its ``port`` (those it accepted there)
    have sent or hold to send that their peers have not acknowledged (Linux's
    ``SIOCOUTQ``, asked of a duplicate of each socket's descriptor; None: not readable)."""
    if ioctl is None:
        return None
    try:
        descriptors = os.listdir("/proc/self/fd")
    except OSError:
        return None
    pending = 0
    for name in descriptors:
        try:
            if not os.readlink(f"/proc/self/fd/{name}").startswith("socket:"):
                continue
            duplicate = os.dup(int(name))
            try:
                connection = socket.socket(fileno=duplicate)
            except OSError:
                os.close(duplicate)
                raise
            with connection:
                if connection.family not in (socket.AF_INET, socket.AF_INET6) \
                        or connection.type != socket.SOCK_STREAM or connection.getsockname()[1] != port:
                    continue
                connection.getpeername()            # the listening socket has none: OSError
                queued = ioctl(connection.fileno(), TIOCOUTQ, bytes(4))
                pending += struct.unpack("i", queued)[0]
        except OSError:                             # closed meanwhile, or not a connection
            continue
    return pending


def wait_delivered(port: int, longest: float) -> bool:
    """Wait until the SDK's server on ``port`` has delivered every message it was given
    (True), or ``longest`` s (False: a viewer that does not read, or nothing to see)."""
    deadline = time.monotonic() + longest
    before = None
    while True:
        threads, pending = _sdk_threads(), unacknowledged(port)
        if threads is None or pending is None:
            time.sleep(max(0.0, min(UNSEEN, deadline - time.monotonic())))
            return False
        if pending == 0 and before == threads and all(state != "R" for state, _ in threads.values()):
            return True
        if time.monotonic() + LOOK > deadline:
            return False
        before = threads
        time.sleep(LOOK)
