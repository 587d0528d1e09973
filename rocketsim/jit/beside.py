"""Kernels compiled into the cache by a second process while a first flight on a cold cache
compiles others (:class:`CompiledBeside`): on two cores the two compile at once, since
numba compiles one function at a time per process, under its compiler lock.

Off unless switched on (``ROCKETSIM_COMPILE_BESIDE=1``, :mod:`rocketsim.jit.settings`,
or :data:`COMPILE_BESIDE` set in the process); the callers queue kernels
(:func:`compile_beside`) and ask whether one is being compiled elsewhere
(:func:`compiling_elsewhere`) whatever the switch says: off, nothing is queued and
nothing is elsewhere. tests/benchmarks/test_bench_compiled_beside.py measures what it
brings a cold first flight.
"""

from __future__ import annotations

import os
from pathlib import Path

from rocketsim.jit import numba_internals
from rocketsim.jit.cache import COMPILE_WAIT, cache_dir
from rocketsim.jit.entries import _kinds
from rocketsim.jit.settings import current

BESIDE_IDLE = 2.0           # s: the second process ends after this long with nothing left to compile
# Whether a cold cache's kernels are queued for a second process: None, as the settings say;
# True or False, this process's choice (off where every core compiles already: a campaign's
# workers)
COMPILE_BESIDE: bool | None = None


def _on() -> bool:
    return current().compile_beside if COMPILE_BESIDE is None else COMPILE_BESIDE


def _claim(folder: str, name: str) -> bool:
    """Take the queued item ``name`` of ``folder`` for this process (False: taken already)."""
    try:
        os.close(os.open(os.path.join(folder, "claim-" + name), os.O_CREAT | os.O_EXCL | os.O_WRONLY))
    except OSError:         # it exists, or the folder is gone (the queue has ended)
        return False
    return True


def _take_item(folder: str, name: str) -> tuple | None:
    """The queued item ``name`` (kernel's module, name, signature), taken for this process;
    None where another has it or it is gone. Read before it is claimed: once claimed, the
    process that queued it may end and remove the folder, and the item is still compiled."""
    import pickle

    if os.path.exists(os.path.join(folder, "claim-" + name)):
        return None
    try:
        with open(os.path.join(folder, name), "rb") as stream:
            item = pickle.load(stream)
    except Exception:       # noqa: BLE001 - gone, or not whole: not taken
        return None
    return item if _claim(folder, name) else None


def _compile_item(folder: str, name: str, item: tuple) -> None:
    """Compile the queued ``item`` (:func:`_take_item`) and mark it done, whatever the
    outcome: a kernel that fails here fails again, with its message, where it is called."""
    import importlib

    module, qualname, signature = item
    try:
        getattr(importlib.import_module(module), qualname).compile(signature)
    except Exception:       # noqa: BLE001 - see the docstring
        pass
    finally:
        try:
            open(os.path.join(folder, "done-" + name), "wb").close()
        except OSError:
            pass


def _queued_items(folder: str) -> list[str]:
    """The queue's items, in the order they are compiled (by priority, then as queued)."""
    try:
        return sorted(name for name in os.listdir(folder) if name.startswith("item-"))
    except OSError:
        return []


def compile_queued(folder: str) -> None:
    """The second process of :class:`CompiledBeside`: compile the queue's items in order, each
    it claims before the first process does, until the queue has had nothing new for
    :data:`BESIDE_IDLE` seconds or its folder is gone."""
    import time

    tried: set[str] = set()
    idle_since = time.monotonic()
    while os.path.isdir(folder):
        for name in _queued_items(folder):
            if name not in tried:
                tried.add(name)
                item = _take_item(folder, name)
                if item is not None:
                    _compile_item(folder, name, item)
                idle_since = time.monotonic()
                break
        else:
            if time.monotonic() - idle_since > BESIDE_IDLE:
                return
            time.sleep(0.01)


