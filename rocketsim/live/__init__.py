"""The live view: a run's MCAP file served to Foxglove as it is written, at a warp.

The front door is :mod:`rocketsim.api.live` (``rocketsim fly --live``,
``rocketsim.fly(..., live=True)``); here are its parts: the file read as it
grows (:mod:`~rocketsim.live.growing`), the clock of the warp
(:mod:`~rocketsim.live.clock`), the Foxglove WebSocket server and its player
(:mod:`~rocketsim.live.server`), the viewers' subscriptions and controls
(:mod:`~rocketsim.live.viewers`), whether the viewers have the last messages
(:mod:`~rocketsim.live.delivery`), the view's CPU against the flight's at max warp
(:mod:`~rocketsim.live.cpu_share`), and the flight's telemetry handed to the
file and a run in memory at once (:mod:`~rocketsim.live.tee`). Nothing below
the front door knows of them.
"""
