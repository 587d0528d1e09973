"""The live view: a run's MCAP file served to Foxglove as it is written, at a warp.

The front door is :mod:`rocketsim.api.live` (``rocketsim fly --live``,
``rocketsim.fly(..., live=True)``); here are its parts: the file read as it
grows (:mod:`~rocketsim.live.growing`), the clock of the warp
(:mod:`~rocketsim.live.clock`), the Foxglove WebSocket server and its player
(:mod:`~rocketsim.live.server`), and the flight's telemetry paced on the view
(:mod:`~rocketsim.live.paced`). Nothing below the front door knows of them.
"""