class CompiledBeside:
    """Kernels of known argument types compiled into the cache by a second Python process
    while this one compiles others: on a cold cache the two cores compile at once (numba
    compiles one function at a time per process, under its compiler lock).

    :meth:`add` queues a kernel for the numba types of some arguments unless the cache
    has it; the second process starts with the first item and takes the items in order
    of priority (then as queued). When this process needs a queued kernel
    (:meth:`rocketsim.jit.kernel.Kernel.entry`) it compiles it itself if the second process has not taken it,
    else waits for it there, meanwhile compiling the items not yet taken, and then loads it
    from the cache. The queue is a temporary folder: each item a file (the kernel's module,
    name and signature), taken by creating its ``claim-`` file (exclusive creation: one
    process wins), a ``done-`` file when compiled. The machine code is the same whichever
    process compiles it; a second process that fails or is slower than :data:`COMPILE_WAIT`
    costs the wait, and the kernel then compiles here as it would have. A kernel this process
    can fly without (a compiled run of many steps: one step at a time is the same flight) it
    does not wait for (:meth:`compiling_elsewhere`).
    """

    def __init__(self):
        self._folder: str | None = None
        self._process = None
        self._queued: dict[tuple, str] = {}    # (kernel, signature) -> its item's name, until needed here
        self._count = 0                         # items queued so far (their names' numbers)
        self._owner = None                      # the process that made the folder (not a forked child)
        self.kernels: set = set()               # the kernels of those items
        self._settled: set = set()              # (kernel, the arguments' kinds) found cached

    def add(self, kernel, args, priority: int = 0) -> bool:
        """Queue ``kernel`` for the numba types of ``args`` (lower ``priority`` first) unless
        it is cached, compiled here or queued; whether it was queued."""
        kinds = _kinds(args)
        if kinds is not None and (kernel, kinds) in self._settled:
            return False            # found cached by an earlier flight of this process
        signature = numba_internals.numba_types(kernel, args)
        if (kernel, signature) in self._queued:
            return False
        if numba_internals.cached(kernel, signature):
            if kinds is not None:
                self._settled.add((kernel, kinds))
            return False
        if self._folder is None:
            import atexit
            import tempfile
            self._folder = tempfile.mkdtemp(prefix="rocketsim-compiling-")
            self._owner = os.getpid()
            atexit.register(self.close)
        name = f"item-{priority:02d}-{self._count:04d}"
        self._count += 1
        part = os.path.join(self._folder, "part-" + name)     # written whole, then named
        with open(part, "wb") as stream:
            stream.write(numba_internals.serialized((kernel.__module__, kernel.__qualname__, signature)))
        os.replace(part, os.path.join(self._folder, name))
        self._queued[kernel, signature] = name
        self.kernels.add(kernel)
        self._start()
        return True

    def _start(self) -> None:
        """Start the second process unless it runs (it ends when idle)."""
        import subprocess
        import sys

        if self._process is not None and self._process.poll() is None:
            return
        package_parent = str(Path(__file__).resolve().parents[2])
        env = {**os.environ, "NUMBA_CACHE_DIR": cache_dir(),
               "PYTHONPATH": os.pathsep.join(filter(None, [package_parent, os.environ.get("PYTHONPATH")]))}
        try:
            self._process = subprocess.Popen(
                [sys.executable, "-c", "import sys; from rocketsim.jit.beside import compile_queued; "
                 "compile_queued(sys.argv[1])", self._folder], env=env,
                stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        except OSError:             # no process to spare: the kernels compile here
            self._process = None

    def _done(self, name: str) -> bool:
        return os.path.exists(os.path.join(self._folder, "done-" + name))

    def wait_for(self, kernel, signature: tuple) -> None:
        """Before this process compiles ``kernel`` for ``signature``: if it is queued and the
        second process has taken it, wait until it is compiled there (compiling the items
        not yet taken meanwhile), at most :data:`COMPILE_WAIT` s; else take it (compiled here)."""
        import time

        name = self._queued.pop((kernel, signature), None)
        if not any(queued is kernel for queued, _ in self._queued):
            self.kernels.discard(kernel)
        if name is None or self._done(name) or _claim(self._folder, name):
            return
        deadline = time.monotonic() + COMPILE_WAIT
        while not self._done(name) and time.monotonic() < deadline:
            if self._process is None or self._process.poll() is not None:
                return              # ended without it: compiled here
            if not self._compile_one():
                time.sleep(0.005)

    def compiling_elsewhere(self, kernel) -> bool:
        """Whether the second process has ``kernel`` to compile (an item of it queued, not yet
        done, the process running): a caller that can fly without it meanwhile (one step at a
        time, the same bits) does, instead of compiling it here or waiting for it."""
        if kernel not in self.kernels or self._process is None or self._process.poll() is not None:
            return False
        return any(queued is kernel and not self._done(name) for (queued, _), name in self._queued.items())

    def finish(self) -> None:
        """Have every queued kernel compiled into the cache (here those the second process has
        not taken, waiting for those it has: :meth:`wait_for`), then end the queue (:meth:`close`)."""
        import subprocess

        for kernel, signature in list(self._queued):
            self.wait_for(kernel, signature)
            kernel.compile(signature)
        self.close()
        if self._process is not None:       # idle now: it ends once the folder is gone
            try:
                self._process.wait(BESIDE_IDLE)
            except subprocess.TimeoutExpired:
                pass

    def _compile_one(self) -> bool:
        """Compile here the first queued item not yet taken; whether there was one."""
        for name in _queued_items(self._folder):
            item = _take_item(self._folder, name)
            if item is not None:
                _compile_item(self._folder, name, item)
                return True
        return False

    def close(self) -> None:
        """End the queue (at this process's exit): the folder removed (by the process that made
        it, not by a child forked from it). The second process takes nothing more; the kernel it
        is compiling it finishes into the cache, after this process has ended if need be (a
        flight shorter than its runs' compiling leaves them compiled for the next), and ends."""
        import shutil

        if self._owner != os.getpid():
            return
        if self._folder is not None:
            shutil.rmtree(self._folder, ignore_errors=True)
            self._folder = None
        self._queued.clear()
        self.kernels.clear()


BESIDE = CompiledBeside()


def compile_beside(kernel, args, priority: int = 0) -> None:
    """On a cold cache, queue ``kernel`` for the types of ``args`` for the second process
    (:class:`CompiledBeside`; lower ``priority`` first) if compiling beside is on (see the
    module) and kernels are compiled."""
    if _on() and not kernel.python:
        BESIDE.add(kernel, args, priority)


def compiling_elsewhere(kernel) -> bool:
    """Whether the second process is compiling ``kernel`` now (:meth:`CompiledBeside.compiling_elsewhere`)."""
    return BESIDE.compiling_elsewhere(kernel)


def finish_beside() -> None:
    """Have every kernel queued for the second process compiled into the cache and end the
    queue (:meth:`CompiledBeside.finish`): after a flight flown to fill the cache, which may
    have ended before its runs were compiled beside, in a process that ends without its
    exit handlers (a pool's worker)."""
    BESIDE.finish()
