"""``rocketsim compile``: compile the flight kernels into the cache ahead of the first flight.

The kernels are compiled for the machine they run on the first time a flight
needs them and cached (:func:`rocketsim.jit.cache_dir`). This command pays that
once, with all cores: it flies each scenario to its end in a pool of processes
(the telemetry is thrown away), so every kernel those flights call is compiled
by one of the processes and saved in the cache, where the others, and every
later flight, load it. On two cores or more each flight has a second process
compiling its runs beside it (:mod:`rocketsim.jit.beside`, switched on here
whatever ``ROCKETSIM_COMPILE_BESIDE`` says), and waits at its end for what it
flew without: a flight per two processes. Flights side by side would share most
of their kernels and wait for each other's compiling of them (measured in
tests/benchmarks/test_bench_startup.py).
"""

from __future__ import annotations

import os
import sys
import time
from pathlib import Path

import click

from rocketsim.errors import InputError
from rocketsim_cli.errors import reports_input_errors


def _start_worker(beside: bool) -> None:
    from rocketsim.api import set_compiling_beside

    set_compiling_beside(beside)        # on: each flight with its second process; off: the pool's
                                        # processes are the cores' compilers already


def _signatures(folder: str) -> int:
    """Compiled signatures in the cache folder ``folder`` (numba's code files): what the workers
    and the processes compiling beside them have saved."""
    return sum(1 for _ in Path(folder).rglob("*.nbc"))


def _warm(path: str) -> tuple[str, int, float, str | None]:
    """Fly the scenario at ``path`` to its end, telemetry discarded: (path, kernels
    compiled in this process, seconds, error message or None)."""
    import tempfile

    from rocketsim.api import finish_compiling_beside as finish_beside, fly_to_file as fly, load
    from rocketsim_cli.compiling import Compiles

    start = time.perf_counter()
    compiles = Compiles()
    error = None
    with tempfile.TemporaryDirectory() as folder, compiles.listening():
        try:
            fly(load(Path(path)), Path(folder) / "warm.mcap")
            finish_beside()             # the runs a flight flew without, compiled beside
        except InputError as failure:
            error = f"error: {failure}"
        except Exception as failure:  # noqa: BLE001 - reported, the other scenarios go on
            error = f"error: {path}: {type(failure).__name__}: {failure}"
    return path, compiles.done, time.perf_counter() - start, error


def _count(n: int, noun: str) -> str:
    return f"{n} {noun}" + ("" if n == 1 else "es" if noun.endswith("s") else "s")


def _scenarios(given: tuple[Path, ...]) -> list[Path]:
    if given:
        return list(given)
    found = sorted(Path("scenarios").glob("*.yaml"))
    if not found:
        raise InputError("no scenarios given and none in ./scenarios: name the scenarios your "
                         "flights use, e.g. rocketsim compile scenarios/*.yaml")
    return found


@click.command("compile")
@click.argument("scenarios", nargs=-1, type=click.Path(dir_okay=False, exists=True, path_type=Path))
@click.option("-j", "--jobs", type=click.IntRange(min=1), default=None,
              help="Processes compiling at once [default: one per core].")
@reports_input_errors
def compile_kernels(scenarios: tuple[Path, ...], jobs: int | None) -> None:
    """Compile the kernels the SCENARIOS fly with into the cache, on all cores.

    Each scenario (default: every scenarios/*.yaml here) is flown to its end
    in a pool of processes (two per flight), its telemetry thrown away; the kernels compiled
    on the way are kept in the cache (ROCKETSIM_CACHE_DIR, default
    ~/.cache/rocketsim), so that later flights start at once. Run it once
    when building a CI image, a container or a campaign's workers.

    \b
    Example:
        rocketsim compile scenarios/*.yaml
        ROCKETSIM_CACHE_DIR=/shared/rocketsim rocketsim compile -j 8 scenarios/*.yaml
    """
    import multiprocessing

    from rocketsim.api import kernel_cache_dir as cache_dir, load

    paths = _scenarios(scenarios)
    for path in paths:                  # a bad file fails now, not after minutes of compiling
        load(path)
    jobs = jobs or os.cpu_count() or 1
    # a flight per two processes where the cores allow: its own and a second one compiling its
    # runs beside it (see the module)
    beside = jobs >= 2
    workers = min(len(paths), jobs // 2 if beside else 1)
    terminal = sys.stderr.isatty()
    context = multiprocessing.get_context("spawn")
    folder = cache_dir()
    before = _signatures(folder)
    start = time.perf_counter()
    failed = []

    def show(finished: int) -> None:
        if terminal:
            sys.stderr.write(f"\rcompiling flight kernels: {finished}/{len(paths)} scenarios flown, "
                             f"{_signatures(folder) - before} kernels compiled, "
                             f"{time.perf_counter() - start:.0f} s\x1b[K")
            sys.stderr.flush()

    with context.Pool(workers, initializer=_start_worker, initargs=(beside,)) as pool:
        pending = [pool.apply_async(_warm, (str(path),)) for path in paths]
        finished = 0
        show(0)
        while pending:
            pending[0].wait(0.25)
            for result in [r for r in pending if r.ready()]:
                pending.remove(result)
                finished += 1
                path, compiled, seconds, error = result.get()
                if error:
                    failed.append(error)
                if terminal:
                    if error:
                        sys.stderr.write(f"\r{error}\x1b[K\n")
                else:
                    click.echo(f"{path}: flown in {seconds:.1f} s, {_count(compiled, 'kernel')} compiled in its process"
                               + (f" ({error})" if error else ""), err=True)
            show(finished)
    if terminal:
        sys.stderr.write("\r\x1b[K")
    how = _count(workers, "process") + (f" and {workers} more compiling beside" if beside else "")
    click.echo(f"compiled {_count(_signatures(folder) - before, 'kernel')} for {_count(len(paths), 'scenario')} "
               f"in {time.perf_counter() - start:.1f} s with {how} into {folder}")
    if failed:
        sys.exit(2)
