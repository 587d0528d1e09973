"""What the viewers of a live view ask of it: their subscriptions and its controls.

A Foxglove app controls the view with the protocol's parameters, or with its
own play, pause and speed buttons through its playback control:

* ``warp``: the warp, a string (``"10"``, ``"10x"``, ``"max"``) or a number;
* ``paused``: true or false.

:class:`ViewerRequests` is the SDK's listener of a
:class:`~rocketsim.live.server.LiveServer`: it counts the viewers'
subscriptions and turns their requests into the server's controls;
:func:`parameters` and :func:`playback_state` are the controls' values as the
protocol carries them.
"""

from __future__ import annotations

import foxglove
from foxglove.websocket import PlaybackCommand, PlaybackState, PlaybackStatus, ServerListener

from rocketsim.live.clock import MAX, PlaybackClock, parse_warp, warp_text

WARP, PAUSED = "warp", "paused"


def parameters(clock: PlaybackClock) -> list:
    """The controls as the protocol's parameters: the warp as text, paused or not."""
    return [foxglove.Parameter(WARP, value=warp_text(clock.warp)), foxglove.Parameter(PAUSED, value=clock.paused)]


def playback_state(clock: PlaybackClock, request_id: str | None = None, ended: bool = False) -> PlaybackState:
    """The state of the playing for Foxglove's playback control (its speed: the warp,
    infinite at max)."""
    status = PlaybackStatus.Ended if ended else PlaybackStatus.Paused if clock.paused else PlaybackStatus.Playing
    warp = clock.warp
    return PlaybackState(status=status, current_time=clock.now() or 0,
                         playback_speed=float("inf") if warp is MAX else warp, did_seek=False,
                         request_id=request_id)


class ViewerRequests(ServerListener):
    """The server's callbacks: the viewers' subscriptions (counted in the server's
    ``subscriptions``) and controls (the server's ``set_warp``, ``pause``, ``resume``)."""

    def __init__(self, live):
        self._live = live

    def on_subscribe(self, client, channel) -> None:
        self._live.subscriptions += 1

    def on_unsubscribe(self, client, channel) -> None:
        self._live.subscriptions -= 1

    def on_get_parameters(self, client, param_names, request_id=None):
        return [p for p in parameters(self._live.clock) if not param_names or p.name in param_names]

    def on_set_parameters(self, client, parameters_set, request_id=None):
        for parameter in parameters_set:
            value = parameter.get_value()
            if parameter.name == WARP:
                try:
                    self._live.set_warp(parse_warp(value if isinstance(value, str) else float(value)))
                except (TypeError, ValueError) as error:
                    self._live.tell(str(error), foxglove.StatusLevel.Warning)
            elif parameter.name == PAUSED:
                self._live.pause() if value else self._live.resume()
        return parameters(self._live.clock)

    def on_playback_control_request(self, request):
        """Foxglove's play, pause and speed buttons (a seek is not done: a flight can only go
        on, and a replay plays on from where it is)."""
        live = self._live
        if 0 < request.playback_speed < float("inf") and request.playback_speed != live.clock.warp:
            live.set_warp(float(request.playback_speed))
        if request.playback_command == PlaybackCommand.Pause:
            live.pause()
        elif request.playback_command == PlaybackCommand.Play:
            live.resume()
        return playback_state(live.clock, request.request_id)
