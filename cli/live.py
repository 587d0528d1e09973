"""The options of a live view in Foxglove (``--live --warp --port --host --paused``), shared
by ``rocketsim fly`` and ``rocketsim replay``."""

from __future__ import annotations

import functools

import click

from rocketsim.api import LOOPBACK, PORT, Live, parse_warp


class Warp(click.ParamType):
    """A warp: a positive number (``10``, ``10x``) or ``max``."""

    name = "warp"

    def convert(self, value, param, ctx):
        try:
            return parse_warp(value)
        except ValueError as error:
            self.fail(str(error), param, ctx)


def live_options(command):
    """Add the live view's options to a command, handed to it as ``live``: a :class:`Live`,
    or None without ``--live`` (the others given without it are a usage error, exit 2)."""

    @click.option("--live", "live", is_flag=True,
                  help="Serve the run to Foxglove as it flies (a Foxglove WebSocket server; "
                       'needs pip install "rocketsim[live]").')
    @click.option("--warp", type=Warp(), default="1", show_default=True,
                  help="With --live: times real time, e.g. 10 or 0.5, or max.")
    @click.option("--port", type=click.IntRange(0, 65535), default=PORT, show_default=True,
                  help="With --live: the server's port (0: any free one).")
    @click.option("--host", default=None,
                  help=f"With --live: the address to listen on (default {LOOPBACK}, this machine "
                       "only; another address lets other machines watch).")
    @click.option("--paused", is_flag=True,
                  help="With --live: start paused, until a viewer sets 'paused' to false or presses play.")
    @functools.wraps(command)
    def wrapper(*args, live: bool, warp: float | None, port: int, host: str | None, paused: bool, **kwargs):
        ctx = click.get_current_context()
        if not live:
            given = [f"--{name}" for name in ("warp", "port", "host", "paused")
                     if ctx.get_parameter_source(name) == click.core.ParameterSource.COMMANDLINE]
            if given:
                raise click.UsageError(f"{', '.join(given)} go with --live")
            return command(*args, live=None, **kwargs)
        return command(*args, live=Live(warp=warp, port=port, host=host or LOOPBACK, paused=paused), **kwargs)

    return wrapper
