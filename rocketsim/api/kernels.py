"""Settings of the compiled kernels a process may change from the front door."""

from __future__ import annotations


def set_compiling_beside(on: bool) -> None:
    """Whether this process queues the kernels its flights need and the cache lacks for a
    second process to compile beside it (:class:`rocketsim.jit.beside.CompiledBeside`),
    whatever ``ROCKETSIM_COMPILE_BESIDE`` says (off unless set). Off where every core
    compiles already: the processes of a pool each flying a scenario to fill the cache."""
    from rocketsim.jit import beside

    beside.COMPILE_BESIDE = on
