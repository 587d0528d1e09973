"""The compiled kernels' cache on disk: its folder, named for a hash of the source, its
lock, and the markers by which processes sharing it compile each kernel once.

numba's cache checks only the source file of the function it compiled, not the
functions that function calls from other modules: after an edit to
``bodies/gravity.py`` a cached ``dynamics/derivative.py`` kernel would still run
the old gravity. So the cache lives in a folder named for a hash of the source of
every module that compiles a kernel and of every library module those import,
followed to closure, and of numba's version and the optimisation level
(``numba-<hash>`` below the settings' cache root,
:mod:`rocketsim.jit.settings`): a change to any module a kernel could read (its
functions or its module-level constants) starts a fresh cache, while an edit to
the pure-Python layers (the simulation loop, the flight computer, scenarios,
telemetry) keeps the compiled kernels.

Processes that compile into one folder at once (test workers, a cold campaign's
workers, the parallel ``rocketsim compile``) save each compiled signature under
the folder's ``.lock`` (:func:`locked`), and compile a kernel only when no other
living process is compiling it (a marker file per kernel and signature below
``.compiling``: :func:`take`); how numba's cache is made to do both is in
:mod:`rocketsim.jit.numba_internals`.
"""

from __future__ import annotations

import hashlib
import os
import re
from contextlib import contextmanager
from pathlib import Path

from rocketsim.jit.settings import current

COMPILE_WAIT = 120.0        # s: the longest a process waits for another's compiling of a kernel

# "from rocketsim.a import b, c", a parenthesised list over several lines, or "import rocketsim.a"
_IMPORT = re.compile(r"^\s*(?:from\s+(rocketsim(?:\.\w+)*)\s+import\s+(\([^)]*\)|[\w ,]+)"
                     r"|import\s+(rocketsim(?:\.\w+)*))", re.M)


def kernel_sources(package: Path) -> list[Path]:
    """The modules that compile kernels and every library module they import, transitively."""
    paths = {}
    for path in package.rglob("*.py"):
        name = path.relative_to(package).with_suffix("").as_posix().replace("/", ".")
        paths[name.removesuffix("__init__").rstrip(".")] = path
    texts = {name: path.read_text() for name, path in paths.items()}

    def imported(text: str) -> set[str]:
        found = set()
        for match in _IMPORT.finditer(text):
            module = (match.group(1) or match.group(3)).removeprefix("rocketsim").lstrip(".")
            names = re.split(r"[\s,()]+", match.group(2) or "")
            found |= {candidate for candidate in [module] + [f"{module}.{n}".lstrip(".") for n in names if n]
                      if candidate in texts}
        return found

    todo = [name for name, text in texts.items() if "njit" in text]
    closure = set(todo)
    while todo:
        for name in imported(texts[todo.pop()]) - closure:
            closure.add(name)
            todo.append(name)
    return sorted(paths[name] for name in closure)


def source_hash() -> str:
    """The hash naming this source's cache folder (see the module)."""
    from importlib.metadata import version
    digest = hashlib.sha256(f"{version('numba')} opt {current().opt_level}".encode())
    package = Path(__file__).resolve().parents[1]
    for path in kernel_sources(package):
        digest.update(path.relative_to(package).as_posix().encode())
        digest.update(path.read_bytes())
    return digest.hexdigest()[:16]


def cache_dir() -> str:
    """The folder of this source's compiled kernels: ``$NUMBA_CACHE_DIR`` if set, else
    ``numba-<hash>`` below the cache root (default ``~/.cache/rocketsim``)."""
    settings = current()
    if settings.numba_cache_dir:
        return settings.numba_cache_dir
    return os.path.join(settings.cache_root, f"numba-{source_hash()}")


@contextmanager
def locked(folder: str):
    """Hold an exclusive lock on ``folder``'s ``.lock`` file (POSIX ``flock``; no lock where
    there is none, as on Windows) while the block runs, the folder made if need be."""
    try:
        import fcntl
    except ImportError:
        yield
        return
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, ".lock"), "a") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        try:
            yield
        finally:
            fcntl.flock(lock, fcntl.LOCK_UN)


def marker(folder: str, what: str) -> str | None:
    """The marker file of the compiling of ``what`` (a kernel, its argument types and the
    machine code's target) below ``folder``'s ``.compiling``, that folder made; None where it
    cannot be."""
    below = os.path.join(folder, ".compiling")
    try:
        os.makedirs(below, exist_ok=True)
    except OSError:
        return None
    return os.path.join(below, hashlib.sha256(what.encode()).hexdigest()[:32])


def take(path: str) -> bool:
    """Create the marker ``path`` for this process, first waiting while another living
    process holds it (at most :data:`COMPILE_WAIT` s); False (compile without it) when it
    cannot be made or the wait ran out. A marker whose process has ended is taken over."""
    import socket
    import time

    me = f"{socket.gethostname()} {os.getpid()}".encode()
    deadline = time.monotonic() + COMPILE_WAIT
    while True:
        try:
            handle = os.open(path, os.O_CREAT | os.O_EXCL | os.O_WRONLY)
        except FileExistsError:
            pass
        except OSError:
            return False
        else:
            os.write(handle, me)
            os.close(handle)
            return True
        if time.monotonic() > deadline:
            return False
        if not held(path, me.split()[0].decode()):
            try:
                os.remove(path)         # its process ended: taken over
            except OSError:
                pass
            continue
        time.sleep(0.005)


def held(path: str, host: str) -> bool:
    """Whether the marker ``path``'s process may still be compiling: a living process of
    ``host``, one of another host (which cannot be asked), or a marker being written."""
    try:
        with open(path, "rb") as stream:
            owner = stream.read().split()
    except FileNotFoundError:
        return False
    except OSError:
        return True
    if len(owner) != 2 or owner[0].decode(errors="replace") != host:
        return True
    try:
        os.kill(int(owner[1]), 0)
    except ProcessLookupError:
        return False
    except (OSError, ValueError):
        return True
    return True


def release(path: str) -> None:
    """Remove this process's marker ``path`` (its compiled signature saved)."""
    try:
        os.remove(path)
    except OSError:
        pass
